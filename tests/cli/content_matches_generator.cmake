# The committed content/ is what the generator writes: run it into a scratch folder and
# compare every file it produced with the committed one, byte for byte (the generator is
# deterministic, and a stale scene renders with yesterday's lights and materials).
# -DGEN=<tl_content_gen> -DCONTENT=<content/> -DSCRATCH=<folder>
file(REMOVE_RECURSE "${SCRATCH}")
file(MAKE_DIRECTORY "${SCRATCH}")
execute_process(COMMAND "${GEN}" "${SCRATCH}" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the generator failed (${rc}):\n${out}${err}")
endif()
file(GLOB_RECURSE produced RELATIVE "${SCRATCH}" "${SCRATCH}/*")
list(LENGTH produced count)
if(count EQUAL 0)
  message(FATAL_ERROR "the generator wrote nothing into ${SCRATCH}")
endif()
set(stale "")
foreach(name IN LISTS produced)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files "${SCRATCH}/${name}" "${CONTENT}/${name}" RESULT_VARIABLE differ)
  if(NOT differ EQUAL 0)
    list(APPEND stale "${name}")
  endif()
endforeach()
file(REMOVE_RECURSE "${SCRATCH}")
if(stale)
  message(FATAL_ERROR "content/ is not what the generator writes: ${stale}\n"
                      "rewrite it with `cmake --build build --target regenerate-content` and commit it")
endif()
message(STATUS "${count} generated files match content/")
