# Planted mistakes: a test of the exercise checker itself (tests/support/exercise_check.hpp).
#
# For lesson NN, the checker tests/exercises/NN-topic.cpp holds, next to each exercise's test
# (its cases and its catalogue of classic mistakes), the mistakes to plant in the lesson's
# solutions, as a comment block CMake reads at configure time:
#   // clang-format off
#   /* planted mistakes of N.K
#   soa_plant(<exercise> <id> FIND <text> WRONG <text> [TYPE <type>] EXPECT <regex>)
#   ...
#   */
#   // clang-format on
# The lines between the first line and "*/" are CMake code (soa_plant(), soa_feedback_test(),
# comments). <text> is an expression of solutions/NN-topic/solutions.cpp (found exactly once;
# no semicolons) and the wrong expression that replaces it; TYPE names the type both convert
# to when their types differ (Eigen expressions). Configuring writes one copy of the
# solutions with every mistake in place, each switched on at run time by SOA_PLANT=<id>
# (tests/support/planted.hpp), off unless SOA_PLANT says. make test's exercise tree compiles
# it as a student's code (exercises.student-config), and ctest runs the lesson's checker on
# it once per mistake: `exercises.NN.planted.<id>` passes when the report of <exercise>
# matches <regex> (the mistake named, e.g. "likely mistake \(transpose\)").
#
# Options, after EXPECT:
#   REJECT <regex>  the test fails when the report matches it (FAIL_REGULAR_EXPRESSION): a
#                   level 3 exercise's first message must not give the catalogue's formula;
#   NAMED <regex>   a second test, `exercises.NN.planted.<id>.named`, runs the same mistake as
#                   a student who has failed the exercise many times (a failed-run count of 99
#                   in its SOA_EXERCISE_CASES): its report must match <regex>, the mistake
#                   named (tests/support/exercise_check.hpp, progress()).

function(soa_plant exercise id)
  cmake_parse_arguments(P "" "FIND;WRONG;TYPE;EXPECT;REJECT;NAMED" "" ${ARGN})
  foreach(key FIND WRONG EXPECT)
    if(NOT DEFINED P_${key})
      message(FATAL_ERROR "${_soa_plant_list}: soa_plant(${exercise} ${id}) has no ${key}")
    endif()
  endforeach()
  string(FIND "${_soa_src}" "${P_FIND}" first)
  string(FIND "${_soa_src}" "${P_FIND}" last REVERSE)
  if(first EQUAL -1)
    message(FATAL_ERROR "${_soa_plant_list}: ${id}: FIND text not in the solutions: ${P_FIND}")
  endif()
  if(NOT first EQUAL last)
    message(FATAL_ERROR "${_soa_plant_list}: ${id}: FIND text is there more than once: ${P_FIND}")
  endif()
  set(full "${exercise}/${id}")
  string(REPLACE "${P_FIND}" "(::soa_planted(\"${full}\") ? ${P_TYPE}(${P_WRONG}) : ${P_TYPE}(${P_FIND}))"
         src "${_soa_src}")
  set(_soa_src "${src}" PARENT_SCOPE)
  list(APPEND _soa_plants "${full}")
  set(_soa_plants "${_soa_plants}" PARENT_SCOPE)
  set(_soa_expect_${full} "${P_EXPECT}" PARENT_SCOPE)
  set(_soa_reject_${full} "${P_REJECT}" PARENT_SCOPE)
  set(_soa_named_${full} "${P_NAMED}" PARENT_SCOPE)
endfunction()

# soa_feedback_test(<exercise> <id>): the way to the named mistake of a level 3 exercise, with
# the planted mistake <id> on (tests/exercises/feedback_check.sh): its first runs do not name
# it, the run after the number of failed runs its statement gives does, and so does a first
# run after the whole hint ladder (make exercises HINT=<exercise>). <regex> is the named
# message, as in NAMED. Called from a block of planted mistakes, after the soa_plant() of <id>.
function(soa_feedback_test exercise id regex)
  string(REGEX MATCH "^([0-9]+)\\.([0-9]+)$" _ "${exercise}")
  set(nn_ex ${CMAKE_MATCH_1})
  set(k_ex ${CMAKE_MATCH_2})
  set(name exercises.${nn}.feedback.${exercise}.${id})
  add_test(NAME ${name}
           COMMAND sh ${PROJECT_SOURCE_DIR}/tests/exercises/feedback_check.sh
                   ${SOA_EXERCISE_WORK}/tests/ex${nn}-exercises ${PROJECT_SOURCE_DIR}
                   ${CMAKE_CURRENT_BINARY_DIR}/planted/feedback/${exercise}-${id}
                   ${exercise} ${exercise}/${id} Exercise${nn_ex}_${k_ex}_* "${regex}")
  set_tests_properties(${name} PROPERTIES LABELS exercises FIXTURES_REQUIRED exercise_tree)
endfunction()

# soa_plant_blocks(<checker> <out>): the CMake code of the checker's blocks of planted
# mistakes ("/* planted mistakes of N.K" ... "*/"), in the order of the file.
function(soa_plant_blocks checker out)
  file(READ ${checker} text)
  set(code "")
  set(marker "/* planted mistakes of ")
  while(TRUE)
    string(FIND "${text}" "${marker}" at)
    if(at EQUAL -1)
      break()
    endif()
    string(SUBSTRING "${text}" ${at} -1 text)
    string(FIND "${text}" "\n" eol)
    string(FIND "${text}" "*/" end)
    if(end EQUAL -1 OR eol EQUAL -1 OR end LESS eol)
      message(FATAL_ERROR "${checker}: a block of planted mistakes has no closing */ line")
    endif()
    string(SUBSTRING "${text}" 0 ${eol} first)
    math(EXPR from "${eol} + 1")
    math(EXPR len "${end} - ${from}")
    string(SUBSTRING "${text}" ${from} ${len} block)
    string(APPEND code "# ${first}\n${block}")
    math(EXPR end "${end} + 2")
    string(SUBSTRING "${text}" ${end} -1 text)
  endwhile()
  set(${out} "${code}" PARENT_SCOPE)
endfunction()

# soa_planted_solutions(<nn> <NN-topic> <checker>): the planted copy of the lesson's solutions
# and its tests, from the blocks of planted mistakes of the checker tests/exercises/NN-topic.cpp
# (a lesson without any: the copy alone).
function(soa_planted_solutions nn dir checker)
  set(solution ${PROJECT_SOURCE_DIR}/solutions/${dir}/solutions.cpp)
  file(READ ${solution} _soa_src)
  set(_soa_plants "")
  set(_soa_plant_list ${checker})
  soa_plant_blocks(${checker} code)
  set(list_file ${CMAKE_CURRENT_BINARY_DIR}/planted/${dir}/plants.cmake)
  file(WRITE ${list_file}.new "${code}")
  file(COPY_FILE ${list_file}.new ${list_file} ONLY_IF_DIFFERENT)
  include(${list_file})
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${checker} ${solution})
  set(out ${CMAKE_CURRENT_BINARY_DIR}/planted/${dir}/solutions.cpp)
  file(WRITE ${out}.new "#include \"planted.hpp\"\n#line 1 \"${solution}\"\n${_soa_src}")
  file(COPY_FILE ${out}.new ${out} ONLY_IF_DIFFERENT)
  # The planted copy as a student's folder (make exercises EXERCISES=<...>/planted, the test of
  # the exercise configuration, tests/exercises/student_config.cmake): its header beside it, and
  # its mistakes listed one a line as <id> TAB <expected report regex>.
  file(COPY_FILE ${PROJECT_SOURCE_DIR}/tests/support/planted.hpp
       ${CMAKE_CURRENT_BINARY_DIR}/planted/${dir}/planted.hpp ONLY_IF_DIFFERENT)
  set(listing "")
  foreach(full IN LISTS _soa_plants)
    string(APPEND listing "${full}\t${_soa_expect_${full}}\n")
  endforeach()
  file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/planted/${dir}/plants.tsv "${listing}")
  # The lesson's tests run its checker as make test's exercise tree built it against this copy
  # (exercises.student-config, tests/exercises/student_config.cmake): with SOA_PLANT unset it
  # is the solutions as written.
  set(program ${SOA_EXERCISE_WORK}/tests/ex${nn}-exercises)
  foreach(full IN LISTS _soa_plants)
    string(REGEX MATCH "^([0-9]+)\\.([0-9]+)/(.*)$" _ "${full}")
    set(filter "Exercise${CMAKE_MATCH_1}_${CMAKE_MATCH_2}_*")
    set(name exercises.${nn}.planted.${CMAKE_MATCH_1}.${CMAKE_MATCH_2}.${CMAKE_MATCH_3})
    add_test(NAME ${name} COMMAND ${program} --report --gtest_filter=${filter})
    set_tests_properties(${name} PROPERTIES LABELS exercises FIXTURES_REQUIRED exercise_tree
      ENVIRONMENT "SOA_PLANT=${full};ASAN_OPTIONS=detect_leaks=0"
      PASS_REGULAR_EXPRESSION "${_soa_expect_${full}}")
    if(NOT "${_soa_reject_${full}}" STREQUAL "")
      set_tests_properties(${name} PROPERTIES FAIL_REGULAR_EXPRESSION "${_soa_reject_${full}}")
    endif()
    if(NOT "${_soa_named_${full}}" STREQUAL "")
      # A student past the exercise's count of failed runs: the count file, 99, written here.
      set(runs ${CMAKE_CURRENT_BINARY_DIR}/planted/runs/${full})
      file(WRITE ${runs}/${CMAKE_MATCH_1}.${CMAKE_MATCH_2}.failed-runs "99\n")
      add_test(NAME ${name}.named COMMAND ${program} --report --gtest_filter=${filter})
      set_tests_properties(${name}.named PROPERTIES LABELS exercises FIXTURES_REQUIRED exercise_tree
        ENVIRONMENT "SOA_PLANT=${full};SOA_EXERCISE_CASES=${runs};ASAN_OPTIONS=detect_leaks=0"
        PASS_REGULAR_EXPRESSION "${_soa_named_${full}}")
    endif()
  endforeach()
endfunction()
