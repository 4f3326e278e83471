# twinlight_add_shaders(TARGET target SOURCES a.comp b.frag ...)
# Compiles GLSL to SPIR-V with glslangValidator at build time into
# ${TWINLIGHT_SHADER_DIR}/<path relative to shaders/>.spv. Every shader sees
# shaders/ on its include path, so `#include "shared/frame.h"` works everywhere.
function(twinlight_add_shaders)
  cmake_parse_arguments(ARG "" "TARGET" "SOURCES" ${ARGN})
  set(outputs)
  file(GLOB_RECURSE shared_headers CONFIGURE_DEPENDS
       "${CMAKE_SOURCE_DIR}/shaders/shared/*.h" "${CMAKE_SOURCE_DIR}/shaders/*.glsl" "${CMAKE_SOURCE_DIR}/shaders/*/*.glsl")
  foreach(src IN LISTS ARG_SOURCES)
    get_filename_component(abs "${src}" ABSOLUTE)
    file(RELATIVE_PATH rel "${CMAKE_SOURCE_DIR}/shaders" "${abs}")
    set(out "${TWINLIGHT_SHADER_DIR}/${rel}.spv")
    get_filename_component(out_dir "${out}" DIRECTORY)
    add_custom_command(
      OUTPUT "${out}"
      COMMAND ${CMAKE_COMMAND} -E make_directory "${out_dir}"
      COMMAND ${GLSLANG_VALIDATOR} --quiet --target-env vulkan1.3 -g
              -I${CMAKE_SOURCE_DIR}/shaders -o "${out}" "${abs}"
      DEPENDS "${abs}" ${shared_headers}
      COMMENT "glslang ${rel}"
      VERBATIM)
    list(APPEND outputs "${out}")
  endforeach()
  add_custom_target(${ARG_TARGET} ALL DEPENDS ${outputs})
endfunction()
