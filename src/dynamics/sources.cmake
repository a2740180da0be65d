target_sources(trackphys PRIVATE
  dynamics/rigid_body.cpp)
