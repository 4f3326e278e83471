# Fails when a source under FOLDER includes a header matching FORBIDDEN: the layering rules a
# test states as a list of headers a folder must not include (read as text, `#include "..."`).
#   -DFOLDER=<folder> -DFORBIDDEN=<regex on the included path> -DRULE=<what the rule is, for the message>
# Plugins are built against engine/{gpu,graph,scene}, lighting_path.h, lighting/common/ and
# shaders/shared/ only (docs/plugins.md); the editor reaches lighting through the session's
# headers only (engine/session/session.h, inspection.h).
file(GLOB_RECURSE sources "${FOLDER}/*.cpp" "${FOLDER}/*.h" "${FOLDER}/*.comp" "${FOLDER}/*.glsl")
if(NOT sources)
  message(FATAL_ERROR "no sources under ${FOLDER}")
endif()
set(bad "")
foreach(f IN LISTS sources)
  file(STRINGS "${f}" lines REGEX "^[ \t]*#[ \t]*include[ \t]+\"")
  foreach(line IN LISTS lines)
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]+\"([^\"]+)\".*" "\\1" header "${line}")
    if(header MATCHES "${FORBIDDEN}")
      string(APPEND bad "\n  ${f}: ${header}")
    endif()
  endforeach()
endforeach()
if(bad)
  message(FATAL_ERROR "${RULE}; these includes break it:${bad}")
endif()
list(LENGTH sources n)
message(STATUS "${n} sources under ${FOLDER} keep the rule: ${RULE}")
