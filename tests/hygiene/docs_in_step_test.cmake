# docs_in_step_test.cmake -- the docs show the real example sources.
#
#   cmake -DSOURCE_DIR=<acetate source> -P tests/hygiene/docs_in_step_test.cmake
#
# In every docs/*.md, a line `<!-- file: PATH -->` must be followed by a fenced code block whose
# text is exactly the file PATH (relative to the source tree). docs/plugin-guide.md must show
# each source of examples/out-of-tree-plugin this way. Any difference fails, naming the page
# and the file.
cmake_minimum_required(VERSION 3.20)
if(NOT SOURCE_DIR)
  message(FATAL_ERROR "docs_in_step_test: -DSOURCE_DIR=... is required")
endif()

set(required_in_guide
  examples/out-of-tree-plugin/tint.cpp
  examples/out-of-tree-plugin/tint.frag
  examples/out-of-tree-plugin/CMakeLists.txt)

file(GLOB pages "${SOURCE_DIR}/docs/*.md")
set(failures "")
set(shown_in_guide "")
foreach(page IN LISTS pages)
  file(READ "${page}" text)
  get_filename_component(page_name "${page}" NAME)
  # Each marker, then the fence's info line, then the body up to the closing fence.
  while(text MATCHES "<!-- file: ([^ ]+) -->\n```[^\n]*\n")
    set(path "${CMAKE_MATCH_1}")
    string(FIND "${text}" "${CMAKE_MATCH_0}" at)
    string(LENGTH "${CMAKE_MATCH_0}" header_length)
    math(EXPR body_at "${at} + ${header_length}")
    string(SUBSTRING "${text}" ${body_at} -1 rest)
    string(FIND "${rest}" "\n```" body_end)
    if(body_end EQUAL -1)
      list(APPEND failures "${page_name}: the block showing ${path} is never closed")
      break()
    endif()
    math(EXPR body_length "${body_end} + 1")
    string(SUBSTRING "${rest}" 0 ${body_length} shown)
    if(NOT EXISTS "${SOURCE_DIR}/${path}")
      list(APPEND failures "${page_name}: shows ${path}, which does not exist")
    else()
      file(READ "${SOURCE_DIR}/${path}" actual)
      if(NOT shown STREQUAL actual)
        list(APPEND failures "${page_name}: the block showing ${path} differs from the file")
      endif()
    endif()
    if(page_name STREQUAL "plugin-guide.md")
      list(APPEND shown_in_guide "${path}")
    endif()
    string(SUBSTRING "${rest}" ${body_end} -1 text)
  endwhile()
endforeach()
foreach(path IN LISTS required_in_guide)
  if(NOT path IN_LIST shown_in_guide)
    list(APPEND failures "plugin-guide.md: does not show ${path} (<!-- file: ${path} --> before its block)")
  endif()
endforeach()
if(failures)
  list(JOIN failures "\n  " failures)
  message(FATAL_ERROR "docs_in_step_test:\n  ${failures}")
endif()
message(STATUS "docs_in_step_test: every shown file matches")
