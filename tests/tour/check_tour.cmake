# lessons/tour.sh on the fake tree of fake/CMakeLists.txt, three times:
#   1. all programs build and pass (lesson 2 slow to build): the lines come in tour order and
#      the tour exits 0;
#   2. lesson 3 does not build: the tour says so and exits non-zero, lesson 2 having run;
#   3. lesson 2 fails its checks: the tour runs the rest and exits non-zero.
#   cmake -DSRC=<source dir> -DWORK=<scratch dir> -DGENERATOR=Ninja -P check_tour.cmake
set(failures 0)

# tour(<case> <out-var> <rc-var> [-D...]): configures the fake tree with the options and runs
# the tour on it.
function(tour name out_var rc_var)
  set(dir ${WORK}/${name})
  file(REMOVE_RECURSE ${dir})
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${CMAKE_CURRENT_LIST_DIR}/fake -B ${dir}
                          -G ${GENERATOR} ${ARGN}
                  OUTPUT_QUIET ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name}: the fake tree does not configure:\n${err}")
  endif()
  execute_process(COMMAND sh ${SRC}/lessons/tour.sh ${dir} 2
                  OUTPUT_VARIABLE out ERROR_VARIABLE out RESULT_VARIABLE rc)
  message("== ${name} (exit ${rc}):\n${out}")
  set(${out_var} "${out}" PARENT_SCOPE)
  set(${rc_var} "${rc}" PARENT_SCOPE)
endfunction()

# expect(<what> <condition>): counts a failure, naming <what>, when the if() condition (CMake
# code in a string) is false.
macro(expect what condition)
  cmake_language(EVAL CODE "if(NOT (${condition}))
    message(\"FAIL: ${what}\")
    math(EXPR failures \"\${failures} + 1\")
  endif()")
endmacro()

set(ok "2 passed, 0 failed")
tour(all-pass out rc -DSLOW=lesson02)
expect("all-pass exits 0" "rc EQUAL 0")
string(REGEX MATCH "Lesson 01[^\n]*${ok}.*Lesson 02[^\n]*${ok}.*Lesson 03[^\n]*${ok}.*Lab  a: ${ok}"
       in_order "${out}")
expect("all-pass: lessons 1, 2, 3 then the lab, each passing" "in_order")

tour(broken out rc -DBROKEN=lesson03)
expect("broken exits non-zero" "NOT rc EQUAL 0")
expect("broken: lesson 2 still runs" "out MATCHES \"Lesson 02[^\n]*${ok}\"")
expect("broken: lesson 3 is said not built" "out MATCHES \"Lesson 03: not built\"")
expect("broken: the tour says it does not build" "out MATCHES \"make run: the tour does not build\"")
expect("broken: the lab does not run" "NOT out MATCHES \"Lab  a\"")

tour(failing out rc -DFAILING=lesson02)
expect("failing exits non-zero" "NOT rc EQUAL 0")
expect("failing: lesson 2's line shows its failure" "out MATCHES \"Lesson 02[^\n]*2 passed, 1 failed\"")
expect("failing: lesson 3 and the lab still run"
       "out MATCHES \"Lesson 03[^\n]*${ok}.*Lab  a: ${ok}\"")
expect("failing: the closing message" "out MATCHES \"make run: a lesson or lab failed its checks\"")

if(failures GREATER 0)
  message(FATAL_ERROR "lessons/tour.sh: ${failures} checks failed")
endif()
message("lessons/tour.sh: order, a build failure and a failing lesson as expected")
