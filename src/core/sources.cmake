target_sources(trackphys PRIVATE
  core/assert.cpp
  core/build_target.cpp
  core/error.cpp)
