# cmake -DCOMMAND="prog;arg;..." -DEXIT=<code> -DREGEX=<regex> -P expect_cli.cmake
# Runs COMMAND; fails unless it exits with EXIT and its stdout + stderr match REGEX.
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code STREQUAL EXIT)
  message(FATAL_ERROR "expected exit code ${EXIT}, got ${code}\nstdout:\n${out}\nstderr:\n${err}")
endif()
if(NOT "${out}${err}" MATCHES "${REGEX}")
  message(FATAL_ERROR "output does not match '${REGEX}'\nstdout:\n${out}\nstderr:\n${err}")
endif()
