// place_car_on_surface: a bisection on the car's height between one where it is clear of
// the static triangles and one where it touches them.
//
// Why a bisection on exact contacts, not a ray under the car: a ray finds the surface
// under one point, but the car meets the surface wherever its ellipsoids do, a wheel on a
// kerb or the high side of a banked turn; the exact ellipsoid-triangle contact is the
// World's own test, so the car placed is clear by the World's measure. The signed distance
// between two convex shapes changes by at most the distance either moves, so at the end,
// with a clear height and a touching one 0.1 mm apart, the car at the clear height is
// within clearance + 0.1 mm of what it touched.

#include "trackphys/world/spawn.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <vector>

#include <glm/geometric.hpp>

#include "trackphys/dynamics/car.hpp"
#include "trackphys/error.hpp"
#include "trackphys/geometry/contact.hpp"
#include "trackphys/geometry/ellipsoid.hpp"

namespace trackphys {
namespace {

// The bisection stops when its clear and touching heights are this close (m).
constexpr double kHeightTolerance = 1e-4;
// Heights beyond this are not placed: doubles there lie more than kHeightTolerance apart
// (1.5e-5 m at 1e11 m, 1.4e14 m at 1e30), and the bisection would land anywhere.
constexpr double kMaxHeight = 1e11;

// Where the car overlaps the statics most at one height: the deepest contact of any of its
// ellipsoids (-infinity when none is within the clearance of a triangle).
struct Deepest {
    double depth = -std::numeric_limits<double>::infinity();
    std::size_t ellipsoid = 0;
    TriangleRef triangle{};
};

// The car's ellipsoids (wheels at full droop) at a given centre-of-mass position.
class CarProbe {
  public:
    CarProbe(const StaticWorld& statics, const Car& car, double clearance)
        : statics_(statics), car_(car), clearance_(clearance) {}

    Ellipsoid ellipsoid(std::size_t i, const glm::dvec3& position) const {
        return car_.body_ellipsoid(i).transformed(car_.state().orientation, position);
    }

    Deepest deepest(const glm::dvec3& position) {
        Deepest deepest;
        for (std::size_t i = 0; i < car_.ellipsoid_count(); ++i) {
            const Ellipsoid e = ellipsoid(i, position);
            refs_.clear();
            statics_.query_aabb(e.bounds().padded(clearance_), refs_);
            for (const TriangleRef& ref : refs_) {
                const double depth = ellipsoid_triangle_contact(
                                         e, statics_.collider(ref.collider).triangle(ref.triangle))
                                         .depth;
                if (depth > deepest.depth) deepest = {depth, i, ref};
            }
        }
        return deepest;
    }

    bool clear(const glm::dvec3& position) { return deepest(position).depth <= -clearance_; }

    // How far the car can drop from `position` before an ellipsoid's lowest point reaches
    // the surface straight below it (the first contact is no lower), or nullopt when no
    // ray from them hits anything.
    std::optional<double> drop_bound(const glm::dvec3& position) const {
        std::optional<double> drop;
        for (std::size_t i = 0; i < car_.ellipsoid_count(); ++i) {
            const auto hit =
                statics_.raycast(lowest_point(ellipsoid(i, position)), glm::dvec3(0.0, -1.0, 0.0),
                                 std::numeric_limits<double>::infinity());
            if (hit && (!drop || hit->hit.distance < *drop)) drop = hit->hit.distance;
        }
        return drop;
    }

  private:
    // The ellipsoid's point of least y: for the ellipsoid's matrix A = R diag(r^2) R^T it is
    // c - A e_y / sqrt(e_y . A e_y).
    static glm::dvec3 lowest_point(const Ellipsoid& e) {
        glm::dvec3 a_ey(0.0);
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3 axis = e.sorted_axes()[k];
            a_ey += axis * (e.sorted_radii()[k] * e.sorted_radii()[k] * axis.y);
        }
        return e.center() - a_ey / std::sqrt(a_ey.y);
    }

    const StaticWorld& statics_;
    const Car& car_;
    double clearance_;
    std::vector<TriangleRef> refs_;
};

std::string describe(const glm::dvec3& p) {
    std::ostringstream text;
    text << "(" << p.x << ", " << p.y << ", " << p.z << ")";
    return text.str();
}

}  // namespace

RigidBodyState place_car_on_surface(const StaticWorld& statics, const CarSpec& spec,
                                    const glm::dvec3& position, const glm::dquat& orientation,
                                    double clearance) {
    // Positive, so that a clear car's lowest points, where the drop's rays start, are off
    // every surface.
    if (!(clearance > 0.0 && clearance <= 1.0))
        throw Error("place_car_on_surface: clearance must be in (0, 1] m, got " +
                    exact_text(clearance));
    RigidBodyState placed;
    placed.position = position;
    placed.orientation = glm::normalize(orientation);
    const Car car(spec, placed);  // validates the spec and the pose
    const auto refuse_beyond_max_height = [&](double y, const char* what) {
        if (!(std::abs(y) <= kMaxHeight))
            throw Error(std::string("place_car_on_surface: ") + what + describe(position) +
                        " is more than 1e11 m from y = 0, where doubles are too coarse to "
                        "place the car to 0.1 mm");
    };
    refuse_beyond_max_height(position.y, "the car at ");
    CarProbe probe(statics, car, clearance);
    auto at = [&](double y) { return glm::dvec3(position.x, y, position.z); };

    // A clear height and a touching one, then the bisection between them.
    double clear_y, touching_y;
    const Deepest start = probe.deepest(position);
    if (start.depth <= -clearance) {
        const std::optional<double> drop = probe.drop_bound(position);
        if (!drop)
            throw Error("place_car_on_surface: no surface below the car at " + describe(position) +
                        " (rays cast straight down from its ellipsoids hit nothing)");
        clear_y = position.y;
        // A little further and a lowest point is inside the surface it reached.
        touching_y = position.y - *drop - kHeightTolerance;
        refuse_beyond_max_height(touching_y, "the surface below the car at ");
    } else {
        const double max_rise = 2.0 * car.bounding_radius();
        double rise = std::clamp(start.depth + clearance, kHeightTolerance, max_rise);
        touching_y = position.y;
        for (;;) {
            const Deepest deepest = probe.deepest(at(position.y + rise));
            if (deepest.depth <= -clearance) break;
            touching_y = position.y + rise;
            if (rise >= max_rise) {
                std::ostringstream why;
                why << "place_car_on_surface: the car at " << describe(position)
                    << " is inside geometry and stays so raised by " << max_rise
                    << " m (twice its bounding radius): ellipsoid " << deepest.ellipsoid << " is "
                    << deepest.depth << " m deep in collider " << deepest.triangle.collider
                    << "'s triangle " << deepest.triangle.triangle;
                throw Error(why.str());
            }
            rise = std::min(2.0 * rise, max_rise);
        }
        clear_y = position.y + rise;
    }
    while (clear_y - touching_y > kHeightTolerance) {
        const double mid = 0.5 * (clear_y + touching_y);
        if (mid <= touching_y || mid >= clear_y) break;  // heights a double step apart
        (probe.clear(at(mid)) ? clear_y : touching_y) = mid;
    }
    placed.position = at(clear_y);
    return placed;
}

}  // namespace trackphys
