# cmake -DCOMMAND=<trackphys> -DARGS="<drive options>" -DSAVE_AT=<s> -DSNAPSHOT=<file>
#       -DPLAIN=<ON|OFF> -P expect_same_drive.cmake
# Drives `trackphys drive ARGS --save-at SAVE_AT SNAPSHOT`, then `trackphys drive ARGS --resume
# SNAPSHOT`: both must report the same simulated time, laps and lap times, distance, top
# speed, resets and state hash. With PLAIN, the drive without --save-at must too (saving does
# not disturb the drive).
function(drive out)
  execute_process(COMMAND ${COMMAND} drive ${ARGS} ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE text
                  ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "drive ${ARGS} ${ARGN} failed (${code}):\n${text}\n${err}")
  endif()
  set(figures)
  foreach(pattern "simulated +[0-9.]+ s in [0-9]+ updates" "laps [^\n]*" "top speed [^\n]*"
                  "distance [^\n]*" "resets [^\n]*" "state hash +[0-9a-f]+")
    string(REGEX MATCH "${pattern}" figure "${text}")
    if(figure STREQUAL "")
      message(FATAL_ERROR "no '${pattern}' in the output of drive ${ARGS} ${ARGN}:\n${text}")
    endif()
    string(APPEND figures "\n  ${figure}")
  endforeach()
  set(${out} "${figures}" PARENT_SCOPE)
endfunction()

file(REMOVE ${SNAPSHOT})
drive(saving --save-at ${SAVE_AT} ${SNAPSHOT})
drive(resumed --resume ${SNAPSHOT})
set(plain "${saving}")
if(PLAIN)
  drive(plain)
endif()
message(STATUS "saving:${saving}\nresumed:${resumed}")
if(NOT saving STREQUAL resumed OR NOT saving STREQUAL plain)
  message(FATAL_ERROR "the drives differ:\nsaving:${saving}\nresumed:${resumed}\nplain:${plain}")
endif()
