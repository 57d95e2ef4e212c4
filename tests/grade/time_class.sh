#!/bin/sh
# The time make grade takes a submission: a scripted measurement, not a test. Makes a class of
# <count> copies of the reference solutions (of LESSONS, all by default) in <scratch>/subs and
# grades it into <scratch>/out with tests/grade/grade.sh, in an exercise tree of its own
# (<scratch>/out/.work/tree, compiled once and kept for the next measurement) or TREE=.
# grade.sh's last line gives the time of the library and the checkers, the time of the
# class and the time a submission; this script adds the machine.
#   [UNSAFE=1] [LESSONS=1,2] [JOBS=N] [TREE=DIR] time_class.sh <source dir> <scratch> <count>
set -eu
src=$(cd "$1" && pwd)
scratch=$2
count=$3
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$scratch/subs"
mkdir -p "$scratch/subs"
k=1
while [ "$k" -le "$count" ]; do
  for d in "$src"/solutions/[0-9][0-9]-*/; do
    l=$(basename "$d")
    mkdir -p "$scratch/subs/student$k/exercises/$l"
    cp "$d"*.cpp "$scratch/subs/student$k/exercises/$l/exercises.cpp"
  done
  k=$((k + 1))
done
echo "time_class: $count submissions of the solutions, lessons ${LESSONS:-all}, JOBS=${JOBS:-2}," \
  "$(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //'), load $(cut -d' ' -f1-3 /proc/loadavg)"
sh "$here/grade.sh" "$src" "$scratch/subs" "$scratch/out" 2>&1 | grep -v '^grade: [0-9]* of '
echo "time_class: the totals (how many students, total): $(sed 1d "$scratch/out/gradebook.csv" |
  sed 's/.*,//' | sort | uniq -c | tr -s ' \n' ' ')"
