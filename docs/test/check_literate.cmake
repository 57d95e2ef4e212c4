# The check of soa_literate (ctest docs.literate): the sample program must give the expected
# page line for line, and a call without its arguments must fail with a usage error.
# Variables: TOOL (soa_literate), SOURCE_DIR (the project's top folder), OUT (page to write).
cmake_minimum_required(VERSION 3.25)
set(sample docs/test/literate_sample.cpp)
set(expected "${SOURCE_DIR}/docs/test/literate_expected.md")
get_filename_component(out_dir "${OUT}" DIRECTORY)
file(MAKE_DIRECTORY "${out_dir}")
execute_process(COMMAND "${TOOL}" --title "Sample page" --anchor sample_program --source
                        ${sample} ${sample} "${OUT}"
                WORKING_DIRECTORY "${SOURCE_DIR}" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "soa_literate failed on ${sample} (exit ${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files "${OUT}" "${expected}"
                RESULT_VARIABLE differ)
if(differ)
  file(READ "${OUT}" got)
  message(FATAL_ERROR "soa_literate: ${OUT} differs from ${expected}; it is:\n${got}")
endif()
execute_process(COMMAND "${TOOL}" --anchor sample_program RESULT_VARIABLE rc ERROR_QUIET)
if(NOT rc EQUAL 2)
  message(FATAL_ERROR "soa_literate without --title and files exited ${rc}, expected 2")
endif()
message(STATUS "soa_literate: the sample page is as expected; a bad call is refused")
