#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "trackphys/collision/mid_phase.hpp"
#include "trackphys/dynamics/car.hpp"
#include "trackphys/geometry/aabb.hpp"
#include "trackphys/geometry/contact.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/world/contact_events.hpp"
#include "trackphys/world/world.hpp"
#include "world/car_scratch.hpp"

namespace trackphys {

// Per-car working memory, kept between updates so a steady state allocates nothing.
struct World::CarSlot {
    static_assert(CarSpec::max_ellipsoids <= 64, "empty_lists holds a bit per ellipsoid");

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

    // What debug_draw shows of the car's last update, taken from the worker's scratch at its
    // end (the scratch is another car's by the time a game draws): the refs of the last
    // step's listed triangles and the last sub-step's survivors, a few lines a car, each
    // ellipsoid's from its start[i] to [i + 1].
    struct DrawnLists {
        // A survivor as drawn: its triangle and depth bound (the mid phase's frame pointer
        // it carried in the scratch is stale once the sub-step ends).
        struct Kept {
            TriangleRef ref;
            double depth_bound;
        };

        void take(const CarScratch& last) {
            listed.clear();
            listed_start.assign(1, 0u);
            for (const LookAheadList& list : last.listed) {
                for (const MidPhaseCandidate& c : list.candidates()) listed.push_back(c.ref);
                listed_start.push_back(static_cast<std::uint32_t>(listed.size()));
            }
            kept.clear();
            for (const CarScratch::Survivor& survivor : last.kept)
                kept.push_back({survivor.ref, survivor.depth_bound});
            kept_start.assign(last.kept_start.begin(), last.kept_start.end());
        }
        void reserve(std::size_t listed_room, std::size_t kept_room, std::size_t ellipsoids) {
            listed.reserve(listed_room);
            listed_start.reserve(ellipsoids + 1);
            kept.reserve(kept_room);
            kept_start.reserve(ellipsoids + 1);
        }
        std::vector<TriangleRef> listed;
        std::vector<std::uint32_t> listed_start;
        std::vector<Kept> kept;
        std::vector<std::uint32_t> kept_start;
    };

    // Per-ellipsoid storage sized for the car, no hint yet.
    CarSlot(Car car_in, MidPhase mid_in);

    Car car;
    MidPhase mid;
    Aabb update_box;  // what mid.begin_update covers
    // The placed ellipsoids, lists and survivors, in the updating worker's scratch: set at
    // the start of each of the car's updates (World::step_island), null outside it.
    CarScratch* scratch = nullptr;
    // Bit i: ellipsoid i's last look-ahead list was empty (CarScratch::start_car).
    std::uint64_t empty_lists = ~std::uint64_t{0};
    DrawnLists drawn;                      // none before the car's first update
    std::vector<Contact> deepest;          // per ellipsoid, this sub-step
    std::vector<TriangleRef> deepest_ref;  // its triangle, tried first next
    std::vector<KnownNormals> known;       // per ellipsoid: recent survivors' normals
    bool pushed = false;                   // by another car, this sub-step
    // What `deepest` holds where an ellipsoid touches nothing (World::contacts says so).
    static constexpr Contact no_contact{-std::numeric_limits<double>::infinity(), glm::dvec3(0.0),
                                        glm::dvec3(0.0)};
    // Where the car is now has nothing to do with its last sub-step (a reset, a teleport): no
    // contact and no hint, so that a touch there is a new one (a body hit).
    void forget_contacts() {
        std::fill(deepest.begin(), deepest.end(), no_contact);
        for (TriangleRef& ref : deepest_ref) ref = TriangleRef{~0u, ~0u};
    }
    // This update's body hits (car index left for World::update to fill), at most one per
    // ellipsoid: room for every body ellipsoid is reserved, so recording never allocates.
    std::vector<BodyHitEvent> hits;
    std::uint64_t hit_ellipsoids = 0;  // bit i: ellipsoid i has its hit this update
    void start_hits() {
        hits.clear();
        hit_ellipsoids = 0;
    }
    // Ellipsoid i's deepest contact, on `ref`, became an overlap at this sub-step: a hit if i
    // is a body ellipsoid without one yet this update.
    void note_touch(std::size_t i, const Contact& contact, const TriangleRef& ref) {
        const std::uint64_t bit = std::uint64_t{1} << i;
        if (car.spec().ellipsoids[i].role != EllipsoidRole::body || (hit_ellipsoids & bit)) return;
        hit_ellipsoids |= bit;
        const double approach =
            -glm::dot(point_velocity(car.state(), contact.point), contact.normal);
        hits.push_back({0, static_cast<std::uint32_t>(i), ref, contact.point, contact.normal,
                        contact.depth, approach});
    }
    // The reset policy's memory: the state at the start of this update, the resets.
    RigidBodyState start_state;
    std::vector<double> start_suspension;
    std::uint64_t resets = 0;
    std::string last_reset;
};

}  // namespace trackphys
