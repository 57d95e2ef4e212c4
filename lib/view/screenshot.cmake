# A still image of a viewer page (docs/viewer.md), taken by Debian's Chromium headless with
# WebGL in software (SwiftShader), for readers without JavaScript and for the notes.
#   cmake -DCHROMIUM=/usr/bin/chromium -DPAGE=dir/index.html -DQUERY="paused=1&t=2"
#         -DPNG=out.png [-DSIZE=1000,620] -P screenshot.cmake
# or include() it and call soa_view_screenshot(<chromium> <page> <query> <png> <size>
# <result-var>): <result-var> is empty on success, else the reason.
# Nothing is loaded from the network: every host name resolves to nothing, and the page's own
# Content-Security-Policy refuses any address but its folder's.

function(soa_view_screenshot chromium page query png size result_var)
  string(RANDOM LENGTH 12 tag)
  set(tmp "$ENV{TMPDIR}")
  if(NOT tmp)
    set(tmp "/tmp")
  endif()
  set(profile "${tmp}/soa-chromium-profile-${tag}")  # a fresh profile: no state between runs
  file(REMOVE "${png}")
  get_filename_component(page_abs "${page}" ABSOLUTE)
  set(url "file://${page_abs}")
  if(query)
    string(APPEND url "?${query}")
  endif()
  execute_process(
    COMMAND "${chromium}" --headless=new --no-sandbox --use-angle=swiftshader
            --enable-unsafe-swiftshader --disable-background-networking
            --disable-component-update --disable-sync --no-first-run --disable-quic
            "--host-resolver-rules=MAP * ~NOTFOUND" --hide-scrollbars
            --user-data-dir=${profile} --virtual-time-budget=4000
            --window-size=${size} --screenshot=${png} "${url}"
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  file(REMOVE_RECURSE "${profile}")
  if(NOT rc EQUAL 0)
    set(${result_var} "chromium exited with ${rc}: ${err}" PARENT_SCOPE)
  elseif(NOT EXISTS "${png}")
    set(${result_var} "chromium wrote no ${png}" PARENT_SCOPE)
  else()
    file(SIZE "${png}" bytes)
    if(bytes LESS 2000)
      set(${result_var} "${png} is only ${bytes} bytes (a blank page?)" PARENT_SCOPE)
    else()
      set(${result_var} "" PARENT_SCOPE)
    endif()
  endif()
endfunction()

if(CMAKE_SCRIPT_MODE_FILE STREQUAL CMAKE_CURRENT_LIST_FILE)
  foreach(var CHROMIUM PAGE PNG)
    if(NOT DEFINED ${var})
      message(FATAL_ERROR "screenshot.cmake: ${var} is not set")
    endif()
  endforeach()
  if(NOT DEFINED SIZE)
    set(SIZE "1000,620")
  endif()
  soa_view_screenshot("${CHROMIUM}" "${PAGE}" "${QUERY}" "${PNG}" "${SIZE}" why)
  if(why)
    message(FATAL_ERROR "screenshot of ${PAGE}: ${why}")
  endif()
endif()
