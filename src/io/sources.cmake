# The io part's sources: target_sources(trackphys PRIVATE io/...).
target_sources(trackphys PRIVATE
  io/car_spec_json.cpp
  io/json_reader.cpp
  io/map_bake.cpp
  io/map_body.cpp
  io/map_check.cpp
  io/map_codec.cpp
  io/map_file.cpp
  io/mesh_export.cpp
  io/mesh_import.cpp
  io/off_header_check.cpp
  io/ply_header_check.cpp
  io/recording.cpp
  io/recording_world.cpp
  io/scenario.cpp
  io/snapshot_file.cpp
  io/vehicle_spec_json.cpp)
