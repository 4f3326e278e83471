# twinlight_add_shaders(TARGET target SOURCES a.comp b.frag ... [ROOT dir])
# Compiles GLSL to SPIR-V with glslangValidator at build time into
# ${TWINLIGHT_SHADER_DIR}/<path relative to ROOT>.spv. ROOT is shaders/ for the engine's own
# (shader "common/taa.comp") and the source tree for a plugin's (shader
# "plugins/<name>/shaders/x.comp"): the same relative path is what hot reload recompiles
# (gpu/shader_reload.h). Every shader sees shaders/ on its include path, so
# `#include "shared/frame.h"` works everywhere, and its own folder (glslang's default).
function(twinlight_add_shaders)
  cmake_parse_arguments(ARG "" "TARGET;ROOT" "SOURCES" ${ARGN})
  if(NOT ARG_ROOT)
    set(ARG_ROOT "${CMAKE_SOURCE_DIR}/shaders")
  endif()
  set(outputs)
  file(GLOB_RECURSE shared_headers CONFIGURE_DEPENDS
       "${CMAKE_SOURCE_DIR}/shaders/shared/*.h" "${CMAKE_SOURCE_DIR}/shaders/*.glsl" "${CMAKE_SOURCE_DIR}/shaders/*/*.glsl")
  foreach(src IN LISTS ARG_SOURCES)
    get_filename_component(abs "${src}" ABSOLUTE)
    file(RELATIVE_PATH rel "${ARG_ROOT}" "${abs}")
    get_filename_component(src_dir "${abs}" DIRECTORY)
    file(GLOB local_headers CONFIGURE_DEPENDS "${src_dir}/*.glsl" "${src_dir}/*.h")
    set(out "${TWINLIGHT_SHADER_DIR}/${rel}.spv")
    get_filename_component(out_dir "${out}" DIRECTORY)
    # From the source root with relative paths: the debug information (-g) names the files as
    # shaders/common/taa.comp, not by where this checkout lies, so every checkout builds the same
    # SPIR-V and Mesa's shader cache (keyed by the SPIR-V) serves lavapipe's compiled pipelines to
    # all of them. With absolute paths a new checkout or worktree compiled every pipeline again on
    # its first test run: the GPU tests' quick process took 507 s instead of 200 s.
    file(RELATIVE_PATH src_from_root "${CMAKE_SOURCE_DIR}" "${abs}")
    add_custom_command(
      OUTPUT "${out}"
      COMMAND ${CMAKE_COMMAND} -E make_directory "${out_dir}"
      COMMAND ${GLSLANG_VALIDATOR} --quiet --target-env vulkan1.3 -g
              -Ishaders -o "${out}" "${src_from_root}"
      WORKING_DIRECTORY "${CMAKE_SOURCE_DIR}"
      DEPENDS "${abs}" ${shared_headers} ${local_headers}
      COMMENT "glslang ${rel}"
      VERBATIM)
    list(APPEND outputs "${out}")
  endforeach()
  add_custom_target(${ARG_TARGET} ALL DEPENDS ${outputs})
endfunction()
