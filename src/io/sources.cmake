# The io part's sources: target_sources(trackphys PRIVATE io/...).
target_sources(trackphys PRIVATE
  io/ac3d_check.cpp
  io/car_spec_json.cpp
  io/json_reader.cpp
  io/map_bake.cpp
  io/map_body.cpp
  io/map_check.cpp
  io/map_codec.cpp
  io/map_file.cpp
  io/mesh_export.cpp
  io/confined_io_system.cpp
  io/gltf_check.cpp
  io/file_bytes.cpp
  io/mesh_checks.cpp
  io/mesh_format.cpp
  io/mesh_import.cpp
  io/obj_check.cpp
  io/off_check.cpp
  io/ply_check.cpp
  io/stl_check.cpp
  io/recording.cpp
  io/recording_world.cpp
  io/regular_file.cpp
  io/scenario.cpp
  io/snapshot_file.cpp
  io/vehicle_spec_json.cpp)
