#!/bin/sh
# The compiler launcher of the student's code (exercises/CMakeLists.txt): runs the compile
# "$@" as it is, and keeps what the compiler said in <object>.diag, so that make exercises
# shows the warnings in the exercise's row on every run, not only on the run that compiled.
#   keep_diagnostics.sh [--quiet] <compiler> <args...>
# --quiet keeps the warnings of a compile that succeeds only in the file (the probes of
# make test, whose warnings are wanted).
quiet=0
if [ "$1" = "--quiet" ]; then
  quiet=1
  shift
fi
obj=""
prev=""
for a in "$@"; do
  [ "$prev" = "-o" ] && obj=$a
  prev=$a
done
[ -n "$obj" ] || exec "$@"
"$@" 2>"$obj.diag.new"
rc=$?
if [ $quiet = 0 ] || [ $rc != 0 ]; then cat "$obj.diag.new" >&2; fi
mv -f "$obj.diag.new" "$obj.diag"
exit $rc
