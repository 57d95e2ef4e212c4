#!/bin/sh
# Gradescope's setup.sh for the course (Gradescope's "Autograder Specifications"): Gradescope
# unzips the autograder into /autograder/source and runs this once, as root, when it builds
# the autograder's image (Ubuntu: its apt-get has the course's packages). The zip is a student
# release (make release) with this file and run_autograder copied to its top (the notes' page
# "Instructors", section Gradescope).
#
# The packages grading needs (make deps with the Makefile's PACKAGES cut to those that
# configure and build the exercise tree: not Chromium, Doxygen, gnuplot, SUNDIALS), then the
# library and the lessons' checkers compiled once into the image (make grade on no
# submission, OUT=/autograder/grade): each submission then compiles only its own code.
#   AUTOGRADER (default /autograder): where Gradescope's folders are
set -eu
ag=${AUTOGRADER:-/autograder}
cd "$ag/source"
if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
  apt-get update -q
  apt-get install -y -q make
fi
make deps PACKAGES="cmake g++ ninja-build pkgconf libeigen3-dev libgtest-dev libgmock-dev \
  libbenchmark-dev nlohmann-json3-dev liburdfdom-dev libtinyxml-dev libsleef-dev"
mkdir -p "$ag/no-submissions"
UNSAFE=1 make grade SUBMISSIONS="$ag/no-submissions" OUT="$ag/grade"
