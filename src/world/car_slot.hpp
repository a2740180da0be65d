#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "trackphys/collision/look_ahead_list.hpp"
#include "trackphys/collision/mid_phase.hpp"
#include "trackphys/dynamics/car.hpp"
#include "trackphys/geometry/aabb.hpp"
#include "trackphys/geometry/contact.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/world/world.hpp"

namespace trackphys {

// Per-car working memory, kept between updates so a steady state allocates nothing.
struct World::CarSlot {
    // A candidate that passed the cull, with an upper bound of its penetration depth.
    struct Survivor {
        TriangleRef ref;
        const NormalizedTriangle* frame;  // the mid phase's, valid for the sub-step
        double depth_bound;
    };

    // A survivor's contact normal from an earlier sub-step: any unit direction bounds a
    // triangle's depth (depth_bound_along), and a recent normal of its own bounds it tightly.
    struct KnownNormal {
        TriangleRef ref{~0u, ~0u};
        glm::dvec3 normal{0.0, 1.0, 0.0};
    };
    // The last few per ellipsoid, replaced in turn: a wheel meets 1 or 2 triangles besides
    // the one it stands on.
    struct KnownNormals {
        std::array<KnownNormal, 4> entries;
        std::size_t next = 0;
        const KnownNormal* find(const TriangleRef& ref) const {
            for (const KnownNormal& k : entries)
                if (k.ref == ref) return &k;
            return nullptr;
        }
        void remember(const TriangleRef& ref, const glm::dvec3& normal) {
            if (const KnownNormal* k = find(ref)) {
                entries[static_cast<std::size_t>(k - entries.data())].normal = normal;
                return;
            }
            entries[next] = {ref, normal};
            next = (next + 1) % entries.size();
        }
    };

    // Per-ellipsoid storage sized for the car, no hint yet.
    CarSlot(Car car_in, MidPhase mid_in);

    // Ellipsoid i's survivors of this sub-step's cull.
    std::span<Survivor> survivors(std::size_t i) {
        return {kept.data() + kept_start[i], kept.data() + kept_start[i + 1]};
    }
    std::span<const Survivor> survivors(std::size_t i) const {
        return const_cast<CarSlot&>(*this).survivors(i);
    }

    Car car;
    MidPhase mid;
    Aabb update_box;                    // what mid.begin_update covers
    std::vector<LookAheadList> listed;  // per ellipsoid, this step
    // The ellipsoids, this sub-step (place_ellipsoids), in the updating worker's scratch: set
    // at the start of each of the car's updates (World::step_island), empty outside it.
    std::span<Ellipsoid> placed;
    // Every ellipsoid's culled survivors in one buffer, in ellipsoid order (one block of
    // lines a sub-step rather than a heap block per ellipsoid): see survivors().
    std::vector<Survivor> kept;
    std::vector<std::uint32_t> kept_start;  // ellipsoid i's from kept_start[i] to [i + 1]
    std::vector<Contact> deepest;           // per ellipsoid, this sub-step
    std::vector<TriangleRef> deepest_ref;   // its triangle, tried first next
    std::vector<KnownNormals> known;        // per ellipsoid: recent survivors' normals
    bool pushed = false;                    // by another car, this sub-step
    // The reset policy's memory: the state at the start of this update, the resets.
    RigidBodyState start_state;
    std::vector<double> start_suspension;
    std::uint64_t resets = 0;
    std::string last_reset;
};

}  // namespace trackphys
