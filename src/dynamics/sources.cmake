target_sources(trackphys PRIVATE
  dynamics/car_spec.cpp
  dynamics/contact_force.cpp
  dynamics/rigid_body.cpp)
