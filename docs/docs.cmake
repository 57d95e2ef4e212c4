# The build step of `make docs` (cmake -P, run by the `docs` target after the lesson tour):
#   1. copy the figures the tour drew (COURSE/NN-topic/*.png|svg, COURSE/labs/<name>/*.png|svg)
#      into FIGURES (IMAGE_PATH), and the tables it wrote (COURSE/NN-topic/*.md,
#      COURSE/labs/<name>/*.md) into TABLES (EXAMPLE_PATH), where a page includes one by
#      `\includedoc name.md`;
#   2. run Doxygen on DOXYFILE into HTML (a fresh folder; any warning fails);
#   3. copy the MathJax subset the pages need from MATHJAX into HTML/mathjax (links
#      dereferenced, so the folder can be copied or served anywhere);
#   4. copy the 3D viewers the tour wrote (COURSE/NN-topic/<name>/index.html, the same under
#      COURSE/labs/<lab>/; docs/viewer.md)
#      into HTML/viewers/<name>/, where the lesson pages embed them;
#   5. check that no page loads anything from the network.
# Variables: DOXYGEN, DOXYFILE, HTML, COURSE, FIGURES, TABLES, MATHJAX; BENCH (optional),
# the folder of `make compare`'s compare.md.
cmake_minimum_required(VERSION 3.25)
foreach(var DOXYGEN DOXYFILE HTML COURSE FIGURES TABLES MATHJAX)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "docs.cmake: ${var} is not set")
  endif()
endforeach()

# 1. Figures: one flat folder, so `\image html name.png` finds every lesson's figures.
file(REMOVE_RECURSE "${FIGURES}")
file(MAKE_DIRECTORY "${FIGURES}")
file(GLOB figures "${COURSE}/[0-9][0-9]-*/*.png" "${COURSE}/[0-9][0-9]-*/*.svg"
     "${COURSE}/labs/*/*.png" "${COURSE}/labs/*/*.svg")
set(seen "")
foreach(fig IN LISTS figures)
  get_filename_component(name "${fig}" NAME)
  if(name IN_LIST seen)
    message(FATAL_ERROR "docs: two programs wrote a figure named ${name} under ${COURSE}; "
                        "figure names must be unique across lessons and labs")
  endif()
  list(APPEND seen "${name}")
  file(COPY_FILE "${fig}" "${FIGURES}/${name}")
endforeach()

# Tables: the Markdown fragments a lesson program wrote from its own numbers (e.g.
# l6_extreme.md), one flat folder as well. Doxygen reads them through `\includedoc`, so
# they may hold Markdown but no Doxygen formulas.
file(REMOVE_RECURSE "${TABLES}")
file(MAKE_DIRECTORY "${TABLES}")
file(GLOB tables "${COURSE}/[0-9][0-9]-*/*.md" "${COURSE}/labs/*/*.md")
set(seen "")
foreach(table IN LISTS tables)
  get_filename_component(name "${table}" NAME)
  if(name IN_LIST seen)
    message(FATAL_ERROR "docs: two programs wrote a table named ${name} under ${COURSE}; "
                        "table names must be unique across lessons and labs")
  endif()
  list(APPEND seen "${name}")
  file(COPY_FILE "${table}" "${TABLES}/${name}")
endforeach()

# The comparison with Orocos KDL and MuJoCo (`make compare`, tests/bench/compare/) writes
# BENCH/compare.md in its own build; the notes include it as make_compare.md when it is
# there, else a line that says how to get it (BENCH is optional).
set(compare_table "${TABLES}/make_compare.md")
if(EXISTS "${compare_table}")
  message(FATAL_ERROR "docs: a lesson wrote a table named make_compare.md; the name is the "
                      "comparison's (make compare)")
endif()
if(DEFINED BENCH AND EXISTS "${BENCH}/compare.md")
  file(COPY_FILE "${BENCH}/compare.md" "${compare_table}")
else()
  file(WRITE "${compare_table}"
       "*No comparison in this build's output: run `make compare` (it writes "
       "`build/bench/compare.md`), then `make docs` again.*\n")
endif()

# 2. Doxygen, on a clean output folder (no stale pages of removed lessons).
if(NOT HTML MATCHES "/docs/html$")
  message(FATAL_ERROR "docs: refusing to clean ${HTML} (expected a folder docs/html)")
endif()
file(REMOVE_RECURSE "${HTML}")
get_filename_component(docs_dir "${HTML}" DIRECTORY)
file(MAKE_DIRECTORY "${docs_dir}")  # Doxygen makes one missing level only
execute_process(COMMAND "${DOXYGEN}" "${DOXYFILE}" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "docs: Doxygen failed (exit ${rc}); warnings are errors "
                      "(WARN_AS_ERROR = FAIL_ON_WARNINGS): fix the warnings printed above")
endif()
if(NOT EXISTS "${HTML}/index.html")
  message(FATAL_ERROR "docs: Doxygen wrote no ${HTML}/index.html")
endif()

# 3. MathJax 2 with SVG output: the loader, the extensions, the TeX input, the element jax,
# and the SVG output with its TeX fonts (about 2.5 MB).
set(mathjax_parts MathJax.js extensions jax/input jax/element jax/output/SVG/config.js
                  jax/output/SVG/jax.js jax/output/SVG/autoload jax/output/SVG/fonts/TeX)
foreach(part IN LISTS mathjax_parts)
  set(src "${MATHJAX}/${part}")
  if(IS_DIRECTORY "${src}")
    file(GLOB_RECURSE files FOLLOW_SYMLINKS LIST_DIRECTORIES false RELATIVE "${MATHJAX}"
         "${src}/*")
  elseif(EXISTS "${src}")
    set(files "${part}")
  else()
    message(FATAL_ERROR "docs: ${src} not found (Debian package libjs-mathjax)")
  endif()
  foreach(f IN LISTS files)
    get_filename_component(dir "${HTML}/mathjax/${f}" DIRECTORY)
    file(MAKE_DIRECTORY "${dir}")
    file(COPY_FILE "${MATHJAX}/${f}" "${HTML}/mathjax/${f}")  # reads through symlinks
  endforeach()
endforeach()

# 4. The viewers: each a folder with its page, its data and three.js; the pages show them in
# an <iframe src="viewers/<name>/index.html">, beside their still image (a figure above).
file(GLOB viewer_pages "${COURSE}/[0-9][0-9]-*/*/index.html" "${COURSE}/labs/*/*/index.html")
set(seen "")
foreach(page IN LISTS viewer_pages)
  get_filename_component(dir "${page}" DIRECTORY)
  get_filename_component(name "${dir}" NAME)
  if(name IN_LIST seen)
    message(FATAL_ERROR "docs: two programs wrote a viewer named ${name} under ${COURSE}; "
                        "viewer names must be unique across lessons and labs")
  endif()
  list(APPEND seen "${name}")
  file(COPY "${dir}/" DESTINATION "${HTML}/viewers/${name}")
endforeach()
list(LENGTH viewer_pages n_viewers)

# 5. Offline: no script, style sheet, image or frame from the network (Doxygen's footer link
# to doxygen.org is a link, not a load, and is allowed).
file(GLOB_RECURSE pages "${HTML}/*.html")
set(bad "")
foreach(page IN LISTS pages)
  file(STRINGS "${page}" hits
       REGEX "<(script|link|img|iframe|object|embed|source)[^>]*(src|href|data)=\"(https?:)?//")
  if(hits)
    list(APPEND bad "${page}")
  endif()
endforeach()
if(bad)
  string(REPLACE ";" "\n  " bad "${bad}")
  message(FATAL_ERROR "docs: these pages load resources from the network:\n  ${bad}")
endif()

list(LENGTH pages n_pages)
list(LENGTH figures n_figures)
list(LENGTH tables n_tables)
message(STATUS "Course notes: ${n_pages} pages, ${n_figures} figures, ${n_tables} tables, "
               "${n_viewers} 3D viewers, offline math -> ${HTML}/index.html")
