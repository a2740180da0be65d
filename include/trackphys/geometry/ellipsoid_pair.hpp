#pragma once

#include <span>

#include "trackphys/export.hpp"
#include "trackphys/geometry/contact.hpp"
#include "trackphys/geometry/ellipsoid.hpp"

namespace trackphys {

/// The exact contact between two solid ellipsoids (docs/ellipsoid_pair.md).
///
/// With M = R diag(r^2) R^T per ellipsoid, the Minkowski difference A - B has the support
/// function h(n) = (cA - cB).n + sqrt(n^T M_A n) + sqrt(n^T M_B n), and the result is its
/// global minimum over unit n:
/// - depth: > 0 when they overlap (the minimum translation distance), < 0 when apart (minus
///   the distance between the solids), exact to ~1e-12 of the larger semi-axis; -infinity
///   only when the centres are farther apart than a double holds;
/// - normal: the unit world direction in which to move a to separate them (when apart: away
///   from b);
/// - point: the midpoint between a's extreme point towards b and b's extreme point towards a.
/// Swapping the arguments negates the normal and changes nothing else, bit for bit. Never
/// NaN, never throws.
TRACKPHYS_API Contact ellipsoid_ellipsoid_contact(const Ellipsoid& a, const Ellipsoid& b);

/// contacts[i] = ellipsoid_ellipsoid_contact(a[i], b[i]) bit for bit, for every i; the
/// spans have one size (else std::invalid_argument). Faster per pair than the single call
/// (the common pairs run four at a time in AVX2 lanes where the CPU has them).
TRACKPHYS_API void ellipsoid_ellipsoid_contacts(std::span<const Ellipsoid> a,
                                                std::span<const Ellipsoid> b,
                                                std::span<Contact> contacts);

/// Whether a and b may come within `reach` (m, >= 0) of each other: false only when a
/// certificate proves them farther apart, i.e. ellipsoid_ellipsoid_contact(a, b).depth
/// < -reach; true proves nothing. The certificates, cheapest first: the bounding spheres,
/// then the gap along the centre line (|d| minus both supports along it, a lower bound of
/// the distance). The cheap rejection in front of the exact contact for a pair phase.
TRACKPHYS_API bool ellipsoids_may_touch(const Ellipsoid& a, const Ellipsoid& b, double reach = 0.0);

}  // namespace trackphys
