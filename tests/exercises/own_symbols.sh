#!/bin/sh
# A student's code defines only its own symbols: run before the link of each checker program
# of a student's code (make exercises, make grade, the probes; soa_link_student() in
# tests/CMakeLists.txt), it refuses the code, as a compile error, when it defines
#   - main: the runner's program has its own;
#   - a strong symbol that the program's other parts also define: the checker, the runner,
#     the library, Google Test, or the C and C++ runtime. A strong definition replaces a weak
#     one (an inline function, a template): the checker's Check::add made to say "pass", say,
#     through an asm label;
#   - a weak symbol that the C and C++ runtime exports, other than the weak copies of the
#     standard library's templates every program has (std::, __gnu_cxx::): it would replace
#     the runtime's (fopen, rename, operator new) for the checker and the runner too.
# A weak symbol that the checker, the runner, the library or Google Test also define is left:
# the link puts them first, and the first definition of a weak symbol is the one kept.
#   own_symbols.sh <nm> <c++filt> <student archive> <object, archive or shared library>...
set -u
nm=$1
filt=$2
student=$3
shift 3

# The other parts' defined symbols: <name>\t<file>, the shared libraries' marked "so".
for f in "$@"; do
  case "$f" in
    *.so | *.so.*)
      "$nm" -D --defined-only "$f" 2>/dev/null |
        awk -v f="${f##*/}" 'NF >= 3 { n = $3; sub(/@.*/, "", n); print n "\t" f "\tso" }' ;;
    *)
      "$nm" -g --defined-only "$f" 2>/dev/null |
        awk -v f="${f##*/}" 'NF >= 3 { print $3 "\t" f "\tstatic" }' ;;
  esac
done >"$student.others" || exit 1

# The student's defined global symbols: <member>\t<type>\t<name>\t<demangled name>.
"$nm" -g --defined-only "$student" 2>/dev/null |
  awk '/^[^ ]+\.o:$/ { member = substr($0, 1, length($0) - 3); next }
       NF >= 3 { print member "\t" $2 "\t" $3 }' >"$student.own"
cut -f3 "$student.own" | "$filt" >"$student.demangled"

status=0
paste "$student.own" "$student.demangled" | awk -F '\t' -v others="$student.others" '
  BEGIN {
    while ((getline line < others) > 0) {
      split(line, o, "\t")
      if (!(o[1] in where)) where[o[1]] = o[2]
      if (o[3] == "so" && !(o[1] in so)) so[o[1]] = o[2]
    }
  }
  function short(s) { return length(s) > 160 ? substr(s, 1, 157) "..." : s }
  {
    member = $1; type = $2; name = $3; what = short($4)
    weak = type ~ /^[WwVvu]$/
    if (name == "main")
      why = "main(): the checker'"'"'s program has its own"
    else if (!weak && (name in where))
      why = what ", which the checker'"'"'s program already has (" where[name] "): a symbol of the checker, the library or the runtime cannot be replaced; give yours another name, or make it static"
    else if (weak && (name in so) && name !~ /^_Z(T[ISV]|GV|Z)?N?K?(St|9__gnu_cxx)/)
      why = what ", which the C and C++ runtime defines (" so[name] "): it cannot be replaced"
    else next
    if (++bad <= 4) print member ": error: your code defines " why
  }
  END {
    if (bad > 4) print member ": error: and " bad - 4 " more such symbols"
    exit bad > 0
  }' || status=1
rm -f "$student.others" "$student.own" "$student.demangled"
exit $status
