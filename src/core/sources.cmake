target_sources(trackphys PRIVATE
  core/assert.cpp)
