# Runs the lesson programs in order, then the labs (cmake -P): one line per program with its
# checks; the full output of each is kept in its folder as output.txt.
# A program that wrote 3D viewers lists them in its folder's views.txt, one per line:
# "<folder> <query>" (lessons/common/viewer.hpp); each gets a still image <folder>.png, taken
# by CHROMIUM (lib/view/screenshot.cmake) at that query, for the notes.
# LESSONS: entries NN-topic|lesson program, run into OUT/NN-topic/.
# LABS: entries name|lab program (lessons/labs/<name>/, built as lab_<name>), run in this
# order into OUT/labs/<name>/, each line with its run time.
# ENTRY instead of LESSONS and LABS: one program, lesson|NN-topic|program or lab|name|program
# (`make run` builds and runs them one at a time: lessons/tour.sh).
string(REPLACE "," ";" lessons "${LESSONS}")
string(REPLACE "," ";" labs "${LABS}")
include("${CMAKE_CURRENT_LIST_DIR}/../lib/view/screenshot.cmake")
file(MAKE_DIRECTORY "${OUT}")
set(failed 0)

# run_program(<exe> <out_dir> <closing-var> <err-var>): runs exe into its freshly cleared
# out_dir (no stale figure outlives the program that drew it), keeps its output as
# out_dir/output.txt, takes the still image of each viewer it wrote; sets <closing-var> to
# its closing line "N passed, M failed" (or why there is none), <err-var> to its stderr when
# it failed, and `failed` (in the caller's scope) when it or a still image failed.
function(run_program exe out_dir closing_var err_var)
  file(REMOVE_RECURSE "${out_dir}")
  file(MAKE_DIRECTORY "${out_dir}")
  execute_process(COMMAND "${exe}" "${out_dir}" OUTPUT_VARIABLE out ERROR_VARIABLE err
                  RESULT_VARIABLE rc)
  file(WRITE "${out_dir}/output.txt" "${out}${err}")
  string(REGEX MATCH "[0-9]+ passed, [0-9]+ failed" closing "${out}")
  if(NOT closing)
    set(closing "no closing line (exit ${rc})")
  endif()
  if(rc EQUAL 0)
    set(err "")
  else()
    set(failed 1 PARENT_SCOPE)
  endif()
  if(EXISTS "${out_dir}/views.txt")
    file(STRINGS "${out_dir}/views.txt" views)
    foreach(view IN LISTS views)
      string(REGEX MATCH "^([^ ]+) ?(.*)$" _ "${view}")
      set(name "${CMAKE_MATCH_1}")
      set(query "${CMAKE_MATCH_2}")
      if(NOT CHROMIUM)
        message("  ${name}.png: no still image, Chromium was not found when CMake configured "
                "(Debian package chromium; make run installs it)")
        set(failed 1 PARENT_SCOPE)
        continue()
      endif()
      soa_view_screenshot("${CHROMIUM}" "${out_dir}/${name}/index.html" "${query}"
                          "${out_dir}/${name}.png" "1000,620" why)
      if(why)
        message("  ${name}.png: ${why}")
        set(failed 1 PARENT_SCOPE)
      endif()
    endforeach()
  endif()
  set(${closing_var} "${closing}" PARENT_SCOPE)
  set(${err_var} "${err}" PARENT_SCOPE)
endfunction()

# tour_entry(<lesson|lab> <NN-topic|name> <program>): runs one program of the tour into its
# folder and prints its line.
function(tour_entry kind name exe)
  if(kind STREQUAL "lesson")
    set(out_dir "${OUT}/${name}")
    run_program("${exe}" "${out_dir}" closing err)
    string(REPLACE "-" " " topic "${name}")
    string(SUBSTRING "${topic}" 3 -1 topic)
    string(SUBSTRING "${name}" 0 2 nn)
    file(GLOB written RELATIVE "${out_dir}" "${out_dir}/*")
    list(SORT written)
    string(REPLACE ";" ", " written "${written}")
    message("Lesson ${nn}  ${topic}: ${closing}  -> ${out_dir}/ (${written})")
  else()
    set(out_dir "${OUT}/labs/${name}")
    string(TIMESTAMP t0 "%s")
    run_program("${exe}" "${out_dir}" closing err)
    string(TIMESTAMP t1 "%s")
    math(EXPR seconds "${t1} - ${t0}")
    message("Lab  ${name}: ${closing} in ${seconds} s  -> ${out_dir}/output.txt")
  endif()
  if(NOT err STREQUAL "")
    message("  ${err}")
  endif()
  set(failed ${failed} PARENT_SCOPE)
endfunction()

if(DEFINED ENTRY)
  string(REPLACE "|" ";" parts "${ENTRY}")
  list(GET parts 0 kind)
  list(GET parts 1 name)
  list(GET parts 2 exe)
  tour_entry(${kind} "${name}" "${exe}")
  if(failed)
    message(FATAL_ERROR "  ${name} failed its checks; see its output.txt")
  endif()
  return()
endif()

message("")
foreach(entry IN LISTS lessons)
  string(REPLACE "|" ";" parts "${entry}")
  list(GET parts 0 dir)
  list(GET parts 1 exe)
  tour_entry(lesson "${dir}" "${exe}")
endforeach()
foreach(entry IN LISTS labs)
  string(REPLACE "|" ";" parts "${entry}")
  list(GET parts 0 name)
  list(GET parts 1 exe)
  tour_entry(lab "${name}" "${exe}")
endforeach()
message("")
if(failed)
  message(FATAL_ERROR "a lesson or lab failed its checks; see its output.txt")
endif()
