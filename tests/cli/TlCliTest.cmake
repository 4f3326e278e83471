# tl_cli_test: one call per command-line or editor test; usage at the top of
# tests/cli/CMakeLists.txt. The command runs under check_command.cmake, which checks the exit
# code, the required output and the forbidden output (validation messages, unexpected
# `twinlight: error`) together.
set(TL_CLI_CHECK "${CMAKE_CURRENT_LIST_DIR}/check_command.cmake")

function(tl_cli_test)
  cmake_parse_arguments(PARSE_ARGV 0 arg "" "NAME;EXIT;MATCH;ERROR;FORBID;ALLOW;WORKING_DIRECTORY"
                        "ENV;LABELS;PROPERTIES;COMMAND;FILE")
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "tl_cli_test(${arg_NAME}): unexpected arguments `${arg_UNPARSED_ARGUMENTS}` "
                        "(a regex cannot contain `;`: use `.` in its place)")
  endif()
  if(NOT arg_NAME OR NOT arg_COMMAND OR NOT arg_EXIT MATCHES "^[0-9]+$")
    message(FATAL_ERROR "tl_cli_test: NAME, EXIT <code> and COMMAND are required (${arg_NAME})")
  endif()
  if(NOT arg_WORKING_DIRECTORY)
    set(arg_WORKING_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}")
  endif()
  if(NOT arg_LABELS)
    set(arg_LABELS cli)
  endif()
  # FILE path regex [FILE path regex]...: numbered -D pairs (a list would split at `;`).
  set(file_args)
  list(LENGTH arg_FILE file_values)
  math(EXPR file_pairs "${file_values} / 2")
  math(EXPR file_odd "${file_values} % 2")
  if(file_odd)
    message(FATAL_ERROR "tl_cli_test(${arg_NAME}): FILE takes a path and a regex")
  endif()
  if(file_pairs GREATER 0)
    math(EXPR last_pair "${file_pairs} - 1")
    foreach(i RANGE ${last_pair})
      math(EXPR path_index "${i} * 2")
      math(EXPR regex_index "${i} * 2 + 1")
      list(GET arg_FILE ${path_index} file_path)
      list(GET arg_FILE ${regex_index} file_regex)
      list(APPEND file_args "-DFILE_${i}=${file_path}" "-DFILE_MATCH_${i}=${file_regex}")
    endforeach()
  endif()
  add_test(NAME ${arg_NAME} WORKING_DIRECTORY "${arg_WORKING_DIRECTORY}"
           COMMAND ${CMAKE_COMMAND} "-DEXIT=${arg_EXIT}" "-DMATCH=${arg_MATCH}" "-DERROR=${arg_ERROR}"
                   "-DFORBID=${arg_FORBID}" "-DALLOW=${arg_ALLOW}" "-DFILE_COUNT=${file_pairs}" ${file_args}
                   -P "${TL_CLI_CHECK}" -- ${arg_COMMAND})
  # Validation on for every test: a validation message fails it.
  set(env LP_NUM_THREADS=2 TWINLIGHT_VALIDATION=1 ${arg_ENV})
  set_tests_properties(${arg_NAME} PROPERTIES LABELS "${arg_LABELS}" ENVIRONMENT "${env}" ${arg_PROPERTIES})
endfunction()
