target_sources(trackphys PRIVATE
  dynamics/car.cpp
  dynamics/car_presets.cpp
  dynamics/car_vehicle.cpp
  dynamics/car_spec.cpp
  dynamics/contact_force.cpp
  dynamics/rigid_body.cpp)
