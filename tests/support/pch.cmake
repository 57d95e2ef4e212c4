# Precompiled headers for the check code (tests, exercise tests, lessons, exercises and
# solutions): Eigen, the library and (for tests) GoogleTest are parsed once per build instead
# of once per translation unit, about 4 CPU-seconds each (CI's cost: see tests/CMakeLists.txt).
# Two headers, each built once by its own object library and reused (REUSE_FROM) by every
# target of its kind; the reusing targets must compile with the same flags, which
# SOA_CHECK_OPT and the directory-wide warnings give them (CMake adds -Winvalid-pch, which
# says so if not).

# The optimization of every check target: -O1 even in Release. They run for seconds, while
# -O3 on Eigen-heavy test code doubles the build. The library, the `soa` command, the lesson
# reports and the benchmarks keep the build type's flags.
set(SOA_CHECK_OPT $<$<CONFIG:Release>:-O1>)

# `make exercises` compiles the student's code (the `plain` targets, with their precompiled
# header) with AddressSanitizer and UBSan, so that a mistake stops at the student's own line;
# the library and the tests are trusted and stay uninstrumented (ASan triples their compile).
option(SOA_SANITIZE_STUDENT "ASan + UBSan for the exercises' code (make exercises)" OFF)
set(SOA_STUDENT_SAN "")
if(SOA_SANITIZE_STUDENT)
  # Eigen frees with its own aligned allocator under ASan (__SANITIZE_ADDRESS__) but with
  # free() elsewhere: the instrumented and the plain code must agree, and malloc is 16-byte
  # aligned with or without ASan on 64-bit Linux.
  set(SOA_STUDENT_SAN -fsanitize=address,undefined -fno-sanitize-recover=all
                      -fno-omit-frame-pointer -DEIGEN_MALLOC_ALREADY_ALIGNED=1)
endif()

set(SOA_PCH_DIR ${CMAKE_CURRENT_LIST_DIR})
# The library alone: lessons, exercises, solutions.
add_library(soa_pch_plain OBJECT ${SOA_PCH_DIR}/pch_source.cpp)
target_compile_options(soa_pch_plain PRIVATE ${SOA_CHECK_OPT} ${SOA_STUDENT_SAN})
target_link_libraries(soa_pch_plain PRIVATE soa)
target_precompile_headers(soa_pch_plain PRIVATE <Eigen/Dense> <Eigen/Eigenvalues> <soa/soa.hpp>)
# GoogleTest and the library: the test executables and the exercise tests.
add_library(soa_pch_test OBJECT ${SOA_PCH_DIR}/pch_source.cpp)
target_compile_options(soa_pch_test PRIVATE ${SOA_CHECK_OPT})
target_link_libraries(soa_pch_test PRIVATE soa GTest::gtest)
target_precompile_headers(soa_pch_test PRIVATE <gtest/gtest.h> <Eigen/Dense> <Eigen/Eigenvalues>
                          <soa/soa.hpp>)

# soa_check_target(<target> plain|test): the check flags and the precompiled header.
function(soa_check_target target kind)
  target_compile_options(${target} PRIVATE ${SOA_CHECK_OPT})
  if(kind STREQUAL "plain" AND SOA_STUDENT_SAN)
    target_compile_options(${target} PRIVATE ${SOA_STUDENT_SAN})
    target_link_options(${target} INTERFACE -fsanitize=address,undefined)
  endif()
  target_precompile_headers(${target} REUSE_FROM soa_pch_${kind})
endfunction()
