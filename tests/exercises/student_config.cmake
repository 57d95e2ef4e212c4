# The exercise configuration, tested as students run it, and the exercise tree of make test:
# `make exercises` itself (its build tree, flags, sanitizers, assertions and call watch, native
# or not as the Makefile sets them), in a build tree of its own, on three sets of code:
#   1. the stubs of every lesson still as shipped: every row "not done", "0 of N"; the
#      checkers linked against them are kept in WORK/stubs/ (ctest exercises.NN.stubs-fail),
#      and the probe students (SOA_EXERCISE_PROBES, tests/CMakeLists.txt) are built;
#   2. the reference solutions (the planted copy, no mistake switched on): every lesson
#      "N of N exercises pass";
#   3. one planted mistake per lesson (SOA_PLANT, all in one run): its row names it, as the
#      lesson's exercises.NN.planted.* test expects.
# For each of the three, make grade's judge too (tests/support/recording.hpp): every lesson's
# program run with --record, then its judge (exNN-judge, no student code) with --replay on the
# record; the judge's rows (status and message) must be the run's, exercise by exercise.
# The checkers of the last run stay in WORK/tests/, linked against the planted copy, for the
# project tree's solution, planted and feedback tests. Without PLANTED (a student release),
# the stubs alone.
#   cmake -DSRC=<source dir> -DWORK=<build dir> [-DPLANTED=<dir of NN-topic/ planted copies>]
#         "-DPRISTINE=<lessons NN whose stubs are as shipped>" -DPROBES=ON|OFF
#         -P student_config.cmake
cmake_minimum_required(VERSION 3.25)
foreach(var SRC WORK)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "student_config.cmake: -D${var}=... is missing")
  endif()
endforeach()
find_program(MAKE NAMES make gmake REQUIRED)
string(REPLACE "," ";" PRISTINE "${PRISTINE}")
set(failures 0)

# make_target(<target> <dir> <out-var> <rc-var> [VAR=value...]): `make <target>` of the source
# tree on this exercise tree with EXERCISES=<dir>, the environment given; its output and exit.
function(make_target target dir out rc_var)
  # The outer make's jobserver is not this make's: the build's parallelism is its own -j.
  execute_process(
    COMMAND ${CMAKE_COMMAND} -E env --unset=MAKEFLAGS --unset=MFLAGS --unset=MAKELEVEL ${ARGN}
            ${MAKE} --no-print-directory -C ${SRC} ${target} EX_DIR=${WORK} EXERCISES=${dir}
            EX_CMAKE_ARGS=-DSOA_EXERCISE_PROBES=${PROBES}
    OUTPUT_VARIABLE text ERROR_VARIABLE text RESULT_VARIABLE rc)
  set(${out} "${text}" PARENT_SCOPE)
  set(${rc_var} ${rc} PARENT_SCOPE)
endfunction()

# make exercises with EXERCISES=<dir> and the given environment; its output in <out>.
function(make_exercises dir out)
  make_target(exercises ${dir} text rc ${ARGN})
  if(NOT rc EQUAL 0)
    message("make exercises EXERCISES=${dir} exited ${rc}:\n${text}")
    math(EXPR f "${failures} + 1")
    set(failures ${f} PARENT_SCOPE)
  endif()
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

# The exercise tree configured for EXERCISES=<dir>, then every lesson's checker (and <more>
# targets) built in one build: make exercises builds lesson by lesson, for a student's first
# table; here all lessons share the cores. A lesson that does not build is left to make
# exercises to report (-k 0).
include(ProcessorCount)
ProcessorCount(jobs)
if(jobs EQUAL 0)
  set(jobs 2)
endif()
function(build_tree dir)
  make_target(exercise-tree ${dir} text rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the exercise tree for ${dir} does not configure:\n${text}")
  endif()
  set(targets soa_exercise_main)
  foreach(lesson IN LISTS lessons)
    string(SUBSTRING "${lesson}" 0 2 nn)
    list(APPEND targets ex${nn}-exercises ex${nn}-judge)
  endforeach()
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK} -j ${jobs} --target ${targets} ${ARGN}
                          -- -k 0
                  OUTPUT_QUIET ERROR_QUIET)
endfunction()

# The report of lesson <nn> within the output of make exercises.
function(lesson_report text nn out)
  string(FIND "${text}" "== Lesson ${nn} exercises" at)
  if(at EQUAL -1)
    set(${out} "" PARENT_SCOPE)
    return()
  endif()
  string(SUBSTRING "${text}" ${at} -1 rest)
  string(SUBSTRING "${rest}" 4 -1 after)
  string(FIND "${after}" "== Lesson " next)
  if(NOT next EQUAL -1)
    math(EXPR next "${next} + 4")
    string(SUBSTRING "${rest}" 0 ${next} rest)
  endif()
  set(${out} "${rest}" PARENT_SCOPE)
endfunction()

macro(fail what)
  message("FAIL: ${what}")
  math(EXPR failures "${failures} + 1")
endmacro()

# judged(<what> [VAR=value...]): every lesson's program of the tree run with --record (in the
# environment given), then its judge with --replay: their --results rows must be the same.
function(judged what)
  foreach(dir IN LISTS lessons)
    string(SUBSTRING "${dir}" 0 2 nn)
    set(rec ${WORK}/judged/${nn})
    file(REMOVE_RECURSE ${rec})
    file(MAKE_DIRECTORY ${rec})
    if(NOT EXISTS ${WORK}/tests/ex${nn}-exercises OR NOT EXISTS ${WORK}/tests/ex${nn}-judge)
      fail("lesson ${nn}, ${what}, judged: ex${nn}-exercises or ex${nn}-judge was not built")
      continue()
    endif()
    execute_process(COMMAND ${CMAKE_COMMAND} -E env ASAN_OPTIONS=detect_leaks=0 ${ARGN}
                            ${WORK}/tests/ex${nn}-exercises --report --record ${rec}
                            --results ${rec}/run.tsv
                    OUTPUT_QUIET ERROR_QUIET)
    execute_process(COMMAND ${WORK}/tests/ex${nn}-judge --report --replay ${rec}
                            --results ${rec}/judge.tsv
                    OUTPUT_QUIET ERROR_QUIET)
    set(run "")
    set(judge "")
    if(EXISTS ${rec}/run.tsv AND EXISTS ${rec}/judge.tsv)
      file(READ ${rec}/run.tsv run)
      file(READ ${rec}/judge.tsv judge)
    endif()
    # The statuses, the third field of each row.
    string(REPLACE ";" "," rows "${judge}")
    string(REGEX MATCHALL "[^\n]+" rows "${rows}")
    set(statuses "")
    foreach(row IN LISTS rows)
      if(row MATCHES "^[^\t]*\t[^\t]*\t([^\t]*)")
        list(APPEND statuses "${CMAKE_MATCH_1}")
      endif()
    endforeach()
    list(LENGTH statuses n)
    if(run STREQUAL "" OR NOT run STREQUAL judge)
      fail("lesson ${nn}, ${what}: the judge's rows are not the run's\nrun:\n${run}\njudge:\n${judge}")
    else()
      list(REMOVE_DUPLICATES statuses)
      string(REPLACE ";" ", " statuses "${statuses}")
      message("lesson ${nn}, ${what}, judged from the record: ${n} rows as the run's (${statuses})")
    endif()
  endforeach()
  set(failures ${failures} PARENT_SCOPE)
endfunction()

file(GLOB lessons RELATIVE ${SRC}/exercises ${SRC}/exercises/[0-9][0-9]-*)
list(SORT lessons)

# 1. The stubs as shipped, then the probe students.
set(probe_target "")
if(PROBES)
  set(probe_target exercise_probes)
endif()
build_tree(${SRC}/exercises ${probe_target})
make_exercises(${SRC}/exercises text)
file(REMOVE_RECURSE ${WORK}/stubs)
foreach(dir IN LISTS lessons)
  string(SUBSTRING "${dir}" 0 2 nn)
  if(NOT nn IN_LIST PRISTINE)
    message("lesson ${nn}, the stubs: not as shipped, not judged")
    continue()
  endif()
  if(EXISTS ${WORK}/tests/ex${nn}-exercises)
    file(COPY ${WORK}/tests/ex${nn}-exercises DESTINATION ${WORK}/stubs)
  endif()
  lesson_report("${text}" ${nn} report)
  string(REGEX MATCHALL "\n  [0-9]+\\.[0-9]+ [^\n]*" rows "${report}")
  set(bad "")
  foreach(row IN LISTS rows)
    if(NOT row MATCHES "not done$")
      string(APPEND bad "${row}")
    endif()
  endforeach()
  list(LENGTH rows n_rows)
  if(n_rows GREATER 0 AND bad STREQUAL "" AND report MATCHES "\n  0 of ${n_rows} exercises pass")
    message("lesson ${nn}, the stubs: ${n_rows} of ${n_rows} not done")
  else()
    fail("lesson ${nn}, the stubs: every row must say \"not done\":${bad}\n${report}")
  endif()
endforeach()
judged("the stubs")
if(PROBES)
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK} --target exercise_probes
                  OUTPUT_VARIABLE out ERROR_VARIABLE out RESULT_VARIABLE rc)
  if(rc EQUAL 0)
    message("the probe students: built")
  else()
    fail("the probe students do not build:\n${out}")
  endif()
endif()
if(NOT PLANTED)
  if(failures GREATER 0)
    message(FATAL_ERROR "the exercise configuration: ${failures} failures")
  endif()
  message("the exercise configuration: the stubs as expected (no solutions here)")
  return()
endif()

file(GLOB lessons RELATIVE ${PLANTED} ${PLANTED}/[0-9][0-9]-*)
list(SORT lessons)
list(LENGTH lessons n_lessons)
if(n_lessons EQUAL 0)
  message(FATAL_ERROR "no planted lessons under ${PLANTED}")
endif()

# 2. The solutions.
build_tree(${PLANTED})
make_exercises(${PLANTED} text)
foreach(dir IN LISTS lessons)
  string(SUBSTRING "${dir}" 0 2 nn)
  lesson_report("${text}" ${nn} report)
  if(report MATCHES "\n  ([0-9]+) of ([0-9]+) exercises pass" AND CMAKE_MATCH_1 EQUAL CMAKE_MATCH_2)
    message("lesson ${nn}, the solutions: ${CMAKE_MATCH_1} of ${CMAKE_MATCH_2} exercises pass")
  else()
    fail("lesson ${nn}, the solutions, in the exercise configuration:\n${report}")
  endif()
endforeach()
judged("the solutions")

# 3. The first planted mistake of each lesson that has any, all switched on in one run, each
#    named in its lesson's row.
set(ids "")
set(planted_lessons "")
foreach(dir IN LISTS lessons)
  file(STRINGS ${PLANTED}/${dir}/plants.tsv plants LIMIT_COUNT 1)
  if(plants STREQUAL "")
    continue()
  endif()
  string(FIND "${plants}" "\t" tab)
  string(SUBSTRING "${plants}" 0 ${tab} id_${dir})
  math(EXPR tab "${tab} + 1")
  string(SUBSTRING "${plants}" ${tab} -1 expect_${dir})
  list(APPEND ids ${id_${dir}})
  list(APPEND planted_lessons ${dir})
endforeach()
string(REPLACE ";" "," ids "${ids}")
make_exercises(${PLANTED} text SOA_PLANT=${ids})
foreach(dir IN LISTS planted_lessons)
  string(SUBSTRING "${dir}" 0 2 nn)
  lesson_report("${text}" ${nn} report)
  if(report MATCHES "${expect_${dir}}")
    message("lesson ${nn}, planted ${id_${dir}}: named")
  else()
    fail("lesson ${nn}, planted ${id_${dir}}: the report does not match '${expect_${dir}}':\n${report}")
  endif()
endforeach()
judged("planted ${ids}" SOA_PLANT=${ids})

if(failures GREATER 0)
  message(FATAL_ERROR "the exercise configuration: ${failures} failures")
endif()
message("the exercise configuration: stubs, solutions and planted mistakes as expected")
