#!/bin/sh
# The student release's text (tests/release/release.sh): the sentences, rows and links about
# the solutions, the planted mistakes, the author's page and the release itself, taken out
# or said for a student. Each edit must change its file: one whose text is gone stops the
# release, naming the file and the edit (then update the edit here).
#   student_text.sh <release dir>
set -eu
dir=$1

# edit <file> <sed arguments...>
edit() {
  file=$1
  shift
  sed "$@" "$dir/$file" >"$dir/$file.new"
  if cmp -s "$dir/$file" "$dir/$file.new"; then
    rm -f "$dir/$file.new"
    echo "make release: $file: this edit of tests/release/student_text.sh finds its text no more: $*"
    exit 1
  fi
  mv "$dir/$file.new" "$dir/$file"
}

edit README.md '/^Students build the lesson programs and do the exercises, instructors run the solution$/,/^checked numerically\.$/c\
Students build the lesson programs, do the exercises and read the generated course notes.\
Every identity the course states is checked numerically.'
edit README.md 's/exercise tests against the solutions$/every exercise fails on its stub/'
edit README.md '/^`make test` also runs `make exercises` itself/,/(`ctest -R exercises\.probe`)\.$/c\
`make test` also runs `make exercises` itself, in a build tree of its own\
(`exercises.student-config`: the same flags, sanitizers, assertions and call watch), on the\
stubs (every row "not done"), then probe "students" with an endless loop, a flood of output,\
an uninitialised variable, an index past the end, a crash inside the checker and forbidden\
inline calls (`ctest -R exercises.probe`).'
edit README.md 's/ How to add an exercise: the$//'
edit README.md '/^notes'"'"' page "Adding an exercise"/d'
edit README.md '/^| `solutions\/` |/d'
edit README.md 's/ and the planted mistakes that test it (in the same file, next to each exercise'"'"'s test: `tests\/exercises\/plant\.cmake`)//'
edit README.md 's/; `solutions\/NN-topic\/` has the reference code (try first)\./\./'
edit README.md '/^## Instructors$/,/^## /{
/^## Instructors$/d
/^## /!d
}'

edit docs/mainpage.md 's/, and the exercise tests against the reference solutions |$/, and every exercise against its stub (each must fail) |/'
edit docs/mainpage.md 's/classic mistakes, planted mistakes)/classic mistakes)/'
edit docs/mainpage.md '/^| the reference solutions |/d'
edit docs/mainpage.md '/\\subpage adding_an_exercise\.$/d'
edit docs/mainpage.md '/\\subpage instructors\.$/d'
edit docs/mainpage.md 's/gives the next hint of a ladder, and$/gives the next hint of a ladder./'
edit docs/mainpage.md '/^ *`solutions\/NN-topic\/` has the reference code (try first)\.$/d'

edit exercises/01-spatial-notation/README.md '/^A worked solution for each exercise is in/,/^Try the exercises before you look at it\.$/d'
edit exercises/01-spatial-notation/README.md -e :a -e '/^\n*$/{$d;N;ba' -e '}'

edit Makefile 's/exercise tests against the solutions$/every exercise failing on its stub/'
edit Makefile 's/^# built\. make test runs this same recipe on the solutions (exercises\.student-config)\.$/# built./'
edit Makefile 's/: exercises\/ itself\. The test of this$/: exercises\/ itself./'
edit Makefile '/^# configuration (tests\/exercises\/student_config\.sh) points it at the solutions\.$/d'
edit Makefile 's/ (tests\/exercises\/stubs\.sh; docs\/adding_an_exercise\.md)\./ (tests\/exercises\/stubs.sh)./'
edit Makefile '/^#   make release /d'
edit Makefile 's/ format release$/ format/'
edit Makefile '/^# The student'"'"'s repository, without the answers, into OUT/,/^$/d'
