target_sources(trackphys PRIVATE
  vehicle/tyre.cpp)
