# The test runner's own test: check_command.cmake must fail every way a command can hide an
# error (wrong exit code, a crash, a validation message, an unexpected or a second error
# line, missing output) and pass the honest cases.
#   cmake -DCHECK=<path to check_command.cmake> -P check_command_test.cmake
cmake_minimum_required(VERSION 3.25)

set(failures 0)
# expect(PASS|FAIL <what> <check arguments> -- <shell text>): lines of the shell text are
# separated by \n (a `;` would split the CMake argument).
function(expect verdict what)
  set(args ${ARGN})
  list(FIND args "--" at)
  list(SUBLIST args 0 ${at} defines)
  math(EXPR from "${at} + 1")
  list(SUBLIST args ${from} -1 script)
  execute_process(COMMAND ${CMAKE_COMMAND} ${defines} -P "${CHECK}" -- sh -c "${script}"
                  RESULT_VARIABLE result OUTPUT_QUIET ERROR_QUIET)
  if((verdict STREQUAL "PASS" AND NOT result EQUAL 0) OR (verdict STREQUAL "FAIL" AND result EQUAL 0))
    message("WRONG: ${what} should ${verdict} (the check exited ${result})")
    math(EXPR n "${failures} + 1")
    set(failures ${n} PARENT_SCOPE)
  else()
    message("ok: ${what}: ${verdict}")
  endif()
endfunction()

expect(PASS "exit 0 and the expected line" -DEXIT=0 -DMATCH=rendered.*frame -- "echo rendered 1 frame")
expect(FAIL "exit 1 where 0 is expected" -DEXIT=0 -DMATCH=rendered -- "echo rendered\nexit 1")
expect(FAIL "a crash" -DEXIT=0 -- "kill -SEGV \$\$")
expect(FAIL "the expected line missing" -DEXIT=0 -DMATCH=rendered -- "echo wrote")
expect(FAIL "a validation message" -DEXIT=0 -- "echo '[error] validation: Validation Error: [ VUID-x ]' >&2")
expect(FAIL "a synchronization hazard" -DEXIT=0 -- "echo 'SYNC-HAZARD-READ-AFTER-WRITE' >&2")
expect(FAIL "the validation count at exit" -DEXIT=1 -DERROR=unused -- "echo 'twinlight: error: 3 Vulkan validation error(s)' >&2\nexit 1")
expect(FAIL "an unexpected error line" -DEXIT=0 -- "echo 'twinlight: error: no scene' >&2")
expect(PASS "the expected error" -DEXIT=1 -DERROR=no.scene -- "echo 'twinlight: error: no scene' >&2\nexit 1")
expect(FAIL "another error than the expected one" -DEXIT=1 -DERROR=no.scene -- "echo 'twinlight: error: bad size' >&2\nexit 1")
expect(FAIL "two error lines" -DEXIT=1 -DERROR=no.scene -- "echo 'twinlight: error: no scene'\necho 'twinlight: error: no scene'\nexit 1")
expect(FAIL "a forbidden word" -DEXIT=0 -DFORBID=nan -- "echo 'relMSE nan'")
expect(PASS "an error logged on purpose" -DEXIT=0 "-DALLOW=shader .* did not compile" -- "echo '[error] shader a.comp did not compile'")
expect(FAIL "another error beside the allowed one" -DEXIT=0 "-DALLOW=shader .* did not compile"
       -- "echo '[error] shader a.comp did not compile'\necho '[error] validation: x'")
set(written "${CMAKE_CURRENT_BINARY_DIR}/check_command_test_file.txt")
file(REMOVE "${written}")
expect(PASS "a file written as required" -DEXIT=0 -DFILE_COUNT=1 "-DFILE_0=${written}" "-DFILE_MATCH_0=^digraph"
       -- "echo 'digraph g {}' > '${written}'")
expect(FAIL "a file with other contents" -DEXIT=0 -DFILE_COUNT=1 "-DFILE_0=${written}" "-DFILE_MATCH_0=^graph"
       -- "echo 'digraph g {}' > '${written}'")
expect(FAIL "a file not written" -DEXIT=0 -DFILE_COUNT=1 "-DFILE_0=${written}.missing" "-DFILE_MATCH_0=."
       -- "true")
file(REMOVE "${written}")

if(failures GREATER 0)
  message(FATAL_ERROR "${failures} case(s) judged wrongly by check_command.cmake")
endif()
