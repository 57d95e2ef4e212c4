#!/bin/sh
# ctest release.no_answers: a student release (tests/release/release.sh; ctest's
# release.make writes it) holds no answer. It fails, naming the place, when the release has
#   - a line distinctive to a solution: a line of solutions/NN-topic/*.cpp, blanks folded, of
#     at least 20 characters, that no other tracked file of the source has (the paths the
#     release leaves out and the checkers' blocks of planted mistakes not counted: they carry
#     pieces of the solutions too);
#   - solutions/, or any other path of tests/release/instructor_only.txt;
#   - a block of planted mistakes ("/* planted mistakes of N.K").
# The source is its last commit, as the release takes it.
#   no_answers.sh <source dir> <release dir> <scratch dir>
set -eu
src=$1
rel=$(cd "$2" && pwd)
scratch=$3
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$scratch"
mkdir -p "$scratch/head"
git -C "$src" archive --format=tar HEAD | tar -xf - -C "$scratch/head"

fail=0
# The instructor's paths, gone.
sed -e 's/#.*//' -e 's/[[:space:]].*//' -e '/^$/d' "$here/instructor_only.txt" >"$scratch/paths"
while read -r path; do
  if [ -e "$rel/$path" ]; then
    echo "FAIL: the release has $path (tests/release/instructor_only.txt leaves it out)"
    fail=1
  fi
done <"$scratch/paths"

# The files: the solutions, every other tracked file of the source, every file of the release.
(cd "$scratch/head" && find solutions -type f -name '*.cpp' | sort) >"$scratch/solutions"
[ -s "$scratch/solutions" ] || { echo "FAIL: no solutions/*/*.cpp in $src: nothing to look for"; exit 1; }
(cd "$scratch/head" && find . -type f | sort) |
  awk 'NR == FNR { left[$0] = 1; next }
       { for (p = $0; p != "."; sub(/\/[^\/]*$/, "", p)) if (substr(p, 3) in left || substr(p, 3) "/" in left) next; print }' \
    "$scratch/paths" - >"$scratch/others"
(cd "$rel" && find . -path ./.git -prune -o -type f -print | sort) >"$scratch/released"

# One awk over the three lists: phase 1 collects the solutions' lines, phase 2 drops those any
# other file has, phase 3 reports each one found in the release. Blanks are folded and the
# ends trimmed; a block of planted mistakes is skipped in phase 2 and reported in phase 3.
{
  echo "phase=1"
  sed 's|^|head/|' "$scratch/solutions"
  echo "phase=2"
  sed 's|^\./|head/|' "$scratch/others"
  echo "phase=3"
  sed "s|^\\./|$rel/|" "$scratch/released"
} >"$scratch/operands"
cd "$scratch"
if grep -v '^phase=[123]$' operands | grep -q '[[:space:]=]'; then
  echo "FAIL: a path with a blank or '=' in it; this check cannot read it"
  exit 1
fi
set +e
awk '
  FNR == 1 { block = 0 }
  { line = $0; gsub(/[ \t\r]+/, " ", line); sub(/^ /, "", line); sub(/ $/, "", line) }
  phase == 1 && length(line) >= 20 && !(line in where) {
    where[line] = substr(FILENAME, 6) ":" FNR
  }
  phase == 2 {
    if (line ~ /^\/\* planted mistakes of /) block = 1
    if (!block) delete where[line]
    if (block && line == "*/") block = 0
  }
  phase == 3 {
    if (!counted) { for (l in where) n++; counted = 1
      if (n == 0) { print "FAIL: no line is distinctive to a solution: nothing to look for"; bad = 1 } }
    file = substr(FILENAME, length(rel) + 2)
    if (line ~ /^\/\* planted mistakes of /) {
      print "FAIL: " file ":" FNR ": a block of planted mistakes: " line; bad = 1
    } else if (line in where) {
      if (++leaks <= 20) print "FAIL: " file ":" FNR ": the line " where[line] " of the solutions: " line
      bad = 1
    }
  }
  END {
    if (leaks > 20) print "FAIL: and " leaks - 20 " more lines of the solutions"
    if (!bad) print "no answer in the release: " n " lines distinctive to the solutions, none found in its files"
    exit bad
  }' rel="$rel" $(cat operands)
rc=$?
set -e
[ $rc = 0 ] || fail=1
exit $fail
