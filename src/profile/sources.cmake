target_sources(trackphys PRIVATE
  profile/profile_statistics.cpp
  profile/tick_clock.cpp
  profile/trace_recorder.cpp)
