target_sources(trackphys PRIVATE
  io/mesh_io.cpp)
