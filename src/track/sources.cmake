# The track part's sources: target_sources(trackphys PRIVATE track/...).
target_sources(trackphys PRIVATE
  track/bezier_loop.cpp
  track/generate_track.cpp
  track/road_profile.cpp
  track/track_mesher.cpp
  track/track_params.cpp
  track/track_shape.cpp
  track/track_stats.cpp)
