#!/bin/sh
# The recorders or the replayers of a lesson's functions, for make grade's two runs of a
# lesson (tests/support/recording.hpp says why):
#   record  each function of exercises.hpp defined as a recorder of the student's, which
#           watch.cmake renames soa_student_<name> in the student's code;
#   replay  each function defined as a replayer of the recorded answers: no student code.
# The lesson's structs get their layout in the record (their members, in order).
#   recording.sh <record|replay> <exercises.hpp> <output .cpp>
set -eu
mode=$1
header=$2
out=$3
here=$(cd "$(dirname "$0")" && pwd)
case "$mode" in record | replay) ;; *) echo "recording.sh: mode record or replay, not $mode" >&2; exit 1 ;; esac
ns=$(grep -m1 -oE '^namespace soa::ex[0-9]+' "$header" | sed 's/.*:://')
[ -n "$ns" ] || { echo "recording.sh: $header: no namespace soa::exNN" >&2; exit 1; }
awk -f "$here/statements.awk" "$header" >"$out.statements"
awk -F '\t' -v mode="$mode" -v ns="$ns" -v header="$header" -f "$here/recording.awk" \
  "$header" "$out.statements" >"$out.tmp"
rm -f "$out.statements"
mv "$out.tmp" "$out"
