#!/bin/sh
# make release OUT=DIR: the student's repository, without the answers (the notes' page
# "Instructors", docs/instructors.md). From the files of the source's last commit (git
# ls-files of HEAD: nothing uncommitted or untracked), it leaves out the paths of
# tests/release/instructor_only.txt, cuts the blocks of planted mistakes out of the checkers
# tests/exercises/NN-topic.cpp (their FIND texts are pieces of the solutions), edits the
# sentences about the solutions (student_text.sh), and commits the result in a new git
# repository. It is written into OUT.tmp-XXXXXX and renamed to OUT at the end: a release that
# stops half-way leaves nothing behind.
#   release.sh <source dir> <out dir>
set -eu
src=${1:-}
out=${2:-}
here=$(cd "$(dirname "$0")" && pwd)
[ -n "$src" ] || { echo "release.sh: usage: release.sh <source dir> <out dir>"; exit 2; }
[ -n "$out" ] || { echo "make release: OUT=DIR is missing: the new or empty folder to write the student's repository into"; exit 2; }
while [ "${out%/}" != "$out" ] && [ "${out%/}" != "" ]; do out=${out%/}; done
if [ -e "$out" ] && { [ ! -d "$out" ] || [ -n "$(ls -A "$out")" ]; }; then
  echo "make release: $out exists and is not an empty folder"
  exit 1
fi
command -v git >/dev/null 2>&1 || { echo "make release: git is needed (the release is the files of HEAD)"; exit 1; }
commit=$(git -C "$src" rev-parse --verify -q HEAD) ||
  { echo "make release: $src is not a git repository with a commit"; exit 1; }

parent=$(dirname "$out")
mkdir -p "$parent"
tmp=$(mktemp -d "$out.tmp-XXXXXX")
trap 'rm -rf "$tmp"' EXIT
trap 'exit 1' HUP INT TERM

# The tracked files of HEAD (git archive writes exactly those).
git -C "$src" archive --format=tar HEAD | tar -xf - -C "$tmp"

# The instructor's paths.
list=$here/instructor_only.txt
sed -e 's/#.*//' -e 's/[[:space:]].*//' -e '/^$/d' "$list" | while read -r path; do
  [ -e "$tmp/$path" ] || { echo "make release: $list: $path is not in $commit (stale entry?)"; exit 1; }
  rm -rf "${tmp:?}/$path"
done

# The blocks of planted mistakes, each with the "// clang-format off" line before it and the
# "// clang-format on" line after it; the checker is left compiling (they are comments).
for f in "$tmp"/tests/exercises/[0-9][0-9]-*.cpp; do
  [ -f "$f" ] || continue
  name=tests/exercises/$(basename "$f")
  awk -v name="$name" '
    function flush() { if (held != "") { print held; held = "" } }
    inblock { if ($0 == "*/") { inblock = 0; after = 1 } next }
    after { after = 0; if ($0 == "// clang-format on") next }
    /^\/\* planted mistakes of / { held = ""; inblock = 1; start = NR; next }
    $0 == "// clang-format off" { flush(); held = $0; next }
    { flush(); print }
    END {
      if (inblock) { print name ":" start ": a block of planted mistakes has no closing */ line" > "/dev/stderr"; exit 1 }
      flush()
    }' "$f" >"$f.new" || { echo "make release: $name: could not cut its planted mistakes"; exit 1; }
  mv "$f.new" "$f"
done

# The sentences about the solutions, for a student.
sh "$here/student_text.sh" "$tmp"

# One commit, by the instructor when git knows who that is.
name=$(git -C "$src" config user.name || echo "SOA course")
email=$(git -C "$src" config user.email || echo "course@example.org")
git -C "$tmp" init -q
git -C "$tmp" add -A
git -C "$tmp" -c user.name="$name" -c user.email="$email" commit -q -m "Student release of $commit"
rmdir "$out" 2>/dev/null || true
mv "$tmp" "$out"
trap - EXIT
echo "make release: the student's repository of $(git -C "$src" rev-parse --short HEAD) is in $out"
if [ -n "$(git -C "$src" status --porcelain --untracked-files=no)" ]; then
  echo "  (the last commit only: the source has uncommitted changes, not in the release)"
fi
