target_sources(trackphys PRIVATE
  world/autopilot.cpp
  world/world.cpp
  world/world_settings.cpp)
