#!/bin/sh
# make grade SUBMISSIONS=DIR OUT=DIR [WEIGHTS=FILE] [LESSONS=1,2] [TREE=DIR] UNSAFE=1: every
# submission of a class judged by the exercise checker, as make exercises judges a student's
# copy (the notes' page "Instructors", docs/instructors.md).
#
# An entry of SUBMISSIONS is one student, named by the entry (its file name without .tar.gz,
# .tgz, .zip or .git): a folder holding exercises/ (or holding one folder that does), a
# .tar.gz, .tgz or .zip of one, or a git repository (a folder with .git/, or a bare one),
# graded at its HEAD commit. Other entries are skipped, saying so. From a submission only the
# regular files exercises/NN-topic/*.cpp of the lessons graded are taken (names of ASCII
# letters, digits, '_', '-' and '.'): never a symbolic link or a file with other hard links,
# never the statements exercises.hpp (the checker compiles against the project's). An
# archive with an entry whose path is absolute or has a ".." is refused whole; only the
# selected entries of an archive are extracted. A lesson the submission has no file of is
# graded on its stub ("not done").
#
# The library and the checkers are compiled once per run, in one exercise tree (OUT/.work/tree,
# configured by make exercise-tree, the flags of make exercises; or TREE=DIR, an exercise tree
# already built, e.g. make test's, configured again for OUT/.work/current). For each
# submission its files are copied into OUT/.work/current and only its lessons' exercise
# libraries are built again (exNN-exercises); the checker runs them with --report and
# --results (tests/exercises/exercise_main.cpp), which says each exercise's status.
#
# The verdict is not that run's: the student's code is linked into it, and could rewrite it.
# That run records the answers the student's functions give the checker (--record); the
# judge, the same checker linked with no student code (exNN-judge), replays them and judges
# (--replay, tests/support/recording.hpp). An exercise passes only if the judge says so and
# the run saw nothing else wrong (a forbidden call, a limit reached); a record that does not
# answer the judge's calls (the run stopped, or the code wrote into it) is never a pass.
#
# OUT (new, empty, or the output of an earlier run, which is replaced) receives:
#   gradebook.csv       a row per student: the name, the points of each exercise, the total
#   statuses.csv        the same rows with each exercise's status in words
#   feedback/NAME.md    what make exercises would have shown that student
#   results/NAME.json   Gradescope's results.json
#   class.md            pass rates, the classic mistakes and symptoms counted, exercises
#                       nobody attempted
# Each file is written to a temporary name and renamed: never a partial file. The gradebook
# and class.md are written again after each submission; Ctrl-C stops at the end of the
# submission being graded (which is left out) and keeps every completed row.
#
# Student code runs in a sandbox (bubblewrap, Debian bubblewrap; in_sandbox below): no
# network, / read-only, a private /tmp and one writable scratch folder per submission; the
# home folder, SUBMISSIONS, OUT (but the exercise tree, read-only), the project's solutions/
# and its build/ folder are not visible. Run as root, student code runs as the user nobody
# (in the sandbox and without it), so that the process limit counts its processes and it
# cannot write what root owns. Under limits: CPU time, wall time, processes, file size, and
# (AddressSanitizer's) memory, each named in the feedback when a run reaches it. Where the
# sandbox cannot start, the grader stops saying why; UNSAFE=1 runs without it (trusted
# submissions, or a container of their own as on Gradescope). A submission's compiles run in
# the same sandbox, as the same user: an #include or .incbin reads only what the runs see.
#
# The instructor's cases: SEEDS=FILE, a seed a line (a positive whole number; # starts a
# comment), kept out of the students' reach (the file is yours, not the project's). Each
# lesson's exercises that pass are run again once per seed, the checker drawing every case
# with the seed mixed in (the runner's --seed): cases no student has seen. An exercise passes
# only if it passes on them too; its row says which seed it failed on.
#   grade.sh <source dir> <submissions dir> <out dir> [<weights file>]
#   environment: UNSAFE, LESSONS (e.g. "1,2"; all by default), TREE, JOBS, SEEDS,
#   SOA_EXERCISE_TIME_LIMIT (seconds per exercise, 10 by default)
set -u
LC_ALL=C
export LC_ALL
here=$(cd "$(dirname "$0")" && pwd)
src=${1:-}
subs=${2:-}
out=${3:-}
weights=${4:-}
jobs=${JOBS:-2}

# One line naming what is wrong, and a non-zero exit.
die() {
  printf 'make grade: %s\n' "$*" >&2
  exit 1
}

[ -n "$src" ] && [ -d "$src/exercises" ] || die "usage: grade.sh <source dir> <submissions dir> <out dir> [<weights file>]"
[ -n "$subs" ] || die "SUBMISSIONS=DIR is missing: the folder of the students' submissions"
[ -d "$subs" ] || die "SUBMISSIONS=$subs is not a folder"
[ -n "$out" ] || die "OUT=DIR is missing: the folder to write the gradebook and the reports into"
[ -z "$weights" ] || [ -f "$weights" ] || die "WEIGHTS=$weights is not a file"
src=$(cd "$src" && pwd -P)
subs=$(cd "$subs" && pwd -P)
mkdir -p "$out" 2>/dev/null || die "OUT=$out: cannot be made"
out=$(cd "$out" && pwd -P)
case "$out/" in
  "$subs"/*) die "OUT=$out is inside SUBMISSIONS=$subs" ;;
esac
work=$out/.work
if [ -n "$(ls -A "$out")" ] && [ ! -f "$work/grade-out" ]; then
  die "OUT=$out is not empty and is not the output of make grade"
fi

# --- the sandbox and the limits ---------------------------------------------------------------
# The limits of a lesson's run (the checker runs each exercise in a child process, stopped
# after SOA_EXERCISE_TIME_LIMIT s of wall time, with an output limit of its own).
lim_wall=300        # s of wall time for a lesson's whole run, or for one compile
lim_cpu=300         # s of CPU time, likewise
lim_nproc=64        # processes (of the user nobody when run as root, else of yours)
lim_fsize=256       # MB: the largest file written (the feedback is a file), and the private /tmp
lim_mem=4096        # MB: AddressSanitizer's limit on an allocation and on the resident memory
# Run as root, student code runs as the user nobody, in the sandbox or not.
drop=""
[ "$(id -u)" != 0 ] || drop="setpriv --reuid=65534 --regid=65534 --clear-groups"
if [ "${UNSAFE:-}" = 1 ]; then
  sandbox=none
else
  sandbox=bwrap
  command -v bwrap >/dev/null 2>&1 ||
    die "the sandbox cannot start: bwrap is not installed (Debian package bubblewrap: make deps); UNSAFE=1 grades without it, for trusted submissions only"
  # shellcheck disable=SC2086
  why=$($drop bwrap --unshare-all --die-with-parent --ro-bind / / --proc /proc --dev /dev \
    --tmpfs /tmp true 2>&1) ||
    die "the sandbox cannot start: bwrap: $(printf '%s' "$why" | head -1) (user namespaces disabled?); UNSAFE=1 grades without it, for trusted submissions only"
fi
# sandboxed <folders> <read-only folders> <command...>: the command under the limits, in the
# sandbox unless UNSAFE=1, in the first of <folders> (one a line), the only ones it can write
# besides its private /tmp; it sees / read-only, but for the hidden folders (the home folder,
# the project's build/ and solutions/, OUT and SUBMISSIONS), which are empty, and in them only
# <folders> and the <read-only folders> (one a line). Exit 137 (killed) when a time limit is
# reached.
sandboxed() {
  rw=$1
  ro=$2
  shift 2
  here_rw=$(printf '%s\n' "$rw" | head -1)
  limits="prlimit --cpu=$lim_cpu --fsize=$((lim_fsize << 20)) --core=0"
  if [ $sandbox = none ]; then
    # shellcheck disable=SC2086
    (cd "$here_rw" && timeout -s KILL "$lim_wall" $drop $limits --nproc=$lim_nproc "$@")
    return
  fi
  # bwrap's options are put before the command last to first. The hidden folders (those not
  # inside another) are empty and read-only: a tmpfs each, remounted read-only once the
  # folders bound inside them are.
  hidden=$(for d in "${HOME:-/}" "$src/build" "$src/solutions" "$out" "$subs"; do
    [ "$d" = / ] || [ ! -d "$d" ] || printf '%s\n' "$d"; done | sort -u |
    awk '{ for (k = 1; k <= n; k++) if (index($0 "/", top[k] "/") == 1) next; top[++n] = $0; print }')
  set -- --chdir "$here_rw" -- "$@"
  old_ifs=$IFS
  IFS='
'
  for d in $hidden; do set -- --remount-ro "$d" "$@"; done
  for d in $rw; do set -- --bind "$d" "$d" "$@"; done
  for d in $ro; do set -- --ro-bind "$d" "$d" "$@"; done
  for d in $hidden; do
    case "$src/" in "$d"/*) ;; *) set -- --tmpfs "$d" "$@" ;; esac
  done
  set -- --ro-bind "$src" "$src" "$@"
  for d in $hidden; do
    case "$src/" in "$d"/*) set -- --tmpfs "$d" "$@" ;; esac
  done
  IFS=$old_ifs
  # shellcheck disable=SC2086
  timeout -s KILL "$lim_wall" $drop $limits --nproc=$lim_nproc bwrap --unshare-all \
    --die-with-parent --new-session --ro-bind / / --proc /proc --dev /dev \
    --size $((lim_fsize << 20)) --tmpfs /tmp "$@"
}

# in_sandbox <scratch> <command...>: a run of student code, sandboxed() with <scratch> (made
# here, empty) its working folder, the exercise tree and the hints read-only.
in_sandbox() {
  scratch=$1
  shift
  rm -rf "${scratch:?}"
  mkdir -p "$scratch"
  [ -z "$drop" ] || chown 65534:65534 "$scratch"
  sandboxed "$scratch" "$tree
$work/hints" "$@"
}

# build_in_sandbox <command...>: a compile of student code, sandboxed() in the exercise tree
# (written by nobody when run as root: the tree is nobody's once the checkers are built), the
# student's files read-only; an #include or .incbin reads only what the runs can. ccache's
# cache is OUT/.work/ccache (yours, in your home folder, is hidden; the runs see neither): a
# file compiled before, a stub of a lesson not done, is not compiled again. With UNSAFE=1,
# under the time limit only, as you.
build_in_sandbox() {
  if [ $sandbox = none ]; then
    timeout -s KILL "$lim_wall" "$@"
    return
  fi
  CCACHE_DIR=$work/ccache sandboxed "$tree
$work/ccache" "$cur" "$@"
}

# The lessons graded: NN-topic folders of the project.
if [ -n "${LESSONS:-}" ]; then
  lessons=""
  for n in $(echo "$LESSONS" | tr ',' ' '); do
    case "$n" in '' | *[!0-9]*) die "LESSONS=$LESSONS: lessons are numbers, e.g. LESSONS=1,2" ;; esac
    nn=$(printf '%02d' "$(expr "$n" + 0)")
    dir=$(cd "$src/exercises" && ls -d "$nn"-* 2>/dev/null | head -1)
    [ -n "$dir" ] || die "LESSONS=$LESSONS: there is no lesson $n"
    lessons="$lessons $dir"
  done
else
  lessons=$(cd "$src/exercises" && ls -d [0-9][0-9]-* | tr '\n' ' ')
fi
all_lessons=$(cd "$src/exercises" && ls -d [0-9][0-9]-* | tr '\n' ' ')

# The stubs stand in for a lesson a submission lacks: they must be the stubs as shipped.
for l in $lessons; do
  (cd "$src" && grep -F " exercises/$l/" tests/exercises/stubs.sha256 | grep '\.cpp$' |
    sha256sum -c --quiet >/dev/null 2>&1) ||
    die "$src/exercises/$l/*.cpp differ from tests/exercises/stubs.sha256: the grader grades a lesson a submission lacks on its stubs; restore them (git checkout exercises/$l)"
done

# A fresh output: the earlier run's reports go; its exercise tree stays (compiled once).
mkdir -p "$work"
: >"$work/grade-out"
rm -rf "$out/feedback" "$out/results" "$out/gradebook.csv" "$out/statuses.csv" "$out/class.md" \
  "$work/rows" "$work/cases" "$work/logs" "$work/sub" "$work/hints"
mkdir -p "$out/feedback" "$out/results" "$work/rows" "$work/cases" "$work/logs" "$work/hints"
: >"$work/rows/gradebook"
: >"$work/rows/statuses"
: >"$work/rows/all.tsv"
: >"$work/rows/names"

# The exercises: <lesson>\t<id>\t<title>, from the statements' "**Exercise N.K: title**".
titles() {
  awk -v dir="$1" 'match($0, /\*\*Exercise [0-9]+\.[0-9]+/) {
      id = substr($0, RSTART + 11, RLENGTH - 11); t = substr($0, RSTART + RLENGTH)
      sub(/^[:.]? */, "", t); sub(/\*\*.*$/, "", t); sub(/ *\(slides? [^)]*\)\.?$/, "", t)
      sub(/\.$/, "", t); print dir "\t" id "\t" t }' "$src/exercises/$1/exercises.hpp"
}
: >"$work/exercises.tsv"
for l in $lessons; do titles "$l" >>"$work/exercises.tsv"; done
: >"$work/all-exercises.tsv"
for l in $all_lessons; do titles "$l" >>"$work/all-exercises.tsv"; done

# Points: "<exercise> <points>" a line (# starts a comment), 1 for an exercise not listed.
cut -f2 "$work/exercises.tsv" | sed 's/$/	1/' >"$work/weights.tsv"
if [ -n "$weights" ]; then
  rm -f "$work/all-exercises.tsv.w"
  msg=$(awk -v file="$weights" -v to="$work/all-exercises.tsv.w" '
    NR == FNR { known[$2] = 1; next }
    { sub(/#.*/, "") }
    NF == 0 { next }
    NF != 2 || !($1 in known) || $2 !~ /^[0-9]+(\.[0-9]+)?$/ {
      print file ":" FNR ": expected \"<exercise> <points>\" (an exercise such as 3.2, points such as 2 or 0.5), got: " $0
      exit 1 }
    { print $1 "\t" $2 > to }' FS='\t' "$work/all-exercises.tsv" FS=' ' "$weights") ||
    die "WEIGHTS=$msg"
  if [ -f "$work/all-exercises.tsv.w" ]; then
    awk -F '\t' 'FILENAME == ARGV[1] { w[$1] = $2; next } { print $1 "\t" (($1 in w) ? w[$1] : $2) }' \
      "$work/all-exercises.tsv.w" "$work/weights.tsv" >"$work/weights.new"
    mv "$work/weights.new" "$work/weights.tsv"
    rm -f "$work/all-exercises.tsv.w"
  fi
fi

max=$(awk -F '\t' '{ s += $2 } END { printf "%g", s }' "$work/weights.tsv")

# The instructor's seeds.
seeds=""
if [ -n "${SEEDS:-}" ]; then
  [ -f "$SEEDS" ] || die "SEEDS=$SEEDS is not a file"
  seeds=$(awk -v file="$SEEDS" '{ sub(/#.*/, "") }
    NF == 0 { next }
    NF != 1 || $1 !~ /^[1-9][0-9]*$/ || length($1) > 18 {
      bad = file ":" FNR ": expected a seed (a positive whole number such as 2027), got: " $0; exit 1 }
    { list = list " " $1 }
    END { print bad != "" ? bad : list; exit bad != "" }' "$SEEDS") || die "SEEDS=$seeds"
  [ -n "$seeds" ] || die "SEEDS=$SEEDS: no seed in it"
fi

if [ $sandbox = none ]; then
  if [ -n "$drop" ]; then who="as the user nobody"; else who="with your rights"; fi
  echo "grade: UNSAFE=1: student code runs without the sandbox, $who" >&2
fi

# The checker names a level 3 exercise's mistake once every hint is read: here, for all.
cut -f2 "$work/all-exercises.tsv" | while read -r id; do echo 99 >"$work/hints/$id"; done

# The student's files: OUT/.work/current/NN-topic/*.cpp, every lesson (the tree compiles the
# lessons not graded too when it is configured), the stubs where a submission has none.
cur=$work/current
stubs() {  # <lesson>
  rm -rf "${cur:?}/$1"
  mkdir -p "$cur/$1"
  cp "$src/exercises/$1/"*.cpp "$cur/$1/"
}
for l in $all_lessons; do stubs "$l"; done

# The exercise tree, configured for OUT/.work/current, then the library and the checkers.
built=$(date +%s)
tree=${TREE:-$work/tree}
echo "grade: the library and the checkers, compiled once in $tree (the first time takes minutes)" >&2
if [ -n "${TREE:-}" ]; then
  grep -q '^SOA_CHECK_STUBS:BOOL=OFF$' "$tree/CMakeCache.txt" 2>/dev/null ||
    die "TREE=$tree is not an exercise tree (make exercise-tree EX_DIR=$tree makes one)"
  cmake -S "$src" -B "$tree" -DSOA_EXERCISES_DIR="$cur" >"$work/logs/configure.log" 2>&1 ||
    die "TREE=$tree does not configure for $cur (see $work/logs/configure.log)"
else
  (unset MAKEFLAGS MFLAGS MAKELEVEL
   make --no-print-directory -C "$src" exercise-tree EX_DIR="$tree" EXERCISES="$cur") \
    >"$work/logs/configure.log" 2>&1 ||
    die "the exercise tree does not configure (see $work/logs/configure.log)"
fi
grep -q '^SOA_WATCH_CALLS:BOOL=ON$' "$tree/CMakeCache.txt" 2>/dev/null ||
  die "the exercise tree $tree does not watch the calls (x86-64 and binutils' nm, objcopy, c++filt): the grader's record of the answers needs it"
targets=soa_exercise_main
for l in $lessons; do
  nn=$(echo "$l" | cut -c1-2)
  targets="$targets ex$nn-tests ex$nn-record ex$nn-judge"
done
# shellcheck disable=SC2086
cmake --build "$tree" -j "$jobs" --target $targets >"$work/logs/checkers.log" 2>&1 ||
  die "the library or a checker does not compile (see $work/logs/checkers.log)"
if [ $sandbox = bwrap ]; then
  mkdir -p "$work/ccache"
  if [ -n "$drop" ]; then
    chown -R 65534:65534 "$tree" "$work/ccache" ||
      die "$tree: cannot be given to the user nobody (chown)"
  fi
fi
built=$(($(date +%s) - built))

# --- one submission ---------------------------------------------------------------------------
note() { printf '%s\n' "$*" >>"$notes"; }

# The lessons' files of a submission's root folder into OUT/.work/current.
take() {  # <root>
  root=$1
  if [ ! -d "$root/exercises" ] || [ -L "$root/exercises" ]; then
    # One folder down (a folder zipped with its name): when exactly one has exercises/.
    count=0
    for d in "$root"/*/exercises; do
      if [ -d "$d" ] && [ ! -L "$d" ] && [ ! -L "${d%/exercises}" ]; then
        count=$((count + 1))
        one=${d%/exercises}
      fi
    done
    [ $count = 1 ] && root=$one
  fi
  if [ ! -d "$root/exercises" ] || [ -L "$root/exercises" ]; then
    note "no exercises/ folder in the submission: every exercise is graded \"not done\""
    return 1
  fi
  for l in $lessons; do
    rm -rf "${cur:?}/$l"
    mkdir -p "$cur/$l"
    if [ -d "$root/exercises/$l" ] && [ ! -L "$root/exercises/$l" ]; then
      for f in "$root/exercises/$l"/*.cpp; do
        [ -e "$f" ] || [ -L "$f" ] || continue
        base=${f##*/}
        case "$base" in
          *[!A-Za-z0-9_.-]*)
            note "exercises/$l: a file whose name is not ASCII letters, digits, '_', '-' and '.' is left out"
            continue ;;
        esac
        if [ -L "$f" ] || [ ! -f "$f" ] || [ "$(stat -c %h "$f")" != 1 ]; then
          note "exercises/$l/$base: not a regular file (a symbolic or hard link?): left out"
          continue
        fi
        cp "$f" "$cur/$l/$base"
      done
    fi
    if [ -z "$(ls "$cur/$l")" ]; then
      note "no file of exercises/$l: its exercises are graded on the stubs (\"not done\")"
      stubs "$l"
    fi
  done
}

# An archive's selected entries into OUT/.work/sub, then take().
unpack() {  # <archive>
  if ! cmake -E tar tf "$1" >"$work/sub.list" 2>/dev/null; then
    note "it could not be read as an archive: every exercise is graded \"not done\""
    return 1
  fi
  bad=$(grep -E -m1 '^/|(^|/)\.\.(/|$)' "$work/sub.list")
  if [ -n "$bad" ]; then
    note "refused: it has an entry outside its folder ($bad): nothing of it is graded, every exercise \"not done\""
    return 1
  fi
  grep -E '^(\./)?([^/]+/)?exercises/[0-9][0-9]-[A-Za-z0-9-]+/[A-Za-z0-9_][A-Za-z0-9_.-]*\.cpp$' \
    "$work/sub.list" >"$work/sub.take"
  # CMake lists a name it cannot convert (not UTF-8) as an empty line.
  if grep -q '^$' "$work/sub.list" || grep -E '(^|/)exercises/[0-9][0-9]-[^/]*/[^/]*\.cpp$' "$work/sub.list" |
    grep -vqE '/[A-Za-z0-9_][A-Za-z0-9_.-]*\.cpp$'; then
    note "an entry whose name is not ASCII letters, digits, '_', '-' and '.' (or not UTF-8) is left out"
  fi
  mkdir -p "$work/sub"
  if [ -s "$work/sub.take" ]; then
    # shellcheck disable=SC2046
    (cd "$work/sub" && cmake -E tar xf "$1" -- $(cat "$work/sub.take")) >/dev/null 2>&1 || {
      note "its files could not be extracted: every exercise is graded \"not done\""
      return 1
    }
  fi
  take "$work/sub"
}

# Every exercise of a lesson with one status and message (through the environment: awk -v
# would read the message's backslashes as escapes).
all_as() {  # <lesson> <status> <escaped message>
  MSG=$3 awk -F '\t' -v l="$1" -v st="$2" '$1 == l { print $2 "\t" st "\t" ENVIRON["MSG"] }' \
    "$work/exercises.tsv" >>"$results"
}
esc() { printf '%s\n' "$1" | tr -d '\000-\010\013-\037\177' | awk -f "$here/escape.awk"; }

# run_lesson <scratch> <results copy> <runner's options...>: the lesson's checker program run
# on the submission in the sandbox (its scratch folder <scratch>), its report added to the
# feedback, a limit it was stopped at named there, the answers recorded in <scratch>; then the
# judge's verdict on them (judge_lesson). <results copy> receives the verdict.
run_lesson() {
  run_cases=$1
  run_copy=$2
  shift 2
  rm -f "$run_copy"
  began=$(date +%s)
  SOA_EXERCISE_CASES=$run_cases SOA_EXERCISE_HINTS=$work/hints \
    ASAN_OPTIONS=detect_leaks=0:max_allocation_size_mb=$lim_mem:hard_rss_limit_mb=$lim_mem \
    in_sandbox "$run_cases" "$prog" --report --header "$src/exercises/$l/exercises.hpp" \
    --results "$run_cases/lesson.tsv" --record "$run_cases" "$@" >>"$feedback" \
    2>"$work/logs/$i-ex$nn.stderr"
  rc=$?
  case $rc in
    0 | 1) ;;
    137)
      if [ $(($(date +%s) - began)) -ge "$lim_wall" ]; then
        echo "  the test program was stopped at a limit: $lim_wall s of wall time for the lesson" >>"$feedback"
      else
        echo "  the test program was stopped at a limit: $lim_cpu s of CPU time (or killed)" >>"$feedback"
      fi ;;
    153) echo "  the test program was stopped at a limit: a file (its output) of $lim_fsize MB" >>"$feedback" ;;
    *) echo "  the test program stopped (exit $rc; see $work/logs/$i-ex$nn.stderr)" >>"$feedback" ;;
  esac
  : >"$work/run.tsv"
  [ -f "$run_cases/lesson.tsv" ] && [ ! -L "$run_cases/lesson.tsv" ] && cp "$run_cases/lesson.tsv" "$work/run.tsv"
  judge_lesson "$run_cases" "$run_copy" "$@"
}

# judge_lesson <record folder> <verdict> <runner's options...>: the judge (the checker with no
# student code, in the sandbox too: the record is the student's) replays the record; <verdict>
# is its results, but where the run of the student's code saw worse (a forbidden call, a
# limit, a crash after the answers it recorded) or the record does not answer the judge's
# calls ("unjudged": that run's status, never a pass); and a forbidden call the build found
# in the code (watch.cmake's step 4, which no student code can change) whatever the runs say.
judge_lesson() {
  record=$1
  verdict=$2
  shift 2
  judged=$record.judge
  rm -rf "${judged:?}"
  mkdir -p "$judged"
  [ -z "$drop" ] || chown 65534:65534 "$judged"
  SOA_EXERCISE_CASES=$judged SOA_EXERCISE_HINTS=$work/hints sandboxed "$judged" "$tree
$work/hints
$record" "$tree/tests/ex$nn-judge" --report --header "$src/exercises/$l/exercises.hpp" \
    --results "$judged/lesson.tsv" --replay "$record" "$@" >"$work/logs/$i-ex$nn.judge" 2>&1 ||
    echo "  the judge stopped (exit $?; see $work/logs/$i-ex$nn.judge)" >>"$feedback"
  : >"$work/judge.tsv"
  [ -f "$judged/lesson.tsv" ] && [ ! -L "$judged/lesson.tsv" ] && cp "$judged/lesson.tsv" "$work/judge.tsv"
  # The forbidden calls the build found in the student's code (watch.cmake, step 4).
  calls=$tree/tests/watch/ex$nn-exercises/watch.cpp.static
  if [ ! -f "$calls" ]; then
    calls=$work/no-calls
    : >"$calls"
  fi
  awk -F '\t' -v OFS='\t' -v note="$work/judge.note" '
    FILENAME == ARGV[1] { calls[$1] = calls[$1] (calls[$1] == "" ? "" : ", ") $2; next }
    FILENAME == ARGV[2] { st[$1] = $3; msg[$1] = $4; name[$1] = $2; next }
    {
      id = $1; s = $3; m = $4
      if (!(id in st)) { s2 = "unjudged"; m2 = "the judge gave no verdict" } else { s2 = st[id]; m2 = msg[id] }
      if (s2 == "unjudged") {
        if (s == "pass") { s = "crashed"; m = m2 "\\nthe answers your code recorded do not answer the checker'"'"'s calls" }
      } else if (s2 != "pass" || s == "pass") { s = s2; m = m2 }
      if ((id in calls) && s != "forbidden-call") {
        s = "forbidden-call"
        m = "your code calls " calls[id] ", which exercise " id " reproduces (its statement says: do not call it): the exercise is to compute it yourself\\n" m
      }
      if (s != $3) { first = m; sub(/\\n.*/, "", first); print "  " id ": " s (first == "" ? "" : ": " first) > note }
      print id, $2, s, m
    }' "$calls" "$work/judge.tsv" "$work/run.tsv" >"$verdict"
  if [ -s "$work/judge.note" ]; then
    echo "  The judge's verdict (the checker run again, without your code, on the answers it gave):" >>"$feedback"
    cat "$work/judge.note" >>"$feedback"
  fi
  rm -f "$work/judge.note"
}

grade_one() {  # <entry> <kind>
  entry=$1
  kind=$2
  rm -rf "$work/sub" "$work/sub.tar"
  ok=1
  case "$kind" in
    link) note "a symbolic link: not followed, every exercise \"not done\""; ok=0 ;;
    folder) take "$entry" || ok=0 ;;
    archive) unpack "$entry" || ok=0 ;;
    git)
      if [ -e "$entry/.git" ] && [ ! -d "$entry/.git" ]; then
        note "its .git is not a folder (a linked worktree?): not followed, every exercise \"not done\""
        ok=0
      elif GIT_CONFIG_NOSYSTEM=1 GIT_CONFIG_GLOBAL=/dev/null git -c safe.directory='*' \
          -c core.fsmonitor=false -C "$entry" archive --format=tar -o "$work/sub.tar" HEAD \
          -- exercises >/dev/null 2>&1; then
        unpack "$work/sub.tar" || ok=0
      else
        note "git archive HEAD -- exercises failed (no commit, or no exercises/ committed): every exercise \"not done\""
        ok=0
      fi ;;
  esac
  for l in $lessons; do
    [ $interrupted = 0 ] || return
    nn=$(echo "$l" | cut -c1-2)
    if [ $ok = 0 ]; then
      all_as "$l" not-done ""
      printf '== Lesson %s exercises (exercises/%s) ==\n  not graded: see the notes above\n\n' \
        "$nn" "$l" >>"$feedback"
      continue
    fi
    log=$work/logs/$i-ex$nn.log
    prog=$tree/tests/ex$nn-exercises
    rm -f "$prog"
    find "$tree/exercises/CMakeFiles/exercises_$nn.dir" -name '*.diag' -exec rm -f {} + 2>/dev/null
    echo "== Lesson $nn exercises (exercises/$l) ==" >>"$feedback"
    if build_in_sandbox cmake --build "$tree" -j "$jobs" --target "ex$nn-exercises" \
      >"$log" 2>&1; then
      set --
      find "$tree/exercises/CMakeFiles/exercises_$nn.dir" -name '*.diag' >"$work/diags" 2>/dev/null
      while IFS= read -r d; do set -- "$@" --warnings "$d"; done <"$work/diags"
      run_lesson "$cases/$nn" "$work/lesson.tsv" "$@"
      # An exercise the program never judged (it stopped): crashed.
      awk -F '\t' -v l="$l" 'FILENAME == ARGV[1] { seen[$1] = 1; next }
        $1 == l && !($2 in seen) { print $2 "\t\tcrashed\tthe test program stopped before judging it" }' \
        "$work/lesson.tsv" "$work/exercises.tsv" >>"$work/lesson.tsv"
      # The instructor's cases: the exercises that pass, once more per seed.
      for seed in $seeds; do
        filter=$(awk -F '\t' '$3 == "pass" { sub(/\./, "_", $1); f = f (f == "" ? "" : ":") "Exercise" $1 "_*" }
          END { print f }' "$work/lesson.tsv")
        [ -n "$filter" ] || break
        printf "== Lesson %s, the instructor's cases (seed %s): the exercises that pass above, again ==\n" \
          "$nn" "$seed" >>"$feedback"
        run_lesson "$cases/$nn.seed" "$work/seed.tsv" "$@" --seed "$seed" --gtest_filter="$filter"
        # A pass that fails on them takes the failure, saying on which seed.
        awk -F '\t' -v OFS='\t' -v seed="$seed" 'FILENAME == ARGV[1] { st[$1] = $3; msg[$1] = $4; next }
          $3 == "pass" && st[$1] != "pass" {
            $3 = ($1 in st) ? st[$1] : "crashed"
            $4 = "with the instructor'"'"'s cases (seed " seed "): " (($1 in st) ? msg[$1] : "the test program stopped before judging it") }
          { print }' "$work/seed.tsv" "$work/lesson.tsv" >"$work/lesson.new"
        mv "$work/lesson.new" "$work/lesson.tsv"
      done
      cut -f1,3- "$work/lesson.tsv" >>"$results"  # <id>\t<status>\t<message>
    else
      errors=$(grep -m8 -E 'error|note: +candidate' "$log" | sed "s|$cur/||g")
      [ -n "$errors" ] || errors="the compile was stopped at the limit of $lim_wall s"
      {
        echo "  does not compile yet (the first errors):"
        printf '%s\n' "$errors" | sed 's/^/    /'
      } >>"$feedback"
      all_as "$l" does-not-compile "$(esc "$errors")"
    fi
    echo >>"$feedback"
  done
}

# --- the class ----------------------------------------------------------------------------------
interrupted=0
trap 'interrupted=1' INT TERM
list=$work/entries
(cd "$subs" && ls -A) >"$list"
m=$(grep -c . "$list")
i=0
done_n=0
start=$(date +%s)
publish() {  # gradebook.csv, statuses.csv, class.md from the rows so far
  header=$(cut -f2 "$work/exercises.tsv" | tr '\n' ',')
  { echo "student,${header}total"; cat "$work/rows/gradebook"; } >"$out/gradebook.csv.tmp"
  mv "$out/gradebook.csv.tmp" "$out/gradebook.csv"
  { echo "student,${header%,}"; cat "$work/rows/statuses"; } >"$out/statuses.csv.tmp"
  mv "$out/statuses.csv.tmp" "$out/statuses.csv"
  # shellcheck disable=SC2086
  awk -v students="$done_n" -v when="$(date -u '+%Y-%m-%d %H:%M UTC')" \
    -v lessons="$(echo $lessons | sed 's/\([0-9][0-9]\)-[^ ]*/\1/g; s/ /, /g')" \
    -v stopped="$1" -f "$here/class.awk" "$work/exercises.tsv" "$work/rows/all.tsv" \
    >"$out/class.md.tmp"
  mv "$out/class.md.tmp" "$out/class.md"
}
publish ""
while IFS= read -r base; do
  i=$((i + 1))
  [ $interrupted = 0 ] || break
  entry=$subs/$base
  case "$base" in
    .*) printf 'grade: %s: a hidden entry, skipped\n' "$base" >&2; continue ;;
  esac
  if [ -L "$entry" ]; then kind="link"; name=$base
  elif [ -d "$entry" ]; then
    if [ -d "$entry/.git" ] || [ -f "$entry/.git" ] || { [ -f "$entry/HEAD" ] && [ -d "$entry/objects" ]; }; then
      kind=git
    else kind=folder; fi
    name=${base%.git}
  else
    case "$base" in
      *.tar.gz) kind=archive; name=${base%.tar.gz} ;;
      *.tgz) kind=archive; name=${base%.tgz} ;;
      *.zip) kind=archive; name=${base%.zip} ;;
      *) printf 'grade: %s: not a submission (a folder, .tar.gz, .tgz, .zip or git repository), skipped\n' "$base" >&2; continue ;;
    esac
  fi
  # The student's name as it can be written in every output: valid UTF-8, no control character.
  raw=$name
  name=$(printf '%s' "$raw" | iconv -c -f UTF-8 -t UTF-8 2>/dev/null | tr -d '\000-\037\177/')
  [ -n "$name" ] && [ "$name" != . ] && [ "$name" != .. ] || name=student-$i
  if grep -Fxq -- "$name" "$work/rows/names"; then
    printf 'grade: %s: the student %s already has a submission: skipped\n' "$base" "$name" >&2
    continue
  fi
  now=$(date +%s)
  if [ $done_n -gt 0 ]; then
    left=$(( (now - start) * (m - i + 1) / done_n ))
    left="about $((left / 60)) min $((left % 60)) s left"
  else left="time left not known yet"; fi
  printf 'grade: %s of %s, %s, %s\n' "$i" "$m" "$name" "$left" >&2
  notes=$work/notes
  results=$work/results.tsv
  feedback=$work/feedback.md
  cases=$work/cases/$i
  : >"$notes"
  : >"$results"
  : >"$feedback"
  mkdir -p "$cases"
  [ "$name" = "$raw" ] ||
    note "the entry's name is not valid UTF-8 or has control characters: graded as $name"
  grade_one "$entry" "$kind"
  [ $interrupted = 0 ] || break
  # The student's outputs, each written whole then renamed.
  iconv -c -f UTF-8 -t UTF-8 <"$results" >"$results.utf8" 2>/dev/null
  notes_esc=$(esc "$(cat "$notes")")
  [ -s "$notes" ] || notes_esc=""
  NAME=$name NOTES=$notes_esc JSON=$out/results/$name.json.tmp \
    awk -v row="$work/row" -v srow="$work/srow" -f "$here/student.awk" \
    "$work/weights.tsv" "$work/exercises.tsv" "$results.utf8" ||
    die "the results of $name could not be written"
  mv "$out/results/$name.json.tmp" "$out/results/$name.json"
  {
    printf '# Exercises of %s\n' "$name"
    echo
    echo "$(sed 's/.*,//' "$work/row") of $max points (gradebook.csv has each exercise's)."
    if [ -s "$notes" ]; then echo; sed 's/^/- /' "$notes"; fi
    echo
    echo '```'
    cat "$feedback"
    echo '```'
  } >"$out/feedback/$name.md.tmp"
  mv "$out/feedback/$name.md.tmp" "$out/feedback/$name.md"
  cat "$work/row" >>"$work/rows/gradebook"
  cat "$work/srow" >>"$work/rows/statuses"
  awk -F '\t' -v name="$name" '{ print name "\t" $0 }' "$results.utf8" >>"$work/rows/all.tsv"
  printf '%s\n' "$name" >>"$work/rows/names"
  done_n=$((done_n + 1))
  publish ""
done <"$list"

if [ $interrupted = 1 ]; then
  publish "Stopped by Ctrl-C after $done_n of $m entries: the students after them are not graded."
  echo "grade: stopped after $done_n of $m entries: $out/gradebook.csv has their rows" >&2
  exit 130
fi
took=$(($(date +%s) - start))
echo "grade: $done_n of $m entries graded in $took s ($((took / (done_n > 0 ? done_n : 1))) s a submission, after $built s for the library and the checkers): $out/gradebook.csv, class.md, feedback/, results/" >&2
