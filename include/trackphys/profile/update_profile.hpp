#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

namespace trackphys {

/// The phases of one physics update (docs/design.md#the-update-loop).
enum class Phase : std::uint8_t {
    broad,      ///< swept car box vs collider boxes and BVHs
    mid,        ///< per-step candidate lists (plane tree build and queries)
    cull,       ///< ellipsoid extents along each NormalizedTriangle's frame axes
    exact,      ///< exact ellipsoid-triangle contact, and the contacts between cars
    integrate,  ///< contact forces and integration
};
inline constexpr std::size_t phase_count = 5;

/// Lower-case name of a phase, as used in tables, JSON keys and traces.
constexpr const char* phase_name(Phase phase) {
    constexpr const char* names[phase_count] = {"broad", "mid", "cull", "exact", "integrate"};
    return names[static_cast<std::size_t>(phase)];
}

/// What one update did: time per phase (microseconds) and how much work it saw.
struct UpdateProfile {
    std::array<double, phase_count> phase_us{};
    double update_us = 0.0;  ///< the whole update, wall clock
    /// Triangles handed to the narrow phase, summed over cars: the broad-phase list in the
    /// none and per_update_tree modes; in precomputed_tree, each ellipsoid's mid-phase list
    /// per step.
    std::uint64_t candidates = 0;
    std::uint64_t mid_queries = 0;         ///< mid-phase queries (the others reused a list)
    std::uint64_t culled_tests = 0;        ///< culls run (per ellipsoid per sub-step)
    std::uint64_t exact_tests = 0;         ///< exact contacts computed
    std::uint64_t contacts = 0;            ///< ellipsoids in contact, summed over sub-steps
    std::uint64_t ellipsoid_substeps = 0;  ///< ellipsoids x sub-steps, to average per ellipsoid
    std::uint64_t car_pairs = 0;           ///< pairs of cars whose update boxes overlap
    std::uint64_t car_pair_tests = 0;      ///< exact ellipsoid-ellipsoid contacts computed
    std::uint64_t car_contacts = 0;        ///< sub-steps of a pair of cars touching, summed
    double max_car_penetration = 0.0;      ///< deepest car-car overlap (m)

    /// Adds another share of the same update (a worker's): times and counts add up, the
    /// penetration is the deeper one. With several workers the phase times are CPU time.
    void merge(const UpdateProfile& other) {
        for (std::size_t i = 0; i < phase_count; ++i) phase_us[i] += other.phase_us[i];
        update_us += other.update_us;
        candidates += other.candidates;
        mid_queries += other.mid_queries;
        culled_tests += other.culled_tests;
        exact_tests += other.exact_tests;
        contacts += other.contacts;
        ellipsoid_substeps += other.ellipsoid_substeps;
        car_pairs += other.car_pairs;
        car_pair_tests += other.car_pair_tests;
        car_contacts += other.car_contacts;
        max_car_penetration = std::max(max_car_penetration, other.max_car_penetration);
    }

    double& operator[](Phase phase) { return phase_us[static_cast<std::size_t>(phase)]; }
    double operator[](Phase phase) const { return phase_us[static_cast<std::size_t>(phase)]; }
};

}  // namespace trackphys
