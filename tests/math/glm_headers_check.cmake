# Every public header that includes glm includes trackphys/math/types.hpp too, whose
# static_asserts refuse glm settings that change the layout of the types the headers pass
# (a game including only world/world.hpp with wxyz quaternions ran silently wrong physics).
#   cmake -DINCLUDE_DIR=<repo>/include -P glm_headers_check.cmake
file(GLOB_RECURSE headers "${INCLUDE_DIR}/trackphys/*.hpp")
set(unchecked "")
foreach(header IN LISTS headers)
  file(READ "${header}" text)
  if(text MATCHES "#include <glm" AND NOT header MATCHES "trackphys/math/types.hpp$"
     AND NOT text MATCHES "#include \"trackphys/math/types.hpp\"")
    list(APPEND unchecked "${header}")
  endif()
endforeach()
if(unchecked)
  list(JOIN unchecked "\n  " shown)
  message(FATAL_ERROR "public headers that include glm but not trackphys/math/types.hpp:\n  ${shown}")
endif()
list(LENGTH headers count)
message(STATUS "${count} public headers: every one that includes glm checks its layout")
