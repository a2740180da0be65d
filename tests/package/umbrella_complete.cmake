# cmake -DINCLUDE_DIR=<include> -P umbrella_complete.cmake
# Fails unless trackphys/trackphys.hpp includes every public header (detail/ holds what
# public headers need to include but users do not use: it comes in through them).
file(GLOB_RECURSE headers RELATIVE "${INCLUDE_DIR}" "${INCLUDE_DIR}/trackphys/*.hpp")
file(READ "${INCLUDE_DIR}/trackphys/trackphys.hpp" umbrella)
foreach(header IN LISTS headers)
  if(header STREQUAL "trackphys/trackphys.hpp" OR header MATCHES "^trackphys/detail/")
    continue()
  endif()
  string(FIND "${umbrella}" "#include \"${header}\"" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "trackphys/trackphys.hpp does not include ${header}")
  endif()
endforeach()
