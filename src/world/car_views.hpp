#pragma once

// How PhysicsRunner fills and interpolates its published CarViews (car_views.cpp).

#include "trackphys/dynamics/car.hpp"
#include "trackphys/world/car_view.hpp"

namespace trackphys::detail {

/// A view of `car` with a WheelView per wheel, all at rest: the storage publishing fills.
CarView sized_view(const Car& car);

/// Writes car's view into `out` (sized by sized_view for this car: no allocation), its spin
/// angles advanced from `last`, the view published dt seconds before.
void take_view(const Car& car, const CarView& last, double dt, CarView& out);

/// The pose alpha (0..1) of the way from older to newer: linear for the position, slerp for
/// the orientation; older's exactly at 0 and newer's at 1.
CarPose interpolate(const CarPose& older, const CarPose& newer, double alpha);

/// The view alpha (0..1) of the way from older to newer into `out` (no allocation once out
/// has held as many wheels): older's exactly at 0 and newer's at 1. In between, the pose as
/// interpolate above, the other numbers linearly, each wheel's orientation made from the
/// interpolated body orientation, steer and spin angles, and the gear newer's.
void interpolate(const CarView& older, const CarView& newer, double alpha, CarView& out);

}  // namespace trackphys::detail
