target_sources(trackphys PRIVATE
  world/autopilot.cpp
  world/spawn.cpp
  world/world.cpp
  world/world_debug_draw.cpp
  world/world_guard.cpp
  world/world_settings.cpp
  world/world_snapshot.cpp)
