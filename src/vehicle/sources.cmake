target_sources(trackphys PRIVATE
  vehicle/drivetrain.cpp
  vehicle/tyre.cpp
  vehicle/vehicle.cpp
  vehicle/vehicle_fingerprint.cpp
  vehicle/vehicle_spec.cpp)
