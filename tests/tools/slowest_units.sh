#!/bin/sh
# The slowest compile units of a build, from ninja's log: each object file's wall time in the
# last build that made it (ninja records start and end, in ms, per output; a target built
# again has a later line, which wins).
#   tests/tools/slowest_units.sh [BUILD_DIR] [COUNT]     (defaults: build/release, 15)
# Wall times overlap under -j: their sum is CPU time only at -j 1.
dir=${1:-build/release}
count=${2:-15}
log=$dir/.ninja_log
if [ ! -f "$log" ]; then
  echo "slowest_units: $log: no ninja log (build first: make build)" >&2
  exit 1
fi
awk -v count="$count" '
  /^#/ { next }
  $4 ~ /\.o$/ { t[$4] = ($2 - $1) / 1000 }
  END {
    n = 0; total = 0
    for (k in t) { n++; total += t[k] }
    printf "%d compile units, %.0f s of compile time in all\n", n, total
    for (k in t) printf "%9.1f s  %s\n", t[k], k | "sort -rn | head -n " count
  }' "$log"
