# Precompiled headers for the check code (tests, exercise tests, lessons, exercises and
# solutions): Eigen, the library and (for tests) GoogleTest are parsed once per build instead
# of once per translation unit, several CPU-seconds each (CI's cost: see tests/CMakeLists.txt).
# Two headers, each built once by its own object library and reused (REUSE_FROM) by every
# target of its kind; the reusing targets must compile with the same flags, which
# SOA_CHECK_OPT and the directory-wide warnings give them (CMake adds -Winvalid-pch, which
# says so if not).

# The optimization of every check target: -O1 even in Release. They run for seconds, while
# -O3 on Eigen-heavy test code doubles the build. The library, the `soa` command, the labs
# and the benchmarks keep the build type's flags.
set(SOA_CHECK_OPT $<$<CONFIG:Release>:-O1>)
# Through ccache (the top-level CMakeLists.txt), GCC's preprocessed output must name the
# precompiled header for ccache to cache the units that use one.
if(CMAKE_CXX_COMPILER_LAUNCHER MATCHES "ccache" AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  list(APPEND SOA_CHECK_OPT -fpch-preprocess)
endif()

# `make exercises` compiles the student's code (the `plain` targets, with their precompiled
# header) with AddressSanitizer and UBSan, so that a mistake stops at the student's own line;
# the library and the tests are trusted and stay uninstrumented (ASan triples their compile).
option(SOA_SANITIZE_STUDENT "ASan + UBSan for the exercises' code (make exercises)" OFF)
set(SOA_STUDENT_SAN "")
if(SOA_SANITIZE_STUDENT)
  # The instrumented and the plain code share Eigen's matrices: the library makes every
  # translation unit use the same heap allocator (EIGEN_MALLOC_ALREADY_ALIGNED, lib/).
  set(SOA_STUDENT_SAN -fsanitize=address,undefined -fno-sanitize-recover=all
                      -fno-omit-frame-pointer)
endif()

# The student's code (and the solutions, compiled as a student's) is also compiled with the
# warnings that catch a student's usual bugs, shown in the exercise's row by make exercises.
# All the `plain` code (lessons too, sharing its precompiled header) checks std::vector's
# indexes (libstdc++'s assertions: ABI-neutral, the library itself does not check).
set(SOA_STUDENT_WARNINGS -Wuninitialized -Wmaybe-uninitialized -Wshadow=local -Wlogical-op
                         -Wduplicated-cond -Wduplicated-branches)
set(SOA_PLAIN_DEFS -D_GLIBCXX_ASSERTIONS)

set(SOA_PCH_DIR ${CMAKE_CURRENT_LIST_DIR})
# The library alone: lessons, exercises, solutions.
add_library(soa_pch_plain OBJECT ${SOA_PCH_DIR}/pch_source.cpp)
target_compile_options(soa_pch_plain PRIVATE ${SOA_CHECK_OPT} ${SOA_PLAIN_DEFS}
                                             ${SOA_STUDENT_SAN})
target_link_libraries(soa_pch_plain PRIVATE soa)
target_precompile_headers(soa_pch_plain PRIVATE <Eigen/Dense> <Eigen/Eigenvalues> <soa/soa.hpp>)
# GoogleTest and the library: the test executables and the exercise tests.
add_library(soa_pch_test OBJECT ${SOA_PCH_DIR}/pch_source.cpp)
target_compile_options(soa_pch_test PRIVATE ${SOA_CHECK_OPT})
target_link_libraries(soa_pch_test PRIVATE soa GTest::gtest)
target_precompile_headers(soa_pch_test PRIVATE <gtest/gtest.h> <Eigen/Dense> <Eigen/Eigenvalues>
                          <soa/soa.hpp>)

# Whether this compiler's AddressSanitizer and UBSan build and run here (the probes of the
# student's loop, tests/CMakeLists.txt, use them as make exercises does).
include(CheckCXXSourceRuns)
set(CMAKE_REQUIRED_FLAGS -fsanitize=address,undefined)
set(CMAKE_REQUIRED_LINK_OPTIONS -fsanitize=address,undefined)
check_cxx_source_runs("int main() { return 0; }" SOA_HAVE_STUDENT_SAN)
unset(CMAKE_REQUIRED_FLAGS)
unset(CMAKE_REQUIRED_LINK_OPTIONS)

# soa_student_target(<target>): the student's code as make exercises compiles it: the check
# flags with line information, the student's warnings, and ASan + UBSan where they run; no
# precompiled header, so that the sanitizers need no header of their own.
function(soa_student_target target)
  target_compile_options(${target} PRIVATE ${SOA_CHECK_OPT} -g ${SOA_PLAIN_DEFS}
                         ${SOA_STUDENT_WARNINGS})
  if(SOA_HAVE_STUDENT_SAN)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined
                           -fno-sanitize-recover=all -fno-omit-frame-pointer)
    target_link_options(${target} INTERFACE -fsanitize=address,undefined)
  endif()
endfunction()

# soa_check_target(<target> plain|student|test): the check flags and the precompiled header;
# `student` is `plain` with the student's warnings (exercises and solutions).
function(soa_check_target target kind)
  target_compile_options(${target} PRIVATE ${SOA_CHECK_OPT})
  if(kind STREQUAL "student")
    target_compile_options(${target} PRIVATE ${SOA_STUDENT_WARNINGS})
    set(kind plain)
  endif()
  if(kind STREQUAL "plain")
    target_compile_options(${target} PRIVATE ${SOA_PLAIN_DEFS})
  endif()
  if(kind STREQUAL "plain" AND SOA_STUDENT_SAN)
    target_compile_options(${target} PRIVATE ${SOA_STUDENT_SAN})
    target_link_options(${target} INTERFACE -fsanitize=address,undefined)
  endif()
  target_precompile_headers(${target} REUSE_FROM soa_pch_${kind})
endfunction()
