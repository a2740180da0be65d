# The collision part's sources: target_sources(trackphys PRIVATE collision/...).
target_sources(trackphys PRIVATE
  collision/brute_force_collider.cpp
  collision/bvh_builder.cpp
  collision/collider_tree.cpp
  collision/static_collider.cpp
  collision/static_world.cpp
  collision/triangle_predicates.cpp
  collision/plane_tree.cpp
  collision/plane_tree_builder.cpp
  collision/plane_tree_frame_cache.cpp
  collision/mid_phase.cpp
  collision/swept_ellipsoid.cpp
  collision/look_ahead_list.cpp)
