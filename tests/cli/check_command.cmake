# Runs one command as a test and judges all of it: the exit code, what the output must say,
# and what it must never say. CTest's PASS_REGULAR_EXPRESSION ignores the exit code, so a
# command that printed the expected line and then failed (or crashed, or reported Vulkan
# validation errors) would pass; this script is what tl_cli_test (TlCliTest.cmake) runs.
#
#   cmake -DEXIT=<code> [-DMATCH=<regex>] [-DERROR=<regex>] [-DFORBID=<regex>] [-DALLOW=<regex>]
#         -P check_command.cmake -- <command> [args...]
#
# EXIT   the exit code the command must return (a signal never matches).
# MATCH  a CMake regex the combined stdout + stderr must match (`.` matches newlines too).
# ERROR  the command must print exactly one `twinlight: error: ` line, and it must match
#        this regex; without ERROR, any `twinlight: error` fails the test.
# FORBID a regex the output must not match, in addition to the ones below.
# FILE_COUNT, FILE_<i>, FILE_MATCH_<i> (i < FILE_COUNT): after the command, file FILE_<i> must
#        exist and its contents match FILE_MATCH_<i>.
# ALLOW  lines matching this regex are exempt from the forbidden ones (an error the test
#        provokes on purpose and logs, e.g. a shader that does not compile).
# Always forbidden: Vulkan validation and synchronization-validation messages, and spdlog
# lines at error level or above. The output is printed whatever the verdict.
cmake_minimum_required(VERSION 3.25)

set(command)
set(seen_separator FALSE)
math(EXPR last "${CMAKE_ARGC} - 1")
foreach(i RANGE 1 ${last})
  if(seen_separator)
    list(APPEND command "${CMAKE_ARGV${i}}")
  elseif(CMAKE_ARGV${i} STREQUAL "--")
    set(seen_separator TRUE)
  endif()
endforeach()
if(NOT command)
  message(FATAL_ERROR "check_command.cmake: no command after `--`")
endif()
if(NOT DEFINED EXIT OR NOT EXIT MATCHES "^[0-9]+$")
  message(FATAL_ERROR "check_command.cmake: -DEXIT=<code> is required (got `${EXIT}`)")
endif()

execute_process(COMMAND ${command} RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)

set(failures)
if(NOT result STREQUAL EXIT)
  list(APPEND failures "exit code `${result}`, expected ${EXIT}")
endif()
if(DEFINED MATCH AND NOT MATCH STREQUAL "" AND NOT output MATCHES "${MATCH}")
  list(APPEND failures "the output does not match `${MATCH}`")
endif()

if(DEFINED FILE_COUNT AND FILE_COUNT GREATER 0)
  math(EXPR last_file "${FILE_COUNT} - 1")
  foreach(i RANGE ${last_file})
    if(NOT EXISTS "${FILE_${i}}")
      list(APPEND failures "${FILE_${i}} was not written")
    else()
      file(READ "${FILE_${i}}" contents)
      if(NOT contents MATCHES "${FILE_MATCH_${i}}")
        list(APPEND failures "${FILE_${i}} does not match `${FILE_MATCH_${i}}`")
      endif()
    endif()
  endforeach()
endif()

# Validation layer messages (the device prints each as `validation: ...`; the layers' own
# text names VUIDs and, with synchronization validation, SYNC-HAZARD-*), the count at exit,
# and anything spdlog logged as an error.
set(forbidden "[Vv]alidation|VUID-|SYNC-HAZARD|\\[error\\]|\\[critical\\]")
if(DEFINED FORBID AND NOT FORBID STREQUAL "")
  string(APPEND forbidden "|${FORBID}")
endif()
set(judged "${output}")
if(DEFINED ALLOW AND NOT ALLOW STREQUAL "")
  string(REGEX REPLACE "[^\n]*${ALLOW}[^\n]*" "(allowed)" judged "${judged}")
endif()
if(judged MATCHES "${forbidden}")
  list(APPEND failures "the output contains `${CMAKE_MATCH_0}` (forbidden: ${forbidden})")
endif()

# (`;` separates CMake list items: counted lines must not contain it.)
string(REPLACE ";" "," scanned "${output}")
string(REGEX MATCHALL "twinlight: error[^\n]*" errors "${scanned}")
list(LENGTH errors error_count)
if(DEFINED ERROR AND NOT ERROR STREQUAL "")
  if(NOT error_count EQUAL 1)
    list(APPEND failures "expected exactly one `twinlight: error:` line, found ${error_count}")
  elseif(NOT errors MATCHES "^twinlight: error: .*${ERROR}")
    list(APPEND failures "the error line does not match `twinlight: error: .*${ERROR}`")
  endif()
elseif(error_count GREATER 0)
  list(APPEND failures "unexpected error: ${errors}")
endif()

string(REPLACE ";" " " shown "${command}")
message("$ ${shown}\n${output}")
if(failures)
  string(REPLACE ";" "\n  " reasons "${failures}")
  message(FATAL_ERROR "FAILED:\n  ${reasons}")
endif()
message("passed: exit ${result}")
