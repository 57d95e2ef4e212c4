# "Do not call the library function this exercise reproduces", enforced (make exercises).
#
# Run at build time on the student's library of a lesson (libexercises_NN.a):
#   cmake -DHEADER=<exercises.hpp> -DARCHIVE=<libexercises_NN.a> -DOUT_ARCHIVE=<watched .a>
#         -DOUT_SRC=<watch.cpp> -DNM=<nm> -DOBJCOPY=<objcopy> -DCXXFILT=<c++filt>
#         -P tests/exercises/watch.cmake
# 1. Each statement's "Do not call ..." / "Do not use ..." sentences name library functions
#    and classes (soa::inverse_dynamics, soa::OperatorsT).
# 2. The student's calls of them are the archive's undefined symbols whose demangled names
#    match; objcopy renames each such reference X to __soa_watch_<i>, in the student's code
#    only (the tests call the same functions for their reference values).
# 3. watch.cpp defines each __soa_watch_<i> as two instructions (x86-64): set the flag
#    soa_watch_hit[i], jump to X; and the table of which exercise forbids which function.
#    exercise_main reads the flags after each exercise and fails the exercise that made a
#    forbidden call, naming the function.
foreach(v HEADER ARCHIVE OUT_ARCHIVE OUT_SRC NM OBJCOPY CXXFILT)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "watch.cmake: -D${v}=... is missing")
  endif()
endforeach()

# 1. exercise -> forbidden names, from the statements.
file(READ ${HEADER} text)
string(REGEX REPLACE "\n[ \t]*///[ \t]?" " " text "${text}")
string(REGEX MATCHALL "\\*\\*Exercise [0-9]+\\.[0-9]+[: ]" titles "${text}")
set(exercises "")
foreach(t IN LISTS titles)
  string(REGEX REPLACE "\\*\\*Exercise ([0-9]+\\.[0-9]+)[: ]" "\\1" ex "${t}")
  list(APPEND exercises ${ex})
endforeach()
set(rest "${text}")
set(rules "")  # "exercise|token" entries
foreach(ex IN LISTS exercises)
  string(FIND "${rest}" "**Exercise ${ex}:" start)
  if(start EQUAL -1)
    string(FIND "${rest}" "**Exercise ${ex} " start)
  endif()
  string(SUBSTRING "${rest}" ${start} -1 rest)
  string(SUBSTRING "${rest}" 12 -1 after)  # past this title, to find the next
  string(FIND "${after}" "**Exercise " next)
  if(next EQUAL -1)
    set(block "${after}")
  else()
    string(SUBSTRING "${after}" 0 ${next} block)
  endif()
  string(REGEX MATCHALL "[Dd]o not (call|use) [^.]*(\\.[^ \n][^.]*)*" sentences "${block}")
  foreach(s IN LISTS sentences)
    string(REGEX MATCHALL "soa::[A-Za-z_][A-Za-z0-9_]*(::[A-Za-z_][A-Za-z0-9_]*)*" tokens "${s}")
    foreach(tok IN LISTS tokens)
      list(APPEND rules "${ex}|${tok}")
    endforeach()
  endforeach()
endforeach()
list(REMOVE_DUPLICATES rules)

# 2. The student's references to them.
execute_process(COMMAND ${NM} -u --format=posix ${ARCHIVE} OUTPUT_VARIABLE nm_out
                RESULT_VARIABLE rc ERROR_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "watch.cmake: ${NM} failed on ${ARCHIVE}")
endif()
string(REGEX MATCHALL "\n_Z[A-Za-z0-9_]+ U" refs "\n${nm_out}")
set(mangled "")
foreach(r IN LISTS refs)
  string(REGEX REPLACE "\n(_Z[A-Za-z0-9_]+) U" "\\1" m "${r}")
  list(APPEND mangled ${m})
endforeach()
list(REMOVE_DUPLICATES mangled)
set(map "")
set(asm "")
set(names "")
set(owners "")
set(count 0)
if(mangled)
  string(REPLACE ";" "\n" mangled_lines "${mangled}")
  file(WRITE ${OUT_SRC}.mangled "${mangled_lines}\n")
  execute_process(COMMAND ${CXXFILT} INPUT_FILE ${OUT_SRC}.mangled OUTPUT_VARIABLE demangled)
  string(REGEX REPLACE "\n$" "" demangled "${demangled}")
  string(REPLACE ";" "\\;" demangled "${demangled}")
  string(REPLACE "\n" ";" demangled "${demangled}")
  set(i 0)
  foreach(m IN LISTS mangled)
    list(GET demangled ${i} d)
    math(EXPR i "${i} + 1")
    set(forbidden_in "")
    set(forbidden_tok "")
    foreach(rule IN LISTS rules)
      string(REGEX REPLACE "\\|.*" "" ex "${rule}")
      string(REGEX REPLACE ".*\\|" "" tok "${rule}")
      string(REGEX REPLACE "^soa::" "" inner "${tok}")
      string(REPLACE "::" "(<[^()]*>)?::" inner "${inner}")
      set(pattern "soa::${inner}")
      string(REGEX MATCH "[A-Za-z0-9_]+$" last "${tok}")
      if(last MATCHES "^[A-Z]")
        set(pattern "${pattern}(<[^()]*>)?::")  # a class: any of its member functions
      else()
        set(pattern "(^|[ (*&,])${pattern}(<[^()]*>)?\\(")
      endif()
      if(d MATCHES "${pattern}")
        list(APPEND forbidden_in ${ex})
        if(NOT forbidden_tok)
          set(forbidden_tok "${tok}")
        endif()
      endif()
    endforeach()
    if(forbidden_in)
      list(REMOVE_DUPLICATES forbidden_in)
      string(REPLACE ";" " " forbidden_in "${forbidden_in}")
      string(APPEND map "${m} __soa_watch_${count}\n")
      string(APPEND asm "  \".globl __soa_watch_${count}\\n\"\n  \"__soa_watch_${count}:\\n\"\n"
             "  \"  movb $1, soa_watch_hit+${count}(%rip)\\n\"\n  \"  jmp ${m}\\n\"\n")
      string(APPEND names "  \"${forbidden_tok}\",\n")
      string(APPEND owners "  \" ${forbidden_in} \",\n")
      math(EXPR count "${count} + 1")
    endif()
  endforeach()
endif()

# 3. The renamed archive and the trampolines.
file(WRITE ${OUT_SRC}.map "${map}")
execute_process(COMMAND ${OBJCOPY} --redefine-syms=${OUT_SRC}.map ${ARCHIVE} ${OUT_ARCHIVE}.new
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "watch.cmake: ${OBJCOPY} failed on ${ARCHIVE}")
endif()
file(RENAME ${OUT_ARCHIVE}.new ${OUT_ARCHIVE})
set(n ${count})
if(n EQUAL 0)
  set(n 1)
endif()
file(WRITE ${OUT_SRC}.new
"// Generated by tests/exercises/watch.cmake from ${HEADER}: the forbidden library calls the
// student's code makes, each through a trampoline that raises its flag.
extern \"C\" {
unsigned char soa_watch_hit[${n}];
extern const int soa_watch_count = ${count};
extern const char* const soa_watch_name[] = {
${names}  nullptr};
extern const char* const soa_watch_exercise[] = {
${owners}  nullptr};
}
asm(\".text\\n\"
${asm}  \"\");
")
file(COPY_FILE ${OUT_SRC}.new ${OUT_SRC} ONLY_IF_DIFFERENT)
