#!/bin/sh
# make exercises HINT=4.7: the next hint of exercise 4.7 (and the ones already shown).
# Hints live in exercises/NN-topic/hints.md, one section per exercise:
#   ## 4.7 <title>
#   Taught in: lesson 4, section 11 (the lesson's page and lessons/04-*/lesson.cpp)
#   1. first hint (may run over several lines)
#   2. ...
# How many a student has seen is kept in <state dir>/<exercise>; once it is all of them, the
# checker names the mistake of a level 3 exercise (tests/support/exercise_check.hpp).
# make exercises passes build/exercises/hints, beside the cases folder the checker is given.
#   hint.sh <exercise> <state dir>
set -eu
ex=$1
state=$2
case "$ex" in
  [0-9].[0-9]|[0-9].[0-9][0-9]) ;;
  *) echo "HINT=$ex: name an exercise as lesson.number, for example HINT=4.2"; exit 0 ;;
esac
nn=$(printf '%02d' "${ex%%.*}")
file=$(ls exercises/$nn-*/hints.md 2>/dev/null | head -1)
if [ -z "$file" ] || ! grep -q "^## $ex " "$file"; then
  echo "exercise $ex has no hints (exercises/$nn-*/hints.md); its statement is in exercises/$nn-*/exercises.hpp"
  exit 0
fi
# The exercise's section: from its heading to the next.
section=$(awk -v ex="$ex" '/^## /{on = ($2 "" == ex "")} on' "$file")
total=$(printf '%s\n' "$section" | grep -c '^[0-9][0-9]*\. ' || true)
mkdir -p "$state"
seen=$(cat "$state/$ex" 2>/dev/null || echo 0)
next=$((seen + 1))
[ "$next" -gt "$total" ] && next=$total
echo "$next" >"$state/$ex"
printf '%s\n' "$section" | awk -v upto="$next" '
  /^## / { print; next }
  /^[0-9]+\. / { n = $1 + 0 }
  n == 0 { print; next }
  n <= upto { print }'
echo
if [ "$seen" -ge "$total" ]; then
  # The solutions are the instructor's: a student release has none to point to.
  solution=solutions/$(basename "$(dirname "$file")")/solutions.cpp
  if [ -f "$solution" ]; then
    echo "(all $total hints of $ex shown; the worked solution is in $solution)"
  else
    echo "(all $total hints of $ex shown)"
  fi
elif [ "$next" -eq "$total" ]; then
  echo "(hint $next of $total, the last: from now on make exercises names the mistake in $ex when it is one it knows)"
else
  echo "(hint $next of $total; make exercises HINT=$ex again for the next)"
fi
