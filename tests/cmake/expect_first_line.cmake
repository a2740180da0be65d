# cmake -DFILE=<file> -DREGEX=<regex> -P expect_first_line.cmake
# Fails unless FILE exists and its first line matches REGEX (a CSV's channel names).
if(NOT EXISTS ${FILE})
  message(FATAL_ERROR "${FILE} does not exist")
endif()
file(STRINGS ${FILE} lines LIMIT_COUNT 1)
if(NOT "${lines}" MATCHES "${REGEX}")
  message(FATAL_ERROR "the first line of ${FILE} does not match '${REGEX}':\n${lines}")
endif()
