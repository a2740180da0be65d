# cmake -DCOMMAND="prog;arg;..." -DEXIT=<code> -DREGEX=<regex> [-DEMPTY_FOLDER=<dir>] -P expect_cli.cmake
# Runs COMMAND; fails unless it exits with EXIT and its stdout + stderr match REGEX.
# With EMPTY_FOLDER: that folder is created empty before the run, the command runs in it (so
# that relative output paths land there), and it must still be empty after it (hidden files
# included): the command left no output and no temporary file.
if(EMPTY_FOLDER)
  file(REMOVE_RECURSE ${EMPTY_FOLDER})
  file(MAKE_DIRECTORY ${EMPTY_FOLDER})
endif()
set(working_directory ${CMAKE_CURRENT_BINARY_DIR})
if(EMPTY_FOLDER)
  set(working_directory ${EMPTY_FOLDER})
endif()
execute_process(COMMAND ${COMMAND} WORKING_DIRECTORY ${working_directory}
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code STREQUAL EXIT)
  message(FATAL_ERROR "expected exit code ${EXIT}, got ${code}\nstdout:\n${out}\nstderr:\n${err}")
endif()
if(NOT "${out}${err}" MATCHES "${REGEX}")
  message(FATAL_ERROR "output does not match '${REGEX}'\nstdout:\n${out}\nstderr:\n${err}")
endif()
if(EMPTY_FOLDER)
  file(GLOB_RECURSE left LIST_DIRECTORIES true ${EMPTY_FOLDER}/* ${EMPTY_FOLDER}/.*)
  if(left)
    message(FATAL_ERROR "the command left files behind in ${EMPTY_FOLDER}: ${left}")
  endif()
endif()
