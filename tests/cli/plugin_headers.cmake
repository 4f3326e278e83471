# Fails when a plugin's source includes an engine header outside the public set: a plugin is
# built against engine/{gpu,graph,scene}, engine/lighting/lighting_path.h and lighting/common/,
# and shaders/shared/ (docs/plugins.md), never a built-in path's internals, the session or the
# editor. -DPLUGINS=<the plugins folder>.
file(GLOB_RECURSE sources "${PLUGINS}/*.cpp" "${PLUGINS}/*.h" "${PLUGINS}/*.comp" "${PLUGINS}/*.glsl")
if(NOT sources)
  message(FATAL_ERROR "no plugin sources under ${PLUGINS}")
endif()
set(bad "")
foreach(f IN LISTS sources)
  file(STRINGS "${f}" lines REGEX "^[ \t]*#[ \t]*include[ \t]+\"")
  foreach(line IN LISTS lines)
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]+\"([^\"]+)\".*" "\\1" header "${line}")
    if(header MATCHES "^lighting/(legacy|rt|reference)/|^session/|^albedo/|^metrics/|imgui|GLFW|^editor/")
      string(APPEND bad "\n  ${f}: ${header}")
    endif()
  endforeach()
endforeach()
if(bad)
  message(FATAL_ERROR "plugins include engine internals:${bad}")
endif()
list(LENGTH sources n)
message(STATUS "${n} plugin sources use the public headers only")
