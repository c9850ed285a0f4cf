# Runs a developer tool and checks its exit code and what it prints (tests/tools/CMakeLists.txt):
#   cmake -DTOOL=<executable> -DARGS=<arguments joined by |> -DEXIT_CODE=<code>
#         [-DSTDOUT=<regex>] [-DSTDERR=<regex>]
#         [-DSETUP_TOOL=<executable> -DSETUP_ARGS=<arguments joined by |>] -P run_tool.cmake
# SETUP_TOOL runs first and must succeed. With EXIT_CODE 2 (bad input) standard output must be empty.
foreach(required TOOL EXIT_CODE)
  if(NOT DEFINED ${required})
    message(FATAL_ERROR "run_tool.cmake: ${required} is not set")
  endif()
endforeach()

if(DEFINED SETUP_TOOL)
  string(REPLACE "|" ";" setup_args "${SETUP_ARGS}")
  execute_process(COMMAND ${SETUP_TOOL} ${setup_args} RESULT_VARIABLE setup_code OUTPUT_VARIABLE setup_out
                  ERROR_VARIABLE setup_err)
  if(NOT setup_code EQUAL 0)
    message(FATAL_ERROR "setup ${SETUP_TOOL} ${SETUP_ARGS} exited with ${setup_code}\n${setup_out}${setup_err}")
  endif()
endif()

string(REPLACE "|" ";" args "${ARGS}")
execute_process(COMMAND ${TOOL} ${args} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(report "${TOOL} ${ARGS}\nexit code: ${code}\nstandard output:\n${out}\nstandard error:\n${err}")
if(NOT code STREQUAL EXIT_CODE)
  message(FATAL_ERROR "expected exit code ${EXIT_CODE}\n${report}")
endif()
if(DEFINED STDOUT AND NOT out MATCHES "${STDOUT}")
  message(FATAL_ERROR "standard output does not match '${STDOUT}'\n${report}")
endif()
if(DEFINED STDERR AND NOT err MATCHES "${STDERR}")
  message(FATAL_ERROR "standard error does not match '${STDERR}'\n${report}")
endif()
if(EXIT_CODE EQUAL 2 AND NOT out STREQUAL "")
  message(FATAL_ERROR "expected nothing on standard output after bad input\n${report}")
endif()
