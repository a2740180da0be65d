target_sources(trackphys PRIVATE
  profile/profile_statistics.cpp
  profile/trace_recorder.cpp)
