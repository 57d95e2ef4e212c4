#!/bin/sh
# The files an exercise's statement determines: its stub, its row of the lesson's README table
# and the checksums of the pristine stubs (tests/exercises/stubs.sha256, stubs.cmake).
#   stubs.sh write <source dir>  make stubs: writes the stub of each statement of
#                                exercises/NN-topic/exercises.hpp that has none into
#                                exercises.cpp (a body that throws exercise::NotDone("N.K
#                                name")), the README tables, then the checksums
#   stubs.sh check <source dir>  ctest exercises.stubs: fails when a statement has no stub
#                                or a README table is not the statements'; a lesson whose
#                                stubs all still throw NotDone but differ from the checksums
#                                (make stubs not run, or a student's first edits) is named
#                                and the test skipped: its stub checks are skipped too
# The statements are read by tests/exercises/statements.awk. A README's table is the part
# between the lines BEGIN and END below; everything else of the README is written by hand.
set -eu
mode=$1
root=$(cd "$2" && pwd)
cd "$root"
BEGIN='<!-- exercises: written by `make stubs` from exercises.hpp -->'
END='<!-- end of exercises -->'
fail=0
stale=""
say() { echo "$*"; fail=1; }

# table <statements>: the README table of a lesson.
table() {
  echo '| # | level, time | function | exercise | must not call |'
  echo '|---|---|---|---|---|'
  awk -F'\t' '{
    args = $6; gsub(/\(void\)/, "", args); sub(/;$/, "", args)
    t = $4
    gsub(/\\f\$/, "`", t); gsub(/\\mathcal /, "", t); gsub(/\\tilde\\phi/, "φ̃", t)
    gsub(/\\phi/, "φ", t); gsub(/\\psi/, "ψ", t); gsub(/\\bar\\tau/, "τ̄", t)
    gsub(/\\Omega/, "Ω", t); gsub(/\\Upsilon/, "Υ", t); gsub(/\^\{-1\}/, "⁻¹", t)
    gsub(/\^\*/, "*", t); gsub(/\^\+/, "⁺", t); gsub(/\\/, "", t)
    f = $5; gsub(/soa::[A-Za-z0-9_:]*/, "`&`", f)
    print "| " $1 " | " $3 " | `" $2 "(" args ")` | " t " | " f " |"
  }' "$1"
}

# stub <statement line>: the stub of one statement.
stub() {
  printf '%s\n' "$1" | awk -F'\t' '{
    n = split($7, d, "\001")
    for (i = 1; i < n; i++) print d[i]
    print d[n] " {"
    if ($6 != "") print "  " $6
    print "  throw exercise::NotDone(\"" $1 " " $2 "\");"
    print "}"
  }'
}

scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
for dir in exercises/[0-9][0-9]-*/; do
  dir=${dir%/}
  hpp=$dir/exercises.hpp
  cpp=$dir/exercises.cpp
  st=$scratch/statements
  awk -f tests/exercises/statements.awk "$hpp" >"$st"
  shipped=1
  while IFS=$(printf '\t') read -r id name rest; do
    if grep -q "NotDone(\"$id " "$cpp"; then continue; fi
    shipped=0
    grep -qE "(^|[^A-Za-z0-9_.:>])$name\(" "$cpp" && continue
    if [ "$mode" = check ]; then
      say "$cpp: no stub for exercise $id, $name (make stubs writes it)"
      continue
    fi
    # Before the namespace's closing line.
    grep "^$id	" "$st" >"$scratch/line"
    stub "$(cat "$scratch/line")" >"$scratch/stub"
    awk -v stub="$scratch/stub" '/^}  \/\/ namespace/ && !done {
        while ((getline l < stub) > 0) print l; print ""; done = 1 } { print }' \
      "$cpp" >"$scratch/cpp"
    cp "$scratch/cpp" "$cpp"
    if command -v clang-format >/dev/null; then clang-format -i "$cpp"; fi
    echo "wrote the stub of $id ($name) into $cpp"
    shipped=1
  done <"$st"
  echo "$shipped" >"$scratch/shipped-$(basename "$dir")"
  readme=$dir/README.md
  table "$st" >"$scratch/table"
  if ! grep -qxF "$BEGIN" "$readme" || ! grep -qxF "$END" "$readme"; then
    say "$readme: no table of the exercises (the lines $BEGIN and $END)"
    continue
  fi
  awk -v b="$BEGIN" -v e="$END" -v t="$scratch/table" '
    $0 == b { print; while ((getline l < t) > 0) print l; skip = 1; next }
    $0 == e { skip = 0 } !skip' "$readme" >"$scratch/readme"
  if ! cmp -s "$scratch/readme" "$readme"; then
    if [ "$mode" = check ]; then
      say "$readme: its table of the exercises is not that of the statements (make stubs writes it)"
    else
      cp "$scratch/readme" "$readme"
      echo "wrote the table of $readme"
    fi
  fi
done
if [ "$mode" = write ]; then
  cmake -DROOT="$root" -DWRITE=ON -P tests/exercises/stubs.cmake
  exit 0
fi
cmake -DROOT="$root" -P tests/exercises/stubs.cmake | sed -n 's/^-- //p' >"$scratch/status"
for dir in exercises/[0-9][0-9]-*/; do
  name=$(basename "$dir")
  [ "$(cat "$scratch/shipped-$name")" = 1 ] || continue
  state=$(grep "^$name: " "$scratch/status" || true)
  case "$state" in
    *": pristine") ;;
    *) stale="$stale exercises/$name" ;;
  esac
done
[ $fail = 0 ] || exit 1
echo "every statement has its stub and its README row"
if [ -n "$stale" ]; then
  echo "skipped:$stale: every stub still throws NotDone but differs from its checksum (a" \
    "student's first edits, or a changed stub without make stubs): the stub checks of these" \
    "lessons are skipped"
fi
exit 0
