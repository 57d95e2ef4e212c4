#!/bin/sh
# ctest grade.class: make grade's script (tests/grade/grade.sh) on a small class made here from
# lesson 1's solutions and stubs, graded on lesson 1 only (LESSONS=1) in an exercise tree that
# is already built (make test's, tests/student-config: TREE=), so that only the students' code
# is compiled:
#   alice        a folder, the solutions; and a symbolic link helper.cpp -> /etc/passwd
#                (left out, or she would not compile)
#   bob.tar.gz   half done: 1.5 to 1.9 still throw NotDone; and a file whose name is not
#                UTF-8 (left out)
#   carol        a git repository, the solutions with the planted mistake 1.2/transpose of the
#                checker (tests/exercises/01-spatial-notation.cpp): class.md must count it
#   dave         a folder whose code does not compile
#   erin         a folder with no exercises/
#   mallory.zip  a zip with an entry ../../x: refused, and the grader goes on
# and the hostile ones, each the solutions with:
#   frank        an endless loop in 1.1: 1.1 timed out, the rest pass
#   grace        exit(0) from a static initializer: every exercise crashed (never judged)
#   heidi        a static initializer that writes into the project, OUT, the submissions and
#                ../, reads the solutions and /etc/shadow, opens a network connection: none of
#                it works (the sandbox), every exercise passes
#   ivan         a fork bomb in 1.1: 1.1 timed out (the process limit holds it), the rest pass
#   judy         1.1 wrong, and a static initializer and a static destructor that print pass
#                lines and write a results file of passes into its scratch folder, and weak
#                definitions of the checker's Check::add and Check::fail that say "pass":
#                1.1 FAIL
#   kevin, liam  _exit(0), abort() from a static initializer: every exercise crashed
#   rita         in 1.1, writes a passing row into every file her process can write (the
#                runner's own channel from the exercise's process among them), then _exit(0):
#                before the judge, 1.1 passed; now it crashed, "not judged"
#   tess         in 1.6, calls soa::Phi::matrix, which 1.6 reproduces, then clears the
#                watch's flags in her process: calls the function it reproduces (the build
#                found the call)
#   mona         in 1.2 an allocation of 10 GB (out of memory), in 1.3 1 GB of output (stopped
#                at the output limit), in 1.4 a SIGSEGV handler that returns, then a segfault
#                (timed out), in 1.6 a call of soa::Phi::matrix, which 1.6 reproduces
#   nick         defines main: does not compile (the runner has its own)
#   olga         1.1 wrong, and strong definitions of the checker's Check::add and Check::fail
#                (asm labels) that say "pass": does not compile, naming them
#   uma          #includes the solutions file by its path, and /etc/shadow: does not compile
#                (the compile is sandboxed too), neither file's text in her feedback
# and the planted ones: patty has one planted mistake of the checker's in each exercise, quinn
# the two that are left (every kind of lesson 1's catalogue; carol's 1.2 transpose too), and
# class.md must count each.
# And Gradescope's run_autograder on alice's work, and on a grader that fails; and a class of
# two graded with the instructor's cases (SEEDS), one of whom learnt the students' by heart,
# and he again through run_autograder with the seeds.
# Then: the gradebook's rows (with WEIGHTS: 1.2 counts 3), the statuses, class.md's counts,
# the feedback, every results/*.json in Gradescope's format (gradescope_check.cmake), nothing
# written outside OUT, and the one-line refusals (a sandbox that cannot start, a bad weights
# line). heidi, ivan and uma only where the sandbox starts: without it they would do what they try.
#   grade_check.sh <source dir> <exercise tree> <scratch dir>
set -u
src=$1
tree=$2
scratch=$3
here=$(cd "$(dirname "$0")" && pwd)
fail=0
check() {  # <what> <command...>: the command must succeed
  what=$1
  shift
  if "$@"; then echo "ok: $what"; else echo "FAIL: $what"; fail=1; fi
}

rm -rf "$scratch"
mkdir -p "$scratch/subs" "$scratch/make"
subs=$scratch/subs
out=$scratch/out
lesson=$(cd "$src/exercises" && ls -d 01-*)
solution=$(ls "$src/solutions/$lesson/"*.cpp | head -1)
stub=$src/exercises/$lesson/exercises.cpp
[ -f "$solution" ] && [ -f "$stub" ] && [ -f "$tree/CMakeCache.txt" ] ||
  { echo "FAIL: needs $src/solutions/$lesson, its stub and the exercise tree $tree"; exit 1; }
# The grader grades a lesson a submission lacks on its stubs: they must be as shipped.
if ! (cd "$src" && grep -F " exercises/$lesson/exercises.cpp" tests/exercises/stubs.sha256 |
  sha256sum -c --quiet >/dev/null 2>&1); then
  echo "skipped: exercises/$lesson/exercises.cpp is not the stub as shipped (your work?)"
  exit 0
fi

# alice
mkdir -p "$subs/alice/exercises/$lesson"
cp "$solution" "$subs/alice/exercises/$lesson/exercises.cpp"
ln -s /etc/passwd "$subs/alice/exercises/$lesson/helper.cpp"

# bob: the second half of the lesson not done (a throw first in each of those functions).
mkdir -p "$scratch/make/bob/exercises/$lesson"
half=$(sed -n 's/.*NotDone("\(1\.[5-9] [a-z_0-9]*\)").*/\1/p' "$stub")
[ "$(printf '%s\n' "$half" | wc -l)" = 5 ] || { echo "FAIL: the stub of 1.5 to 1.9 changed"; exit 1; }
awk -v half="$half" '
  BEGIN { n = split(half, f, "\n") }
  { print }
  /#include "exercises.hpp"/ { print "#include \"not_done.hpp\"" }
  /^[A-Za-z].*\) \{$/ {
    for (i = 1; i <= n; i++) if (index($0, " " substr(f[i], 5) "(")) print "  throw exercise::NotDone(\"" f[i] "\");" }
' "$solution" >"$scratch/make/bob/exercises/$lesson/exercises.cpp"
printf 'int not_taken;\n' >"$scratch/make/bob/exercises/$lesson/$(printf 'caf\351').cpp"
tar -czf "$subs/bob.tar.gz" -C "$scratch/make/bob" exercises

# The planted mistakes of the checker (tests/exercises/NN-topic.cpp, tests/exercises/plant.cmake):
# plant_field <exercise> <id> <FIND|WRONG|TYPE|EXPECT|NAMED> prints the field's text.
plant_field() {
  awk -v head="soa_plant($1 $2" -v key="$3" '$0 == head { on = 1; next }
    on && /^soa_plant\(/ { exit }
    on && index($0, key " [=[") { s = substr($0, index($0, key " [=[") + length(key) + 4)
      sub(/\]=\].*/, "", s); print s; exit }' "$src/tests/exercises/$lesson.cpp"
}
# planted <student> <exercise>/<id>...: the solutions with each mistake in place, as
# plant.cmake writes it (its FIND text replaced by TYPE(WRONG)).
planted() {
  who=$1
  shift
  mkdir -p "$subs/$who/exercises/$lesson"
  cp "$solution" "$scratch/planting"
  for p in "$@"; do
    find_text=$(plant_field "${p%%/*}" "${p#*/}" FIND)
    wrong_text=$(plant_field "${p%%/*}" "${p#*/}" WRONG)
    type_text=$(plant_field "${p%%/*}" "${p#*/}" TYPE)
    [ -n "$find_text" ] && [ -n "$wrong_text" ] ||
      { echo "FAIL: no planted mistake $p in tests/exercises/$lesson.cpp"; exit 1; }
    awk -v find="$find_text" -v wrong="$type_text($wrong_text)" '{
        at = index($0, find)
        if (at) { $0 = substr($0, 1, at - 1) wrong substr($0, at + length(find)); n++ }
        print }
      END { if (n != 1) exit 1 }' "$scratch/planting" >"$scratch/planting.new" ||
      { echo "FAIL: the FIND text of $p is not once in $solution"; exit 1; }
    mv "$scratch/planting.new" "$scratch/planting"
  done
  mv "$scratch/planting" "$subs/$who/exercises/$lesson/exercises.cpp"
}
# carol: the planted mistake 1.2/transpose, in a git repository.
planted carol 1.2/transpose
git -C "$subs/carol" init -q &&
  git -C "$subs/carol" add exercises &&
  git -C "$subs/carol" -c user.name=carol -c user.email=carol@example.org commit -q -m work ||
  { echo "FAIL: could not make carol's git repository"; exit 1; }

# The class is graded in the sandbox where this machine can start it (bwrap installed, user
# namespaces allowed), else with UNSAFE=1, saying so.
sandboxed=1
unsafe=""
if ! bwrap --unshare-all --ro-bind / / true 2>/dev/null &&
  ! setpriv --reuid=65534 --regid=65534 --clear-groups bwrap --unshare-all --ro-bind / / true 2>/dev/null; then
  echo "note: bubblewrap cannot start here: the class is graded with UNSAFE=1, the sandbox's checks left out"
  sandboxed=""
  unsafe=1
fi

# The hostile students: the solutions with <code> after the #include of exercises.hpp and
# <body> first in apply_phi (1.1).
hostile() {  # <student> <code> <body>
  mkdir -p "$subs/$1/exercises/$lesson"
  CODE=$2 BODY=$3 awk '{ print }
    /#include "exercises.hpp"/ { print ENVIRON["CODE"] }
    /^Force apply_phi\(/ { print ENVIRON["BODY"] }' "$solution" \
    >"$subs/$1/exercises/$lesson/exercises.cpp"
}
hostile frank "" "  for (volatile unsigned spin = 0;; spin = spin + 1u) {}"
hostile grace "#include <cstdlib>
static const int quits = (std::exit(0), 0);" ""
[ -z "$sandboxed" ] || hostile heidi "#include <cstdio>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>
static int tries() {
  for (const char* p : {\"$src/HACKED\", \"$out/HACKED\", \"$subs/HACKED\", \"../HACKED\",
                        \"$scratch/HACKED\"})
    if (std::FILE* f = std::fopen(p, \"w\")) { std::fclose(f); std::printf(\"WROTE %s\\n\", p); }
  for (const char* p : {\"$solution\", \"/etc/shadow\"})
    if (std::FILE* f = std::fopen(p, \"r\")) { std::fclose(f); std::printf(\"READ %s\\n\", p); }
  const int s = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(80);
  a.sin_addr.s_addr = htonl(0x01010101);
  if (s >= 0 && connect(s, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0) std::printf(\"CONNECTED\\n\");
  if (s >= 0) close(s);
  return 0;
}
static const int tried = tries();" ""
[ -z "$sandboxed" ] || hostile ivan "#include <unistd.h>" "  for (;;) fork();"
# uma: her lesson 1 is the solutions file, #included by its path, and a second file #includes
# /etc/shadow. The compile runs in the sandbox, which shows neither.
if [ -n "$sandboxed" ]; then
  mkdir -p "$subs/uma/exercises/$lesson"
  printf '#include "%s"\n' "$solution" >"$subs/uma/exercises/$lesson/exercises.cpp"
  printf '#include "/etc/shadow"\n' >"$subs/uma/exercises/$lesson/peek.cpp"
fi
# The checker's Check::add (each instantiation) and Check::fail, as its object file names them:
# a student's definitions of these, through asm labels, answer "pass" for every comparison.
checker_object=$(ls "$tree/tests/CMakeFiles/ex01-tests.dir/exercises/"*.o 2>/dev/null | head -1)
says_pass() {  # <attributes>: C++ defining every such symbol to say "pass"
  nm "$checker_object" 2>/dev/null | awk -v attr="$1" '$2 == "W" && $3 ~ /^_ZN3soa4test5Check(3add|4failEj$)/ {
    n++
    if ($3 ~ /4failEj$/) print attr "void says_pass_" n "() asm(\"" $3 "\");\n" attr "void says_pass_" n "() {}"
    else print attr "bool says_pass_" n "() asm(\"" $3 "\");\n" attr "bool says_pass_" n "() { return true; }" }'
}
[ -n "$(says_pass "")" ] ||
  { echo "FAIL: no Check::add or Check::fail in the checker's object file $checker_object"; exit 1; }
hostile judy "#include <cstdio>
static int fake() {
  std::printf(\"1.1 apply_phi pass\\n[  PASSED  ] 9 tests.\\n\");
  if (std::FILE* f = std::fopen(\"lesson.tsv\", \"w\")) {
    std::fputs(\"1.1\\tapply_phi\\tpass\\t\\n\", f);
    std::fclose(f);
  }
  return 0;
}
static const int faked = fake();
struct Again {  // and once more, after the runner has written its file
  ~Again() { fake(); }
};
static Again again;
$(says_pass "__attribute__((weak)) ")" "  return Force(f_y.linear(), f_y.angular());"
hostile olga "$(says_pass "")" "  return Force(f_y.linear(), f_y.angular());"
hostile nick "int main() { return 0; }" ""
hostile kevin "#include <unistd.h>
static const int quits = (_exit(0), 0);" ""
hostile liam "#include <cstdlib>
static const int aborts = (std::abort(), 0);" ""
hostile rita "#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>" "  for (int fd = 3; fd < 1024; ++fd) {
    const int flags = fcntl(fd, F_GETFL);
    struct stat st;
    if (flags < 0 || (flags & O_ACCMODE) == O_RDONLY || fstat(fd, &st) != 0 ||
        !S_ISREG(st.st_mode) || ftruncate(fd, 0) != 0 || lseek(fd, 0, SEEK_SET) != 0)
      continue;
    const char row[] = \"0 0 0 0\\n\";
    if (write(fd, row, sizeof row - 1) < 0) continue;
  }
  _exit(0);"
# mona: four exercises, each hostile in its own way.
mkdir -p "$subs/mona/exercises/$lesson"
awk '{ print }
  /#include "exercises.hpp"/ { print "#include <csignal>\n#include <cstdint>\n#include <cstdio>\n#include <vector>" }
  /^Acceleration spatial_cross\(/ {
    print "  {\n    std::vector<char> ten_gb(std::size_t(10) << 30, 1);"
    print "    if (ten_gb[std::size_t(7) << 30] != 1) return {};\n  }" }
  /^SpatialInertia parallel_axis\(/ {
    print "  for (long i = 0; i < (1L << 24); ++i)  // 1 GB"
    print "    std::fputs(\"0123456789012345678901234567890123456789012345678901234567890123\\n\", stdout);" }
  /^UnitQuaternion quaternion_from_axis_angle\(/ {
    print "  std::signal(SIGSEGV, [](int) {});"
    print "  *reinterpret_cast<volatile int*>(std::uintptr_t(64)) = 1;" }
  /^Velocity reverse_velocity\(/ { print "  (void)phi_xy.matrix();" }' "$solution" \
  >"$subs/mona/exercises/$lesson/exercises.cpp"
[ "$(grep -c -E 'ten_gb|1 GB|SIGSEGV|phi_xy.matrix' "$subs/mona/exercises/$lesson/exercises.cpp")" = 5 ] ||
  { echo "FAIL: mona's functions 1.2, 1.3, 1.4 and 1.6 are not in $solution"; exit 1; }
# tess: 1.6 calls soa::Phi::matrix, which it reproduces, then clears the watch's flags.
mkdir -p "$subs/tess/exercises/$lesson"
awk '{ print }
  /#include "exercises.hpp"/ { print "extern \"C\" unsigned char soa_watch_hit[];\nextern \"C\" const int soa_watch_count;" }
  /^Velocity reverse_velocity\(/ {
    print "  (void)phi_xy.matrix();"
    print "  for (int i = 0; i < soa_watch_count; ++i) soa_watch_hit[i] = 0;" }' "$solution" \
  >"$subs/tess/exercises/$lesson/exercises.cpp"
grep -q 'soa_watch_hit\[i\] = 0' "$subs/tess/exercises/$lesson/exercises.cpp" ||
  { echo "FAIL: tess's 1.6 is not in $solution"; exit 1; }
# patty and quinn: every planted mistake of lesson 1's checker, one in each exercise: patty has
# the first of each exercise, quinn the second.
sed -n 's|^soa_plant(\(1\.[0-9]*\) \([a-z0-9-]*\)$|\1/\2|p' "$src/tests/exercises/$lesson.cpp" >"$scratch/plants"
patty=$(awk -F/ '!($1 in n) { n[$1]; print }' "$scratch/plants")
quinn=$(awk -F/ '++n[$1] == 2' "$scratch/plants")
[ -z "$(awk -F/ '++n[$1] == 3' "$scratch/plants")" ] ||
  { echo "FAIL: an exercise of lesson 1 has three planted mistakes: add a student for the third"; exit 1; }
# shellcheck disable=SC2086
planted patty $patty
# shellcheck disable=SC2086
planted quinn $quinn

# dave, erin
mkdir -p "$subs/dave/exercises/$lesson" "$subs/erin"
{ cat "$stub"; echo "int broken = ;"; } >"$subs/dave/exercises/$lesson/exercises.cpp"
echo "my notes" >"$subs/erin/README.txt"

# mallory: a zip whose one entry is ../../x (stored, empty: every field is known).
{
  printf 'PK\003\004\024\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\007\000\000\000../../x'
  printf 'PK\001\002\024\000\024\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\007\000'
  printf '\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000\000../../x'
  printf 'PK\005\006\000\000\000\000\001\000\001\000\065\000\000\000\045\000\000\000\000\000'
} >"$subs/mallory.zip"

printf '# 1.2 counts three\n1.2 3\n' >"$scratch/weights"
touch "$scratch/stamp"
sleep 1

# The refusals: one line, non-zero, nothing written. A bwrap that cannot start (as where user
# namespaces are disabled): the grader stops, naming the sandbox.
mkdir -p "$scratch/nobwrap"
printf '#!/bin/sh\necho "bwrap: No permissions to create new namespace" >&2\nexit 1\n' \
  >"$scratch/nobwrap/bwrap"
chmod +x "$scratch/nobwrap/bwrap"
msg=$(PATH=$scratch/nobwrap:$PATH sh "$here/grade.sh" "$src" "$subs" "$scratch/refused" 2>&1)
rc=$?
check "a sandbox that cannot start: one line naming it, exit non-zero" \
  test $rc != 0 -a "$(printf '%s\n' "$msg" | wc -l)" = 1 -a ! -e "$scratch/refused/gradebook.csv"
case "$msg" in *"sandbox cannot start"*"No permissions"*UNSAFE=1*) ;; *) echo "FAIL: the refusal says: $msg"; fail=1 ;; esac
printf '1.2 three\n' >"$scratch/bad-weights"
msg=$(UNSAFE=1 LESSONS=1 TREE=$tree sh "$here/grade.sh" "$src" "$subs" "$scratch/refused" \
  "$scratch/bad-weights" 2>&1)
rc=$?
check "a bad weights line: one line naming the file and line, exit non-zero" \
  test $rc != 0 -a "$(printf '%s\n' "$msg" | wc -l)" = 1
case "$msg" in *"$scratch/bad-weights:1:"*) ;; *) echo "FAIL: the bad weights say: $msg"; fail=1 ;; esac

# The class.
UNSAFE=$unsafe LESSONS=1 TREE=$tree JOBS=${JOBS:-2} sh "$here/grade.sh" "$src" "$subs" "$out" \
  "$scratch/weights" 2>"$scratch/grade.err"
rc=$?
cat "$scratch/grade.err"
check "the grader finishes (exit 0)" test $rc = 0

row() { grep "^$1," "$out/gradebook.csv"; }
expect_row() {  # <student> <row>
  got=$(row "$1")
  if [ "$got" = "$2" ]; then echo "ok: $1's row"; else
    echo "FAIL: $1's row is \"$got\", not \"$2\""; fail=1; fi
}
check "the gradebook's header" test "$(head -1 "$out/gradebook.csv")" = \
  "student,1.1,1.2,1.3,1.4,1.5,1.6,1.7,1.8,1.9,total"
expect_row alice "alice,1,3,1,1,1,1,1,1,1,11"
expect_row bob "bob,1,3,1,1,0,0,0,0,0,6"
expect_row carol "carol,1,0,1,1,1,1,1,1,1,8"
expect_row dave "dave,0,0,0,0,0,0,0,0,0,0"
expect_row erin "erin,0,0,0,0,0,0,0,0,0,0"
expect_row mallory "mallory,0,0,0,0,0,0,0,0,0,0"
expect_row frank "frank,0,3,1,1,1,1,1,1,1,10"
expect_row grace "grace,0,0,0,0,0,0,0,0,0,0"
if [ -n "$sandboxed" ]; then
  expect_row heidi "heidi,1,3,1,1,1,1,1,1,1,11"
  expect_row ivan "ivan,0,3,1,1,1,1,1,1,1,10"
  expect_row uma "uma,0,0,0,0,0,0,0,0,0,0"
fi
expect_row judy "judy,0,3,1,1,1,1,1,1,1,10"
expect_row kevin "kevin,0,0,0,0,0,0,0,0,0,0"
expect_row liam "liam,0,0,0,0,0,0,0,0,0,0"
expect_row rita "rita,0,3,1,1,1,1,1,1,1,10"
expect_row tess "tess,1,3,1,1,1,0,1,1,1,10"
expect_row mona "mona,1,0,0,0,1,0,1,1,1,5"
expect_row nick "nick,0,0,0,0,0,0,0,0,0,0"
expect_row olga "olga,0,0,0,0,0,0,0,0,0,0"
failing_row() {  # <student> <exercise>/<id>...: the row with those exercises failed
  who=$1
  shift
  r=$who
  total=0
  for e in 1.1 1.2 1.3 1.4 1.5 1.6 1.7 1.8 1.9; do
    p=1
    [ $e != 1.2 ] || p=3
    for f in "$@"; do [ "${f%%/*}" != $e ] || p=0; done
    r=$r,$p
    total=$((total + p))
  done
  echo "$r,$total"
}
# shellcheck disable=SC2086
expect_row patty "$(failing_row patty $patty)"
# shellcheck disable=SC2086
expect_row quinn "$(failing_row quinn $quinn)"
students=18
[ -z "$sandboxed" ] || students=21
check "a row per student" test "$(wc -l <"$out/gradebook.csv")" = $((students + 1))
srow() { grep "^$1," "$out/statuses.csv"; }
check "bob: 1.5 to 1.9 not done" \
  test "$(srow bob)" = "bob,pass,pass,pass,pass,not done,not done,not done,not done,not done"
check "carol: 1.2 FAIL" test "$(srow carol | cut -d, -f3)" = FAIL
check "dave: does not compile" test "$(srow dave | cut -d, -f2)" = "does not compile"
check "frank: 1.1 timed out" test "$(srow frank | cut -d, -f2)" = "timed out"
check "grace: 1.1 crashed" test "$(srow grace | cut -d, -f2)" = "crashed"
check "judy: 1.1 FAIL (her weak Check::add and Check::fail are not the ones linked)" \
  test "$(srow judy | cut -d, -f2)" = FAIL
check "kevin (_exit): every exercise crashed" \
  test "$(srow kevin)" = "kevin,crashed,crashed,crashed,crashed,crashed,crashed,crashed,crashed,crashed"
check "liam (abort): every exercise crashed" \
  test "$(srow liam)" = "liam,crashed,crashed,crashed,crashed,crashed,crashed,crashed,crashed,crashed"
check "rita: 1.1 crashed, not judged (her forged row is not the verdict)" \
  test "$(srow rita | cut -d, -f2)" = crashed
check "rita's feedback: the judge's verdict" grep -q "1.1: crashed: not judged: " "$out/feedback/rita.md"
check "tess: 1.6 calls the function it reproduces (the build found the call; she cleared the run's flags)" \
  test "$(srow tess | cut -d, -f7)" = "calls the function it reproduces"
check "mona: 10 GB out of memory, 1 GB of output stopped, a SIGSEGV handler timed out, a forbidden call" \
  test "$(srow mona)" = "mona,pass,out of memory,crashed (SIGXFSZ),timed out,pass,calls the function it reproduces,pass,pass,pass"
check "mona's feedback: the output limit named" grep -q 'printed more than 64 MB' "$out/feedback/mona.md"
check "nick: does not compile, his main named" grep -q 'error: your code defines main()' "$out/feedback/nick.md"
check "olga: does not compile, the checker's Check::add named" \
  grep -q 'error: your code defines bool soa::test::Check::add<' "$out/feedback/olga.md"
# Each planted mistake counted in class.md: a mistake the checker names, by its name (NAMED,
# else EXPECT: the grader reads every hint), once per student who has it; a symptom by its
# words; else the exercise's FAIL.
for p in 1.2/transpose $patty $quinn; do echo "$p"; done | sort | uniq -c >"$scratch/plant-counts"
while read -r count p; do
  e=${p%%/*}
  says=$(plant_field "$e" "${p#*/}" NAMED)
  [ -n "$says" ] || says=$(plant_field "$e" "${p#*/}" EXPECT)
  name=$(printf '%s\n' "$says" | sed -n 's/.*likely mistake \\(\([^\\]*\)\\).*/\1/p')
  symptom=$(printf '%s\n' "$says" | sed -n 's/.*symptom: \([^\\[(]*\).*/\1/p')
  e_re=$(echo "$e" | sed 's/\./\\./')
  if [ -n "$name" ]; then
    check "class.md counts $p: $count of $students, likely mistake ($name)" \
      grep -q "^- $e_re ([^)]*): $count of $students — likely mistake ($name)" "$out/class.md"
  elif [ -n "$symptom" ]; then
    check "class.md counts $p: the symptom \"$symptom\"" \
      sh -c 'grep "^- $1 (" "$3" | grep -qF -- " — symptom: $2"' - "$e_re" "$symptom" "$out/class.md"
  else
    check "class.md counts $p: a FAIL of $e" grep -q "^| $e_re [^|]* | [0-9]* | [1-9]" "$out/class.md"
  fi
done <"$scratch/plant-counts"
if [ -n "$sandboxed" ]; then
  check "ivan: 1.1 timed out" test "$(srow ivan | cut -d, -f2)" = "timed out"
  check "heidi: nothing written, read or connected from the sandbox" \
    test -z "$(grep -E '^ *(WROTE|READ /work|READ [^ ]*solutions|READ /etc/shadow|CONNECTED)' "$out/feedback/heidi.md")"
  check "heidi: no HACKED file anywhere" \
    test ! -e "$src/HACKED" -a ! -e "$out/HACKED" -a ! -e "$subs/HACKED" -a ! -e "$scratch/HACKED"
  check "uma: does not compile, the solutions not found by her #include" \
    sh -c 'test "$(grep "^uma," "$1" | cut -d, -f2)" = "does not compile" &&
      grep -qF "$2: No such file or directory" "$3"' - "$out/statuses.csv" "$solution" "$out/feedback/uma.md"
  check "the sandboxed compiles keep their ccache in OUT/.work/ccache" \
    test -n "$(find "$out/.work/ccache" -type f -name '*R' 2>/dev/null | head -1)"
  check "uma: no line of /etc/shadow in her feedback" \
    sh -c '! grep -qE "(^|[ :])(root|daemon|nobody):[^ :]*:[0-9]*:" "$1"' - "$out/feedback/uma.md"
fi
passed=5
[ -z "$sandboxed" ] || passed=6
check "class.md: 1.1 passes for $passed of $students" grep -q "^| 1\\.1 [^|]* | $passed | " "$out/class.md"
check "class.md: nobody left out an exercise" grep -q '^None: every exercise was attempted' "$out/class.md"
check "erin's feedback: no exercises/ folder" grep -q 'no exercises/ folder' "$out/feedback/erin.md"
check "mallory's feedback: refused, naming the entry" grep -q 'refused: .*\.\./\.\./x' "$out/feedback/mallory.md"
check "alice's feedback: the link left out" grep -q 'helper.cpp: not a regular file' "$out/feedback/alice.md"
check "bob's feedback: the non-UTF-8 file name left out" grep -q 'is left out' "$out/feedback/bob.md"
check "dave's feedback: the compiler's error" grep -q 'error' "$out/feedback/dave.md"
check "carol's feedback: the table of make exercises naming the mistake" \
  grep -q 'likely mistake (transpose)' "$out/feedback/carol.md"
n_json=$(ls "$out/results/"*.json | wc -l)
check "a results.json per student" test "$n_json" = $students
check "every results.json in Gradescope's format" \
  cmake "-DFILES=$(ls "$out/results/"*.json | tr '\n' ';')" -P "$here/gradescope_check.cmake"
check "alice's results.json: score 11" grep -q '"score": 11,' "$out/results/alice.json"
check "nothing written outside OUT: no ../../x" \
  test ! -e "$out/x" -a ! -e "$scratch/x" -a ! -e "$out/.work/x" -a ! -e "$(dirname "$scratch")/x"
check "nothing written into the submissions" test -z "$(find "$subs" -newer "$scratch/stamp" ! -type l)"
check "no partial file left (*.tmp)" test -z "$(find "$out" -name '*.tmp' ! -path '*/.work/*')"
# Gradescope's run_autograder (tests/grade/gradescope/) on alice's work, AUTOGRADER standing
# for /autograder and this test's exercise tree for setup.sh's; then with a grader that
# fails (no lesson 99): a results.json that says so, never none.
ag=$scratch/ag
mkdir -p "$ag/submission"
cp -R "$subs/alice/exercises" "$ag/submission/"
ln -s "$src" "$ag/source"
AUTOGRADER=$ag LESSONS=1 TREE=$tree sh "$src/tests/grade/gradescope/run_autograder" 2>"$scratch/ag.err"
check "run_autograder: results.json, score 9" grep -q '"score": 9,' "$ag/results/results.json"
cp "$ag/results/results.json" "$scratch/ag-alice.json"
AUTOGRADER=$ag LESSONS=99 sh "$src/tests/grade/gradescope/run_autograder" 2>/dev/null
check "run_autograder, the grader failing: results.json naming the reason" \
  grep -q '"output": "The autograder could not grade this submission: .*lesson 99' "$ag/results/results.json"
check "run_autograder's results.json files in Gradescope's format" \
  cmake "-DFILES=$scratch/ag-alice.json;$ag/results/results.json" -P "$here/gradescope_check.cmake"
check "the progress lines: N of M, the student, the time left" \
  grep -q "^grade: 3 of $students, carol, about [0-9]* min [0-9]* s left\$" "$scratch/grade.err"

# The instructor's cases (SEEDS=FILE). sam has learnt 1.4's cases by heart: his answer is right
# for every (n, theta) the checker draws, and half-angle-less for any other. The inputs are
# those a first student, rec, met: her 1.4 writes each into its scratch folder.
mkdir -p "$scratch/rec/rec/exercises/$lesson" "$scratch/seeded/sam/exercises/$lesson" \
  "$scratch/seeded/alice/exercises/$lesson"
cp "$solution" "$scratch/seeded/alice/exercises/$lesson/exercises.cpp"
at='  return UnitQuaternion(std::sin(half) * unit, std::cos(half));'
grep -qxF "$at" "$solution" || { echo "FAIL: 1.4's last line in $solution is not: $at"; exit 1; }
AT=$at awk '$0 == ENVIRON["AT"] {
    print "  if (std::FILE* f = std::fopen(\"inputs.txt\", \"a\")) {"
    print "    std::fprintf(f, \"{%.17g, %.17g, %.17g, %.17g},\\n\", n.x(), n.y(), n.z(), theta);"
    print "    std::fclose(f);\n  }" }
  { print } /#include "exercises.hpp"/ { print "#include <cstdio>" }' "$solution" \
  >"$scratch/rec/rec/exercises/$lesson/exercises.cpp"
UNSAFE=$unsafe LESSONS=1 TREE=$tree sh "$here/grade.sh" "$src" "$scratch/rec" "$scratch/rec-out" \
  2>/dev/null
inputs=$scratch/rec-out/.work/cases/1/01/inputs.txt
check "rec: the inputs of 1.4 written" test -s "$inputs"
AT=$at awk 'FILENAME == ARGV[1] { known = known "      " $0 "\n"; next }
  $0 == ENVIRON["AT"] {
    print "  static const double known[][4] = {\n" known "  };"
    print "  bool seen = false;"
    print "  for (const auto& k : known)"
    print "    seen = seen || (k[0] == n.x() && k[1] == n.y() && k[2] == n.z() && k[3] == theta);"
    print "  if (!seen) return UnitQuaternion(std::sin(theta) * unit, std::cos(theta));" }
  { print }' "$inputs" "$solution" >"$scratch/seeded/sam/exercises/$lesson/exercises.cpp"
printf '# the instructor'"'"'s\n2027\n' >"$scratch/seeds"
UNSAFE=$unsafe LESSONS=1 TREE=$tree SEEDS=$scratch/seeds sh "$here/grade.sh" "$src" \
  "$scratch/seeded" "$scratch/seeded-out" 2>"$scratch/seeded.err"
check "SEEDS: the grader finishes" test $? = 0
seeded=$scratch/seeded-out
check "SEEDS: alice passes every exercise on the instructor's cases too" \
  test "$(grep '^alice,' "$seeded/gradebook.csv")" = "alice,1,1,1,1,1,1,1,1,1,9"
check "SEEDS: sam passes 1.4 on the students' cases" \
  grep -q '^  1\.4 .* pass$' "$seeded/feedback/sam.md"
check "SEEDS: sam fails 1.4 on the instructor's, and only 1.4" \
  test "$(grep '^sam,' "$seeded/statuses.csv")" = "sam,pass,pass,pass,FAIL,pass,pass,pass,pass,pass"
check "SEEDS: sam's 1.4 says it failed on the instructor's cases" \
  grep -q "with the instructor's cases (seed 2027)" "$seeded/results/sam.json"
# Gradescope with the instructor's cases (SEEDS, which a seeds.txt in the autograder's source
# stands for), on sam: his 1.4 fails on them.
rm -rf "$ag/submission" "$ag/results"
mkdir -p "$ag/submission"
cp -R "$scratch/seeded/sam/exercises" "$ag/submission/"
AUTOGRADER=$ag LESSONS=1 TREE=$tree SEEDS=$scratch/seeds \
  sh "$src/tests/grade/gradescope/run_autograder" 2>/dev/null
check "run_autograder with the instructor's seeds: sam's 1.4 fails on their cases (score 8)" \
  sh -c 'grep -q "\"score\": 8," "$1" && grep -q "with the instructor.s cases (seed 2027)" "$1"' \
  - "$ag/results/results.json"
printf '2027\nseven\n' >"$scratch/bad-seeds"
msg=$(UNSAFE=1 LESSONS=1 TREE=$tree SEEDS=$scratch/bad-seeds sh "$here/grade.sh" "$src" \
  "$scratch/seeded" "$scratch/refused" 2>&1)
rc=$?
check "a bad seeds line: one line naming the file and line, exit non-zero" \
  test $rc != 0 -a "$(printf '%s\n' "$msg" | wc -l)" = 1
case "$msg" in *"$scratch/bad-seeds:2:"*) ;; *) echo "FAIL: the bad seeds say: $msg"; fail=1 ;; esac
exit $fail
