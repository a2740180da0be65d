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

/// ellipsoid_ellipsoid_contact(a, b) started from the normal of an earlier contact of the
/// same pair (its `normal`, as returned for (a, b)): the same contract (the global minimum,
/// certified or found by the same search), usually two evaluations of h instead of three
/// when the pair has moved little since (docs/ellipsoid_pair.md, "Warm start"). A zero,
/// non-finite or misleading start costs time, never accuracy. The descent starts at the
/// previous minimiser and ends when it is certified (apart, or shallow); when it is not, the
/// call answers as the cold one does, bit for bit. A certified answer is not the cold call's
/// bits: both descents end at the same minimiser within ~2^-40 rad, within the same
/// contract. Swapping the arguments and negating the start negates the normal and changes
/// nothing else, bit for bit.
TRACKPHYS_API Contact ellipsoid_ellipsoid_contact(const Ellipsoid& a, const Ellipsoid& b,
                                                  const glm::dvec3& previous_normal);

/// contacts[i] = ellipsoid_ellipsoid_contact(a[i], b[i]) bit for bit, for every i; the
/// spans have one size (else std::invalid_argument). From two pairs up, the pairs that need
/// no search take less time each than in the single call: they run four at a time in AVX2
/// lanes where the CPU has them, two at a time otherwise (docs/ellipsoid_pair.md).
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
