#include "triangle_predicates.hpp"

#include <sstream>

#include "geometry/mesh_surface_check.hpp"
#include "trackphys/error.hpp"
#include "trackphys/geometry/triangle.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys::collision_detail {
namespace {

std::string describe(const glm::dvec3& v) {
    std::ostringstream text;
    text << "(" << v.x << ", " << v.y << ", " << v.z << ")";
    return text.str();
}

}  // namespace

CapsuleQuery make_capsule_query(const glm::dvec3& start, const glm::dvec3& end, double radius) {
    if (!is_finite(start) || !is_finite(end))
        throw Error("sphere/capsule query: center or segment end is not finite: " +
                    describe(start) + " to " + describe(end));
    if (!std::isfinite(radius) || !(radius >= 0.0))
        throw Error("sphere/capsule query: radius must be finite and >= 0, got " +
                    exact_text(radius));
    CapsuleQuery q{start, end, radius * radius, {}};
    q.box.expand(start);
    q.box.expand(end);
    q.box = q.box.padded(radius);
    return q;
}

RayQuery make_ray_query(const glm::dvec3& origin, const glm::dvec3& unit_dir, double max_distance) {
    if (!is_finite(origin) || !is_finite(unit_dir))
        throw Error("raycast: origin " + describe(origin) + " or direction " + describe(unit_dir) +
                    " is not finite");
    if (!(std::abs(glm::dot(unit_dir, unit_dir) - 1.0) <= 2e-6))
        throw Error("raycast: direction " + describe(unit_dir) + " is not unit length");
    if (!(max_distance >= 0.0))
        throw Error("raycast: max_distance must be >= 0, got " + exact_text(max_distance));
    RayQuery ray{origin, unit_dir, {}, max_distance};
    for (int a = 0; a < 3; ++a)
        ray.inv_dir[a] =
            unit_dir[a] != 0.0 ? 1.0 / unit_dir[a] : std::numeric_limits<double>::infinity();
    return ray;
}

std::vector<std::uint32_t> validate_and_keep(const TriangleMesh& mesh) {
    constexpr double kMax = StaticCollider::kMaxCoordinate;
    if (mesh.triangles.size() > StaticCollider::kMaxTriangles)
        throw Error("mesh has " + std::to_string(mesh.triangles.size()) +
                    " triangles, more than the collider limit " +
                    std::to_string(StaticCollider::kMaxTriangles));
    detail::check_surface_count(mesh);
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
        const glm::dvec3& v = mesh.vertices[i];
        if (!is_finite(v))
            throw Error("mesh vertex " + std::to_string(i) + " is not finite: " + describe(v));
        if (std::abs(v.x) > kMax || std::abs(v.y) > kMax || std::abs(v.z) > kMax)
            throw Error("mesh vertex " + std::to_string(i) + " " + describe(v) +
                        " is beyond the collider limit of 1e18 m");
    }
    std::vector<std::uint32_t> kept;
    kept.reserve(mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const auto& tri = mesh.triangles[t];
        for (int k = 0; k < 3; ++k)
            if (tri[k] >= mesh.vertices.size())
                throw Error("mesh triangle " + std::to_string(t) + " corner " + std::to_string(k) +
                            " refers to vertex " + std::to_string(tri[k]) + " but the mesh has " +
                            std::to_string(mesh.vertices.size()) + " vertices");
        const Triangle triangle(mesh.vertices[tri[0]], mesh.vertices[tri[1]],
                                mesh.vertices[tri[2]]);
        if (!triangle.is_degenerate()) kept.push_back(static_cast<std::uint32_t>(t));
    }
    return kept;
}

}  // namespace trackphys::collision_detail
