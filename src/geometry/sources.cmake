target_sources(trackphys PRIVATE
  geometry/ellipsoid.cpp
  geometry/mesh_chunks.cpp
  geometry/normalized_triangle.cpp
  geometry/triangle.cpp)
target_sources(trackphys PRIVATE
  geometry/contact.cpp
  geometry/contact_extremes.cpp
  geometry/point_ellipse.cpp
  geometry/point_ellipsoid.cpp)
target_sources(trackphys PRIVATE
  geometry/ellipsoid_pair.cpp
  geometry/ellipsoid_pair_kernel.cpp
  geometry/ellipsoid_pair_lanes.cpp)
# A file of its own in a unity build (the sanitized presets' CMAKE_UNITY_BUILD): the -O0 test
# of the pair lanes (tests/geometry) links its own copy of this file in place of the
# library's, which it could not do were the file inside a batch of others.
set_source_files_properties(geometry/ellipsoid_pair_lanes.cpp PROPERTIES
                            SKIP_UNITY_BUILD_INCLUSION ON)
