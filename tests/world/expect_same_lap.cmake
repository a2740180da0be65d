# cmake -DCOMMAND=<trackphys> -DSNAPSHOT=<file> -P expect_same_lap.cmake
# One lap of the default track, saving at 40 s on the way (saving does not disturb the drive:
# drive.cli_save_at), then the same lap resumed from there: it must report the same lap
# time, laps and state hash (the autopilot's lap counting continues from the snapshot).
function(drive out)
  execute_process(COMMAND ${COMMAND} drive --laps 1 ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE text
                  ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "drive --laps 1 ${ARGN} failed (${code}):\n${text}\n${err}")
  endif()
  string(REGEX MATCH "laps +[0-9]+ +lap times [0-9.]+ s" laps "${text}")
  string(REGEX MATCH "state hash +[0-9a-f]+" hash "${text}")
  if(laps STREQUAL "" OR hash STREQUAL "")
    message(FATAL_ERROR "no lap or hash in:\n${text}")
  endif()
  set(${out} "${laps} / ${hash}" PARENT_SCOPE)
endfunction()

file(REMOVE ${SNAPSHOT})
drive(saving --save-at 40 ${SNAPSHOT})
drive(resumed --resume ${SNAPSHOT})
message(STATUS "saving:  ${saving}\nresumed: ${resumed}")
if(NOT saving STREQUAL resumed)
  message(FATAL_ERROR "the resumed lap differs:\nsaving:  ${saving}\nresumed: ${resumed}")
endif()
