target_sources(trackphys PRIVATE
  track/bezier_track.cpp)
