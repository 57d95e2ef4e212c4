#!/bin/sh
# make run: the lesson tour, lesson by lesson. Lesson 1 and the core library are built first
# and lesson 1 runs; then one build of everything else the tour runs goes on in the
# background, and each lesson runs as soon as its program is built (ninja's log says so).
# The labs run last, alone: the simulation and timing labs measure run time.
#   sh lessons/tour.sh BUILD_DIR JOBS
# BUILD_DIR/tour.txt (lessons/CMakeLists.txt) lists the programs; lessons/tour.cmake runs one
# and prints its line. The build's output is kept in BUILD_DIR/tour-build.log.
build=$1
jobs=$2
here=$(cd "$(dirname "$0")" && pwd)
list=$build/tour.txt
log=$build/tour-build.log
if [ ! -f "$list" ]; then
  echo "make run: $list is missing (the build folder was not configured)" >&2
  exit 1
fi
out=$(sed -n 's/^out|//p' "$list")
chromium=$(sed -n 's/^chromium|//p' "$list")
failed=0

# run_entry <kind> <name> <program>: tour.cmake runs it and prints its line.
run_entry() {
  cmake "-DENTRY=$1|$2|$3" "-DOUT=$out" "-DCHROMIUM=$chromium" -P "$here/tour.cmake" \
    || failed=1
}

# build_failed <what>: the build's last lines, and the tour stops.
build_failed() {
  echo "make run: $1 does not build; the end of $log:" >&2
  grep -E 'error|FAILED' "$log" | head -20 >&2
  exit 1
}

first=$(grep -m1 '^lesson|' "$list")
first_target=$(echo "$first" | cut -d'|' -f3)
echo
if [ ! -x "$(echo "$first" | cut -d'|' -f4)" ]; then
  echo "Building the library and lesson 1 (a few minutes the first time; the build's output: $log)"
fi
cmake --build "$build" -j "$jobs" --target "$first_target" >"$log" 2>&1 \
  || build_failed "lesson 1"
echo
run_entry lesson "$(echo "$first" | cut -d'|' -f2)" "$(echo "$first" | cut -d'|' -f4)"

# The rest in one background build. A program is ready when ninja's log has its line (ninja
# appends one as each step ends, with the output's time, after this start), or, for one that
# was up to date, when the build has ended.
rest=$(grep -v "^lesson|$(echo "$first" | cut -d'|' -f2)|" "$list" | grep -E '^(lesson|lab)\|')
targets=$(echo "$rest" | cut -d'|' -f3 | tr '\n' ' ')
root=$(cd "$build" && pwd)
since=$(date +%s%N)
cmake --build "$build" -j "$jobs" --target $targets >>"$log" 2>&1 &
builder=$!

# linked <path relative to the build>: ninja's log has it, written after the start.
linked() {
  awk -F'\t' -v p="$1" -v t="$since" '$4 == p && $3 + 0 >= t + 0 { f = 1 } END { exit !f }' \
    "$build/.ninja_log"
}

# wait_for <program>: returns when it is built (0) or the build ended without it (1).
wait_for() {
  rel=${1#"$root"/}
  until linked "$rel"; do
    if ! kill -0 "$builder" 2>/dev/null; then
      [ -x "$1" ]
      return
    fi
    sleep 1
  done
}

while IFS='|' read -r kind name target program; do
  if wait_for "$program"; then
    run_entry "$kind" "$name" "$program"
  else
    echo "Lesson ${name%%-*}: not built (see $log)"
  fi
done <<EOF
$(echo "$rest" | grep '^lesson|')
EOF
wait "$builder" || build_failed "the tour"
while IFS='|' read -r kind name target program; do
  run_entry "$kind" "$name" "$program"
done <<EOF
$(echo "$rest" | grep '^lab|')
EOF
echo
if [ "$failed" != 0 ]; then
  echo "make run: a lesson or lab failed its checks; see its output.txt" >&2
  exit 1
fi
