#!/bin/sh
# ctest exercises.committed-work: a student's committed work must not break `make test`.
# A scratch copy of the project's files (as a fresh clone has them, uncommitted changes
# included) in a new git repository gets lesson 4 solved (the solutions copied in) and
# lesson 5 half-written (code that does not compile), both committed; configured like `make test`
# configures, it must skip the stub checks of lessons 4 and 5, still check the others (on the
# checker make test's exercise tree links against their stubs), and build neither lesson's
# exercise code by default.
#   committed_work.sh <source dir> <scratch dir>
set -eu
src=$1
scratch=$2
rm -rf "$scratch"
mkdir -p "$scratch/repo"
(cd "$src" && git ls-files -co --exclude-standard -z | xargs -0 tar cf -) | (cd "$scratch/repo" && tar xf -)
cd "$scratch/repo"
# Which lessons are pristine before the "student" writes (in a student's own repository,
# some may not be): those must stay checked.
pristine=$(cmake -DROOT="$PWD" -P tests/exercises/stubs.cmake 2>&1 |
           sed -n 's/^-- \([0-9][0-9]\)-[^:]*: pristine$/\1/p' | grep -v '^0[45]$' || true)
git init --quiet
git add -A
git -c user.name=course -c user.email=course@example.org commit --quiet -m "the course"
l4=$(ls -d exercises/04-*)
l5=$(ls -d exercises/05-*)
cp "solutions/${l4#exercises/}/solutions.cpp" "$l4/exercises.cpp"
printf '\nthis line is a student half-way through and does not compile\n' >>"$l5/exercises.cpp"
git -c user.name=student -c user.email=student@example.org commit --quiet -am "my exercises"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >"$scratch/configure.log" 2>&1 \
  || { cat "$scratch/configure.log"; exit 1; }
cd build
fail=0
for nn in 04 05; do
  out=$(ctest -R "^exercises\.$nn\.stubs-fail\$" 2>&1 || true)
  echo "$out" | grep -q "Skipped" || { echo "lesson $nn: stub check not skipped:"; echo "$out"; fail=1; }
  if ninja -t commands all | grep -q "exercises_$nn\.dir"; then
    echo "lesson $nn: the student's code is part of the default build"; fail=1
  fi
done
for nn in $pristine; do
  ctest -N | grep -q "exercises\.$nn\.stubs-fail" || { echo "lesson $nn: stub check missing"; fail=1; }
  grep "add_test(\[=\[exercises\.$nn\.stubs-fail\]=\]" tests/CTestTestfile.cmake |
    grep -q "stubs/ex$nn-exercises\" \"--expect-all-fail" ||
    { echo "lesson $nn: its stub check does not run the checker on the stubs"; fail=1; }
done
[ $fail = 0 ] && echo "committed work: lessons 04 and 05 skipped; pristine lessons still checked:" $pristine
exit $fail
