target_sources(trackphys PRIVATE
  world/world.cpp
  world/world_settings.cpp)
