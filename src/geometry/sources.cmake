target_sources(trackphys PRIVATE
  geometry/ellipsoid.cpp
  geometry/normalized_triangle.cpp
  geometry/sphere_cull_variants.cpp
  geometry/triangle.cpp)
