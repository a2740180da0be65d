target_sources(trackphys PRIVATE
  world/autopilot.cpp
  world/car_islands.cpp
  world/car_views.cpp
  world/car_pair_contact.cpp
  world/car_touches.cpp
  world/cars_along_track.cpp
  world/physics_runner.cpp
  world/race_drivers.cpp
  world/race_grid.cpp
  world/spawn.cpp
  world/thread_pool.cpp
  world/world.cpp
  world/world_debug_draw.cpp
  world/world_guard.cpp
  world/world_island.cpp
  world/world_settings.cpp
  world/world_snapshot.cpp)
