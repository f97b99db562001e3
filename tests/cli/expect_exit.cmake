# Runs a command and checks its exit code and output, for command-line tests.
#   cmake -DEXPECTED_EXIT=2 -DEXPECTED_OUTPUT=<regex> -P expect_exit.cmake -- <command> [args...]
# The regex is matched against stdout and stderr together; on failure both are printed.

if(NOT DEFINED EXPECTED_EXIT OR NOT DEFINED EXPECTED_OUTPUT)
  message(FATAL_ERROR "usage: cmake -DEXPECTED_EXIT=N -DEXPECTED_OUTPUT=REGEX -P expect_exit.cmake -- COMMAND...")
endif()

# Everything after "--" is the command (CMAKE_ARGV0 is cmake itself).
set(command)
set(seen_separator FALSE)
math(EXPR last "${CMAKE_ARGC} - 1")
foreach(i RANGE ${last})
  if(seen_separator)
    list(APPEND command "${CMAKE_ARGV${i}}")
  elseif(CMAKE_ARGV${i} STREQUAL "--")
    set(seen_separator TRUE)
  endif()
endforeach()
if(NOT command)
  message(FATAL_ERROR "expect_exit.cmake: no command after --")
endif()

execute_process(COMMAND ${command}
  RESULT_VARIABLE exit_code
  OUTPUT_VARIABLE out
  ERROR_VARIABLE err
  TIMEOUT 60)
set(output "${out}${err}")

set(failed FALSE)
if(NOT exit_code STREQUAL "${EXPECTED_EXIT}")
  set(failed TRUE)
  message("exit code ${exit_code}, expected ${EXPECTED_EXIT}")
endif()
if(NOT output MATCHES "${EXPECTED_OUTPUT}")
  set(failed TRUE)
  message("output does not match: ${EXPECTED_OUTPUT}")
endif()
if(failed)
  string(REPLACE ";" " " shown "${command}")
  message("command: ${shown}\n--- stdout ---\n${out}--- stderr ---\n${err}--------------")
  message(FATAL_ERROR "expect_exit failed")
endif()
