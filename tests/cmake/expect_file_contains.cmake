# cmake -DFILE=<file> -DREGEX=<regex> -P expect_file_contains.cmake
# Fails unless FILE exists and its text matches REGEX somewhere (an SVG's title).
if(NOT EXISTS ${FILE})
  message(FATAL_ERROR "${FILE} does not exist")
endif()
file(READ ${FILE} text)
if(NOT "${text}" MATCHES "${REGEX}")
  message(FATAL_ERROR "${FILE} does not contain '${REGEX}'")
endif()
