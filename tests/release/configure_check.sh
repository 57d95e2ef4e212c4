#!/bin/sh
# ctest release.configure: a student release (tests/release/release.sh; ctest's
# release.make writes it) configures with CMake, with no solutions/ (no build: seconds), and its
# make test would run the library's tests, the lessons' and, for every lesson, the check
# that each exercise fails on its stub (exercises.NN.stubs-fail, on the checkers that
# exercises.student-config builds from the stubs alone), and nothing that needs the solutions.
#   configure_check.sh <release dir> <scratch dir> <CMake generator> <C++ compiler>
set -eu
rel=$1
scratch=$2
generator=$3
cxx=$4
rm -rf "$scratch"
mkdir -p "$scratch"
build=$scratch/build
cmake -S "$rel" -B "$build" -G "$generator" -DCMAKE_CXX_COMPILER="$cxx" \
  -DCMAKE_BUILD_TYPE=Release >"$scratch/configure.log" 2>&1 ||
  { cat "$scratch/configure.log"; echo "FAIL: the release does not configure ($scratch/configure.log)"; exit 1; }
# The tests: a name a line. The library's test programs are found when they run (GoogleTest's
# PRE_TEST discovery): before a build they are listed as <program>_NOT_BUILT.
(cd "$build" && ctest -N 2>/dev/null) | sed -n 's/^ *Test *#[0-9]*: //p' | sort -u >"$scratch/tests"
fail=0
has() {
  grep -Eq "$1" "$scratch/tests" || { echo "FAIL: the release has no test $2"; fail=1; }
}
has '_test_NOT_BUILT$' "of the library (a GoogleTest program <name>_test)"
for d in "$rel"/lessons/[0-9][0-9]-*/; do
  lesson=$(basename "$d")
  has "^lesson\.$lesson\$" "lesson.$lesson"
done
for f in "$rel"/tests/exercises/[0-9][0-9]-*.cpp; do
  nn=$(basename "$f" | cut -c1-2)
  has "^exercises\.$nn\.stubs-fail\$" "exercises.$nn.stubs-fail"
done
# The stubs' checkers are built by make exercises' recipe, on the stubs alone here.
has '^exercises\.student-config$' "exercises.student-config (the exercise configuration on the stubs)"
if ! grep -q '"-DPLANTED="' "$build/tests/CTestTestfile.cmake"; then
  echo "FAIL: the release's exercises.student-config is given planted solutions"
  fail=1
fi
answers='^exercises\.([0-9]+\.(solutions|planted|feedback)|committed-work|watch-probe)'
if grep -Eq "$answers" "$scratch/tests"; then
  echo "FAIL: the release has tests that need the solutions:"
  grep -E "$answers" "$scratch/tests" | head -5
  fail=1
fi
targets='(solutions_[0-9][0-9]|ex[0-9][0-9]-solutions)'
if grep -Eq "$targets" "$build/build.ninja" 2>/dev/null; then
  echo "FAIL: the release's build has targets of the solutions:"
  grep -Eo "[^ ]*$targets[^ ]*" "$build/build.ninja" | sort -u | head -5
  fail=1
fi
[ $fail = 0 ] && echo "the release configures: $(wc -l <"$scratch/tests") tests," \
  "the library's, the lessons' and every exercises.NN.stubs-fail, none needing the solutions"
exit $fail
