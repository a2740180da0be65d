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
