# The pristine stubs: which lessons of exercises/ are still as shipped.
#
# `make test` checks that every exercise fails on its stub, but only for the lessons whose
# files (exercises/NN-topic/*.cpp, *.hpp) still have the checksums of
# tests/exercises/stubs.sha256: a student's work, committed or not, is never built or
# judged by `make test` (only `make exercises` looks at it). Git plays no part.
#
if(CMAKE_SCRIPT_MODE_FILE)
  cmake_policy(VERSION 3.25)
endif()

# Included by tests/CMakeLists.txt for soa_stub_status(); also a script:
#   cmake -DROOT=<source dir> -P tests/exercises/stubs.cmake            lists each lesson's state
#   cmake -DROOT=<source dir> -DWRITE=ON -P tests/exercises/stubs.cmake rewrites stubs.sha256
#     (after changing a statement or a stub: `make stub-sums`)

# The files of lesson directory <dir> (NN-topic) that the checksums cover, relative to <root>.
function(soa_stub_files root dir out)
  file(GLOB files RELATIVE ${root} ${root}/exercises/${dir}/*.cpp ${root}/exercises/${dir}/*.hpp)
  list(SORT files)
  set(${out} ${files} PARENT_SCOPE)
endfunction()

# soa_stub_status(<root> <dir> <out_pristine> <out_why>): TRUE when every file of the lesson
# has the listed checksum and no file was added or removed; else FALSE and, in <out_why>,
# the first file that differs.
function(soa_stub_status root dir out why)
  set(list_file ${root}/tests/exercises/stubs.sha256)
  file(STRINGS ${list_file} lines)
  set(listed "")
  foreach(line IN LISTS lines)
    if(line MATCHES "^([0-9a-f]+)  (exercises/${dir}/.*)$")
      list(APPEND listed ${CMAKE_MATCH_2})
      set(sum_${CMAKE_MATCH_2} ${CMAKE_MATCH_1})
    endif()
  endforeach()
  soa_stub_files(${root} ${dir} files)
  foreach(f IN LISTS files)
    if(NOT f IN_LIST listed)
      set(${out} FALSE PARENT_SCOPE)
      set(${why} "${f} is new" PARENT_SCOPE)
      return()
    endif()
    file(SHA256 ${root}/${f} sum)
    if(NOT sum STREQUAL sum_${f})
      set(${out} FALSE PARENT_SCOPE)
      set(${why} "${f} has your work" PARENT_SCOPE)
      return()
    endif()
  endforeach()
  foreach(f IN LISTS listed)
    if(NOT f IN_LIST files)
      set(${out} FALSE PARENT_SCOPE)
      set(${why} "${f} is gone" PARENT_SCOPE)
      return()
    endif()
  endforeach()
  if(NOT listed)
    set(${out} FALSE PARENT_SCOPE)
    set(${why} "exercises/${dir} is not in tests/exercises/stubs.sha256" PARENT_SCOPE)
    return()
  endif()
  set(${out} TRUE PARENT_SCOPE)
  set(${why} "" PARENT_SCOPE)
endfunction()

if(CMAKE_SCRIPT_MODE_FILE AND CMAKE_SCRIPT_MODE_FILE STREQUAL CMAKE_CURRENT_LIST_FILE)
  if(NOT ROOT)
    message(FATAL_ERROR "stubs.cmake: pass -DROOT=<the project's source directory>")
  endif()
  file(GLOB dirs RELATIVE ${ROOT}/exercises ${ROOT}/exercises/[0-9][0-9]-*)
  list(SORT dirs)
  if(WRITE)
    set(text "")
    foreach(dir IN LISTS dirs)
      soa_stub_files(${ROOT} ${dir} files)
      foreach(f IN LISTS files)
        file(SHA256 ${ROOT}/${f} sum)
        string(APPEND text "${sum}  ${f}\n")
      endforeach()
    endforeach()
    file(WRITE ${ROOT}/tests/exercises/stubs.sha256 "${text}")
    message(STATUS "wrote tests/exercises/stubs.sha256")
  else()
    foreach(dir IN LISTS dirs)
      soa_stub_status(${ROOT} ${dir} pristine why)
      if(pristine)
        message(STATUS "${dir}: pristine")
      else()
        message(STATUS "${dir}: modified (${why})")
      endif()
    endforeach()
  endif()
endif()
