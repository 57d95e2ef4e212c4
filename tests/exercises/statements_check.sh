#!/bin/sh
# ctest exercises.statements: what every exercise statement must have, checked on the sources.
#   - each statement (exercises/NN-topic/exercises.hpp) has its level, time and what it uses
#     ("*Level L of 3, about M min; uses N.J.*") under its title, and "uses" names exercises
#     that exist;
#   - each lesson has at least two exercises of level 3 (worked out: derive, predict, find the
#     bug), and each of those a ladder of at least three hints in hints.md with the lesson
#     section that teaches it ("Taught in:");
#   - the lesson program and the lesson's page in the notes point to each exercise where its
#     material is taught: a "now do" that names it, or, found from its statement, the "now
#     do" of the lesson's section that the statement cites ("lesson L, section K, "Title"":
#     the one in section K of the lesson program, and the one of the page that names an
#     exercise that one names);
#   - make exercises HINT=N.K shows the hints one at a time (tests/exercises/hint.sh);
#   - each level 3 statement says after how many failed runs the checker names a mistake it
#     knows ("after N failed runs", read by tests/support/exercise_check.hpp);
#   - a statement or hint that cites a lesson's section gives its number and its title, as
#     the lesson program numbers it (lessons/NN-topic/lesson.cpp, "/// ## K. Title"): the
#     notes' pages name their headings, so the number alone finds nothing there;
#   - no solution calls another exercise's function.
#   statements_check.sh <source dir> <scratch dir>
set -eu
root=$1
scratch=$2
cd "$root"
fail=0
say() { echo "$*"; fail=1; }
all=$(grep -ho '\*\*Exercise [0-9]*\.[0-9]*[: ]' exercises/*/exercises.hpp | sed 's/[^0-9.]//g')
for dir in exercises/[0-9][0-9]-*/; do
  dir=${dir%/}
  nn=$(basename "$dir" | cut -c1-2)
  lesson=${nn#0}
  hpp=$dir/exercises.hpp
  exs=$(grep -o '\*\*Exercise [0-9]*\.[0-9]*[: ]' "$hpp" | sed 's/[^0-9.]//g')
  level3=0
  for ex in $exs; do
    meta=$(grep -A3 "\*\*Exercise $ex[: ]" "$hpp" | grep -o '\*Level [1-3] of 3, about [0-9]* min[^*]*\*' | head -1 || true)
    if [ -z "$meta" ]; then say "$hpp: exercise $ex has no '*Level L of 3, about M min*' line"; continue; fi
    case "$meta" in *"Level 3 of 3"*) level3=$((level3 + 1)) ;; esac
    for used in $(echo "$meta" | sed -n 's/.*uses \(.*\)\.\*$/\1/p' | grep -o '[0-9]*\.[0-9]*'); do
      echo "$all" | grep -qx "$used" || say "$hpp: exercise $ex uses $used, which does not exist"
    done
    exre=$(echo "$ex" | sed 's/\./\\./')
    # The sections of its own lesson the statement cites, and the exercises the "now do" of
    # those sections of the lesson program name.
    cited=$(awk -v ex="$ex" '/\*\*Exercise /{on = index($0, "**Exercise " ex ":") || index($0, "**Exercise " ex " ")} on' "$hpp" |
              sed 's|^ *///||' | tr '\n' ' ' | tr -s ' ' |
              grep -oE "[Ll]esson $lesson, sections? [0-9]+" | grep -oE '[0-9]+$' || true)
    program=$(ls lessons/$nn-*/lesson.cpp 2>/dev/null | head -1)
    named=""
    for k in $cited; do
      [ -n "$program" ] || break
      named="$named $(awk -v k="$k" '/^ *\/\/\/ +## [0-9]+\. /{on = ($3 == k ".")} on' "$program" |
                       grep -i -A2 "now do" | grep -oE '\b[0-9]+\.[0-9]+\b' || true)"
    done
    for prog in lessons/$nn-*/lesson.cpp docs/lesson$nn.md; do
      [ -f "$prog" ] || continue
      # "Now do exercises 6.1 (...), 6.4 (...)": the sentence may run over three lines.
      pointers=$(grep -i -A2 "now do" "$prog" || true)
      echo "$pointers" | grep -q "\b$exre\b" && continue
      found=0
      for other in $named; do
        echo "$pointers" | grep -q "\b$(echo "$other" | sed 's/\./\\./')\b" && found=1
      done
      [ $found = 1 ] ||
        say "$prog: no 'now do $ex' where its material is taught (nor in the section its statement cites)"
    done
    case "$meta" in
      *"Level 3 of 3"*)
        awk -v ex="$ex" '/\*\*Exercise /{on = index($0, "**Exercise " ex ":") || index($0, "**Exercise " ex " ")} on' "$hpp" |
          grep -q 'after [0-9][0-9]* failed runs' ||
          say "$hpp: exercise $ex (level 3) does not say after how many failed runs its mistake is named"
        hints=$dir/hints.md
        if [ ! -f "$hints" ] || ! grep -q "^## $ex " "$hints"; then
          say "$dir: exercise $ex (level 3) has no hints in hints.md"
          continue
        fi
        section=$(awk -v ex="$ex" '/^## /{on = ($2 "" == ex "")} on' "$hints")
        echo "$section" | grep -q '^Taught in: ' || say "$hints: $ex does not say where it is taught"
        n=$(echo "$section" | grep -c '^[0-9][0-9]*\. ' || true)
        [ "$n" -ge 3 ] || say "$hints: $ex has $n hints, fewer than 3"
        # The ladder, one at a time.
        state=$scratch/hints-$ex
        rm -rf "$state"
        first=$(sh tests/exercises/hint.sh "$ex" "$state")
        second=$(sh tests/exercises/hint.sh "$ex" "$state")
        echo "$first" | grep -q "(hint 1 of $n;" || say "HINT=$ex: the first call does not show hint 1 of $n"
        echo "$first" | grep -q '^2\. ' && say "HINT=$ex: the first call shows hint 2 already"
        echo "$second" | grep -q '^2\. ' || say "HINT=$ex: the second call does not show hint 2"
        ;;
    esac
  done
  # A solution never calls another exercise's function (finished work would read "not done"
  # while that one is a stub): each name of exercises.hpp appears once in the solution's code,
  # as its definition (calls of the library's own soa::name are fine).
  sol=$(ls solutions/$nn-*/solutions.cpp 2>/dev/null | head -1)
  if [ -n "$sol" ]; then
    for name in $(grep -oE '^[A-Za-z][A-Za-z0-9_:<>, ]*[ &*][a-z_][a-z_0-9]*\(' "$hpp" |
                  grep -oE '[a-z_][a-z_0-9]*\($' | tr -d '(' | sort -u); do
      uses=$(grep -v '^ *//' "$sol" | grep -oE "(^|[^.:a-zA-Z0-9_])$name\(" | wc -l)
      [ "$uses" -le 1 ] || say "$sol: calls $name, an exercise's function: a solution must stand alone"
    done
  fi
  # Section citations: "lesson L, section K, "Title"" (over line breaks of the comments), the
  # title that of section K of lessons/0L-*/lesson.cpp (in hints.md without Doxygen math).
  for f in "$hpp" "$dir/hints.md"; do
    [ -f "$f" ] || continue
    text=$(sed 's|^ *///||' "$f" | tr '\n' ' ' | tr -s ' ')
    bare=$(printf '%s' "$text" | grep -oE '[Ll]esson [0-9]+, sections? [0-9]+([^,0-9]|, [^"]|$)' || true)
    [ -z "$bare" ] || say "$f: a section cited without its title: $(printf '%s\n' "$bare" | head -1)"
    printf '%s' "$text" | grep -oE '[Ll]esson [0-9]+, section [0-9]+, "[^"]*"' | while IFS= read -r cite; do
      l=$(printf '%s\n' "$cite" | sed -E 's/^[Ll]esson ([0-9]+),.*/\1/')
      k=$(printf '%s\n' "$cite" | sed -E 's/^[^,]*, section ([0-9]+),.*/\1/')
      title=$(printf '%s\n' "$cite" | sed -E 's/^[^"]*"(.*)"$/\1/')
      prog=$(ls lessons/$(printf '%02d' "$l")-*/lesson.cpp 2>/dev/null | head -1)
      heading=$(sed -n "s|^ *///  *## $k\. \(.*\)\$|\1|p" "$prog" 2>/dev/null | head -1)
      plain=$(printf '%s\n' "$heading" | sed 's/\\f\$//g; s/\\mathcal //g; s/\\//g; s/[{}]//g; s/\^\*/*/g')
      [ -n "$heading" ] || { echo "$f: lesson $l has no section $k ($cite)"; exit 1; }
      [ "$title" = "$heading" ] ||
        [ "$(printf '%s' "$title" | tr -d ' ')" = "$(printf '%s' "$plain" | tr -d ' ')" ] ||
        { echo "$f: $cite, but section $k of $prog is \"$heading\""; exit 1; }
    done || fail=1
  done
  [ "$level3" -ge 2 ] || say "$hpp: lesson $lesson has $level3 exercises of level 3 (worked out), fewer than 2"
done
[ $fail = 0 ] && echo "every statement has its level, time and uses; hints and pointers are in place"
exit $fail
