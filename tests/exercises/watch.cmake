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
# 4. Inline members and templates leave no undefined symbol: the student's code compiled once
#    more at -O0 -fno-inline -ffunction-sections (-DCALLS_OBJECTS=<a|b>, read with
#    -DOBJDUMP=<objdump>) keeps each call as a relocation in its caller's section. Each
#    exercise's function, and the student's own functions it calls, are searched for the
#    calls its statement forbids; such a call is flagged before the program runs.
# 5. The student's definitions of the exercises' functions are renamed soa_student_<name> in
#    the same archive: the program reaches them through the lesson's recorders (make grade's
#    record of the answers, tests/support/recording.hpp).
cmake_policy(VERSION 3.25)
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
set(exercise_functions "")
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
  # The function the exercise asks for: the first line of the block that is not a comment.
  if(block MATCHES "\n[^\n]*[ *&]([A-Za-z_][A-Za-z0-9_]*)\\(")
    set(function_of_${CMAKE_MATCH_1} ${ex})
    list(APPEND exercise_functions ${CMAKE_MATCH_1})
  endif()
  # "Do not call soa::X ..." sentences, and "Reproduces [the ... of] soa::X": the lessons'
  # rule is that an exercise never calls what it reproduces.
  string(REGEX MATCHALL "[Dd]o not (call|use) [^.]*(\\.[^ \n][^.]*)*" sentences "${block}")
  string(REGEX MATCHALL "Reproduces (the [a-z -]+ of )?soa::[A-Za-z_][A-Za-z0-9_:]*[A-Za-z0-9_]"
         reproduces "${block}")
  list(APPEND sentences ${reproduces})
  foreach(s IN LISTS sentences)
    string(REGEX MATCHALL
           "soa::[A-Za-z_][A-Za-z0-9_]*(::(operator[*+-]|[A-Za-z_][A-Za-z0-9_]*))*(\\(const [A-Za-z_]+&\\))?"
           tokens "${s}")
    foreach(tok IN LISTS tokens)
      list(APPEND rules "${ex}|${tok}")
    endforeach()
  endforeach()
endforeach()
list(REMOVE_DUPLICATES rules)

# The regex of a rule's token in a demangled name: soa::Phi also matches soa::PhiT<double>
# (the course's aliases of the class templates); a class matches any of its members.
# A token "soa::f(const X&)" names one overload: the one whose first parameter is soa::X.
function(token_pattern tok out)
  set(first_param "")
  if(tok MATCHES "^(.*)\\(const ([A-Za-z_]+)&\\)$")
    set(tok "${CMAKE_MATCH_1}")
    set(first_param "soa::${CMAKE_MATCH_2}[<,)& ]")
  endif()
  string(REGEX REPLACE "^soa::" "" inner "${tok}")
  string(REGEX REPLACE "([*+])" "\\\\\\1" inner "${inner}")
  string(REPLACE "::" "T?(<[^()]*>)?::" inner "${inner}")
  set(pattern "soa::${inner}")
  if(tok MATCHES "^soa::[A-Z][A-Za-z0-9_]*$")  # a class: any of its members
    set(pattern "${pattern}T?(<[^()]*>)?::")
  else()
    set(pattern "(^|[ (*&,])${pattern}(<[^()]*>)?\\(${first_param}")
  endif()
  set(${out} "${pattern}" PARENT_SCOPE)
endfunction()

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
      token_pattern("${tok}" pattern)
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

# 4. The forbidden calls seen in the code itself, inline members and templates included.
set(static_hits "")
if(DEFINED CALLS_OBJECTS AND DEFINED OBJDUMP)
  string(REPLACE "|" ";" objects "${CALLS_OBJECTS}")
  set(dump "")
  foreach(obj IN LISTS objects)
    execute_process(COMMAND ${OBJDUMP} -r ${obj} OUTPUT_VARIABLE out RESULT_VARIABLE rc
                    ERROR_QUIET)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "watch.cmake: ${OBJDUMP} -r failed on ${obj}")
    endif()
    string(APPEND dump "${out}")
  endforeach()
  # The functions' sections, "RELOCATION RECORDS FOR [.text.<function>]:" each followed by
  # one line a reference ("<offset> <type> <symbol>[+-addend]") and a blank line.
  string(REPLACE ";" "" dump "${dump}")
  string(REGEX MATCHALL "RELOCATION RECORDS FOR \\[\\.text\\.[^]]+\\]" headers "${dump}")
  set(callers "")
  foreach(h IN LISTS headers)
    string(REGEX REPLACE "^RELOCATION RECORDS FOR \\[\\.text\\.([^]]+)\\]$" "\\1" c "${h}")
    list(APPEND callers "${c}")
  endforeach()
  # Demangled, without return types and arguments: "soa::ex06::transform_symmetric".
  function(demangle symbols)
    string(REPLACE ";" "\n" symbol_lines "${symbols}")
    file(WRITE ${OUT_SRC}.calls "${symbol_lines}\n")
    execute_process(COMMAND ${CXXFILT} INPUT_FILE ${OUT_SRC}.calls OUTPUT_VARIABLE demangled)
    string(REPLACE ";" "" demangled "${demangled}")
    string(REPLACE "\n" ";" demangled "${demangled}")
    foreach(sym d IN ZIP_LISTS symbols demangled)
      set(name_${sym} "${d}" PARENT_SCOPE)
    endforeach()
  endfunction()
  demangle("${callers}")
  # The student's own functions: those defined in this code outside the library, Eigen and
  # the standard library (the library's inline functions are defined here too, at -O0).
  set(own "")
  foreach(c IN LISTS callers)
    # The qualified name alone: template arguments, return type and parameters left out.
    string(REPLACE "(anonymous namespace)" "anonymous" d "${name_${c}}")
    set(before "")
    while(NOT d STREQUAL before)
      set(before "${d}")
      string(REGEX REPLACE "<[^<>]*>" "" d "${d}")
    endwhile()
    string(REGEX REPLACE "\\(.*" "" d "${d}")
    string(REGEX REPLACE ".* " "" d "${d}")
    if(d MATCHES "^soa::ex[0-9]+::([A-Za-z_][A-Za-z0-9_]*)")
      list(APPEND own ${c})
      set(exercise_fn_${c} ${CMAKE_MATCH_1})
    elseif(NOT d MATCHES "^(soa|Eigen|std|__gnu_cxx)::")
      list(APPEND own ${c})
    endif()
  endforeach()
  # What each of the student's functions calls.
  set(callees "")
  foreach(c IN LISTS own)
    string(FIND "${dump}" "RELOCATION RECORDS FOR [.text.${c}]:" at)
    string(SUBSTRING "${dump}" ${at} -1 block)
    string(FIND "${block}" "\n\n" end)
    string(SUBSTRING "${block}" 0 ${end} block)
    string(REGEX MATCHALL "\n[0-9a-f]+ +[A-Z0-9_]+ +(\\.text\\.)?_Z[A-Za-z0-9_.]+" refs "${block}")
    set(calls_${c} "")
    foreach(r IN LISTS refs)
      string(REGEX REPLACE ".* (\\.text\\.)?(_Z[A-Za-z0-9_]+).*" "\\2" callee "${r}")
      list(APPEND calls_${c} ${callee})
    endforeach()
    list(REMOVE_DUPLICATES calls_${c})
    list(APPEND callees ${calls_${c}})
  endforeach()
  list(REMOVE_DUPLICATES callees)
  set(unnamed "")
  foreach(callee IN LISTS callees)
    if(NOT DEFINED name_${callee})
      list(APPEND unnamed ${callee})
    endif()
  endforeach()
  if(unnamed)
    demangle("${unnamed}")
  endif()
  foreach(c IN LISTS own)
    set(ex "")
    if(DEFINED exercise_fn_${c} AND DEFINED function_of_${exercise_fn_${c}})
      set(ex ${function_of_${exercise_fn_${c}}})
    endif()
    if(NOT ex)
      continue()
    endif()
    # Everything this exercise's function reaches through the student's own functions.
    set(reach ${c})
    set(todo ${c})
    while(todo)
      list(POP_FRONT todo f)
      foreach(callee IN LISTS calls_${f})
        if(callee IN_LIST own AND NOT callee IN_LIST reach)
          list(APPEND reach ${callee})
          list(APPEND todo ${callee})
        endif()
      endforeach()
    endwhile()
    foreach(f IN LISTS reach)
      foreach(callee IN LISTS calls_${f})
        if(callee IN_LIST own)
          continue()
        endif()
        foreach(rule IN LISTS rules)
          string(REGEX REPLACE "\\|.*" "" rule_ex "${rule}")
          if(NOT rule_ex STREQUAL ex)
            continue()
          endif()
          string(REGEX REPLACE ".*\\|" "" tok "${rule}")
          token_pattern("${tok}" pattern)
          if(name_${callee} MATCHES "${pattern}")
            list(APPEND static_hits "${ex}|${tok}")
          endif()
        endforeach()
      endforeach()
    endforeach()
  endforeach()
  list(REMOVE_DUPLICATES static_hits)
endif()
set(hit_init "")
if(count GREATER 0)
  string(REPEAT "0, " ${count} hit_init)
endif()
foreach(hit IN LISTS static_hits)
  string(REGEX REPLACE "\\|.*" "" ex "${hit}")
  string(REGEX REPLACE ".*\\|" "" tok "${hit}")
  string(APPEND names "  \"${tok}\",\n")
  string(APPEND owners "  \" ${ex} \",\n")
  string(APPEND hit_init "1, ")
  math(EXPR count "${count} + 1")
endforeach()

# 5. The student's own definitions of the exercises' functions, renamed soa_student_<name>
#    (the mangled name's last part, _ZN3soa4exNN<length><name>...): the checker reaches them
#    through the lesson's recorders (tests/support/recording.hpp), which take their names.
execute_process(COMMAND ${NM} -g --defined-only --format=posix ${ARCHIVE} OUTPUT_VARIABLE defs
                RESULT_VARIABLE rc ERROR_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "watch.cmake: ${NM} failed on ${ARCHIVE}")
endif()
string(REGEX MATCHALL "\n_ZN3soa4ex[0-9][0-9][1-9][0-9]*[A-Za-z_][A-Za-z0-9_]* [TW]" defined
       "\n${defs}")
list(REMOVE_DUPLICATES defined)  # one definition a member of the archive
foreach(d IN LISTS defined)
  string(REGEX REPLACE "^\n(_ZN3soa4ex[0-9][0-9])([1-9][0-9]*)(.*) [TW]$" "\\1;\\2;\\3" parts "${d}")
  list(GET parts 0 prefix)
  list(GET parts 1 length)
  list(GET parts 2 rest)
  string(SUBSTRING "${rest}" 0 ${length} fn)
  string(SUBSTRING "${rest}" ${length} -1 tail)
  if(fn IN_LIST exercise_functions)
    string(LENGTH "soa_student_${fn}" new_length)
    string(APPEND map "${prefix}${length}${fn}${tail} ${prefix}${new_length}soa_student_${fn}${tail}\n")
  endif()
endforeach()

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
unsigned char soa_watch_hit[${n}] = {${hit_init}};
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
# The calls step 4 found, "<exercise>\t<function>" a line, for make grade: known before any
# student code runs, they count whatever the run of that code says (tests/grade/grade.sh).
set(static_list "")
foreach(hit IN LISTS static_hits)
  string(REPLACE "|" "\t" hit "${hit}")
  string(APPEND static_list "${hit}\n")
endforeach()
file(WRITE ${OUT_SRC}.static "${static_list}")
