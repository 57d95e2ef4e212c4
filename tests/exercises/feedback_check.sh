#!/bin/sh
# ctest exercises.NN.feedback.<exercise>.<id> (tests/exercises/plant.cmake, soa_feedback_test):
# when a level 3 exercise names its mistake. With the planted mistake <plant> on, as
# `make exercises` runs it (SOA_EXERCISE_CASES=<scratch>/cases, hints in <scratch>/hints):
#   - runs 1 to N, N the failed runs its statement gives ("after N failed runs"), do not
#     name the mistake and say which failed run they are; run N+1 names it (<named regex>);
#   - with a fresh count, a run after every hint but the last of `make exercises
#     HINT=<exercise>` does not name it; a run after the last hint does.
#   feedback_check.sh <binary> <source dir> <scratch> <exercise> <plant> <gtest filter> <named regex>
set -eu
bin=$1
root=$2
scratch=$3
ex=$4
plant=$5
filter=$6
named=$7
cd "$root"
fail=0
say() { echo "FAIL: $*"; fail=1; }
nn=$(printf '%02d' "${ex%%.*}")
hpp=$(ls exercises/$nn-*/exercises.hpp)
# The statement's count: "after N failed runs", in the exercise's statement.
n=$(awk -v ex="$ex" '/\*\*Exercise /{on = index($0, "**Exercise " ex ":") || index($0, "**Exercise " ex " ")} on' "$hpp" |
    sed -n 's/.*after \([0-9][0-9]*\) failed runs.*/\1/p' | head -1)
[ -n "$n" ] || { echo "FAIL: the statement of $ex in $hpp gives no 'after N failed runs'"; exit 1; }
run() {
  SOA_PLANT=$plant SOA_EXERCISE_CASES=$scratch/cases ASAN_OPTIONS=detect_leaks=0 \
    "$bin" --report --gtest_filter="$filter"
}
rm -rf "$scratch"
mkdir -p "$scratch/cases"
i=1
while [ "$i" -le "$n" ]; do
  out=$(run)
  if printf '%s\n' "$out" | grep -Eq "$named"; then say "failed run $i of $ex names the mistake"; fi
  printf '%s\n' "$out" | grep -q "this is failed run $i)" ||
    say "failed run $i of $ex does not say 'this is failed run $i'"
  i=$((i + 1))
done
# expect_named WHAT: this run's report names the mistake (WHAT says which run it is).
expect_named() {
  out=$(run)
  if printf '%s\n' "$out" | grep -Eq "$named"; then
    echo "$1 names the mistake:"
    printf '%s\n' "$out" | grep -E "$named" | head -3
  else
    say "$1 does not name the mistake:"
    printf '%s\n' "$out" | head -20
  fi
}
expect_named "failed run $i of $ex (after $n)"
# The hint ladder, from a fresh count.
rm -rf "$scratch"
mkdir -p "$scratch/cases"
total=$(awk -v ex="$ex" '/^## /{on = ($2 "" == ex "")} on' exercises/$nn-*/hints.md | grep -c '^[0-9][0-9]*\. ' || true)
[ "$total" -ge 1 ] || { echo "FAIL: $ex has no hints"; exit 1; }
h=1
while [ "$h" -lt "$total" ]; do
  sh tests/exercises/hint.sh "$ex" "$scratch/hints" >/dev/null
  h=$((h + 1))
done
out=$(run)
if printf '%s\n' "$out" | grep -Eq "$named"; then
  say "$ex names the mistake after $((total - 1)) of its $total hints"
fi
last=$(sh tests/exercises/hint.sh "$ex" "$scratch/hints")
printf '%s\n' "$last" | grep -q "(hint $total of $total" ||
  say "HINT=$ex does not reach hint $total of $total: $last"
expect_named "after all $total hints of $ex, its first failed run"
[ $fail = 0 ] && echo "$ex: named after $n failed runs, or after the $total hints"
exit $fail
