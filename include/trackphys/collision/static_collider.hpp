#pragma once

#include <array>
#include <bit>
#include <compare>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <type_traits>
#include <vector>

#include <glm/vec3.hpp>

#include "trackphys/detail/bvh_node.hpp"
#include "trackphys/export.hpp"
#include "trackphys/geometry/aabb.hpp"
#include "trackphys/geometry/normalized_triangle.hpp"
#include "trackphys/geometry/triangle.hpp"
#include "trackphys/geometry/triangle_mesh.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

namespace detail {
struct MapCodec;
}

/// The closest hit of a ray cast.
struct RayHit {
    double distance;         ///< along the unit direction from the origin (m), in [0, max]
    std::uint32_t triangle;  ///< index into the mesh's triangle list as given
    glm::dvec3 normal;       ///< the triangle's unit CCW normal (not flipped toward the ray)
};

/// One triangle of one collider, as the world-level queries report it.
struct TriangleRef {
    std::uint32_t collider;  ///< id given by StaticWorld::add
    std::uint32_t triangle;  ///< index into that collider's mesh triangle list

    /// Ordered by collider, then triangle (sort candidates for a deterministic order).
    auto operator<=>(const TriangleRef&) const = default;
    /// Equal members, tested as one 64-bit word: the defaulted == compares the two members
    /// with two compares and a branch, and the exact phase looks a survivor up among the
    /// last deepest and the recent normals.
    constexpr bool operator==(const TriangleRef& other) const {
        static_assert(std::has_unique_object_representations_v<TriangleRef> &&
                      sizeof(TriangleRef) == sizeof(std::uint64_t));
        return std::bit_cast<std::uint64_t>(*this) == std::bit_cast<std::uint64_t>(other);
    }
};

/// A static triangle mesh ready for queries: validated, degenerate triangles dropped and
/// counted, and a binned-SAH BVH over the rest (docs/design.md#broad-phase-the-bvh).
/// Immutable after construction, so one collider can be shared by any number of threads.
///
/// Every query has the exact meaning of its BruteForceCollider twin and returns exactly
/// the same triangles: the BVH only skips what the predicate provably rejects.
/// - query_aabb: the triangle's box (min/max of its double vertices) overlaps the query
///   box, closed intervals as Aabb::overlaps.
/// - query_sphere / query_capsule: the triangle's box overlaps the query shape's box, and
///   its distance to the center (or segment), computed in double, is <= radius.
/// - raycast: the closest hit on either face (Moller-Trumbore in double) at a distance >= 0
///   along the ray (the line crossing a triangle behind the origin is no hit), the distance
///   clamped into the ray's span through the triangle's box; equal distances go to the
///   lower index.
/// Queries append to caller-owned vectors and use a fixed stack: no allocation once the
/// vectors have grown to their working size.
///
/// Layout (bytes_used() counts it all): vertices in double, re-ordered by first use in leaf
/// order and without unused ones (24 bytes each, ~12 a triangle on a shared-vertex mesh);
/// per triangle, in leaf order, its three vertex indices (12), and its box in 16 bits,
/// rounded outward in a grid over its subtree of up to 4096 triangles (12), beside its mesh
/// index (4) in 128-byte blocks of eight (BvhSlotBlock: one SSE2 16-bit compare per bound
/// tests a block, and the indices it reports share its cache lines); the inverse map mesh
/// index -> leaf slot (4); ~0.003 eight-wide 256-byte nodes (~0.8: a leaf lane holds up to
/// 96 triangles, in the order of the SAH leaves of up to 32 it was made of), each with the
/// index of its 48-byte grids (~0.1). About 45 bytes a triangle on a track mesh, ~105 on a
/// soup of unshared vertices. The box queries test the 16-bit
/// boxes eight at a time and read a triangle's vertices only when its box lies within about
/// two grid steps of the query's (sphere and capsule: for the distance test).
/// NormalizedTriangle frames are not stored here: 120 bytes in double would nearly triple
/// the ~45 bytes a triangle, and every exact predicate needs the double vertices anyway.
/// A world's plane trees keep them instead when they fit kPlaneTreeFrameBudget (a generated
/// track's do); otherwise the mid phase builds the frames it culls with
/// normalized_triangle(). Surface ids, when
/// the mesh has any but 0, by mesh index (2 bytes a triangle).
class TRACKPHYS_API StaticCollider {
  public:
    /// Largest accepted |coordinate| (m): node bounds are float, and 1e18 m keeps every
    /// bound, area and SAH cost finite.
    static constexpr double kMaxCoordinate = 1e18;
    /// Largest number of mesh triangles (slot and node indices use 31 bits).
    static constexpr std::size_t kMaxTriangles = 0x7fff'ffffu;

    /// Validates the mesh and builds the BVH. Throws trackphys::Error naming the vertex or
    /// triangle when a coordinate is not finite (or beyond kMaxCoordinate), an index is out
    /// of range, or there are more than kMaxTriangles triangles.
    explicit StaticCollider(const TriangleMesh& mesh);

    /// Throws what the constructor would throw for this mesh, without building the BVH:
    /// whether a collider accepts the mesh, for one pass over it (trackphys info).
    static void check(const TriangleMesh& mesh);

    /// Appends to `out` the mesh index of every kept triangle whose box overlaps `box`.
    void query_aabb(const Aabb& box, std::vector<std::uint32_t>& out) const;
    /// query_aabb appending (collider_id, triangle) pairs instead (the world's broad phase;
    /// a separate name keeps query_aabb a single, pinned signature).
    void query_aabb_refs(const Aabb& box, std::uint32_t collider_id,
                         std::vector<TriangleRef>& out) const;
    /// Appends every kept triangle within `radius` (m, finite, >= 0) of `center`.
    /// Throws trackphys::Error on a non-finite center or a bad radius.
    void query_sphere(const glm::dvec3& center, double radius,
                      std::vector<std::uint32_t>& out) const;
    /// Appends every kept triangle within `radius` of the segment [start, end]: the triangles a
    /// sphere of that radius touches while it moves from start to end (a swept sphere).
    void query_capsule(const glm::dvec3& start, const glm::dvec3& end, double radius,
                       std::vector<std::uint32_t>& out) const;
    /// The closest triangle hit by the ray origin + t * unit_dir, t in [0, max_distance].
    /// Throws trackphys::Error if unit_dir is not unit length (within 1e-6), or an input is
    /// not finite (max_distance may be +infinity) or max_distance is negative.
    std::optional<RayHit> raycast(const glm::dvec3& origin, const glm::dvec3& unit_dir,
                                  double max_distance) const;

    /// Number of triangles in the mesh as given (valid triangle indices are below it).
    std::size_t mesh_triangle_count() const { return triangle_to_slot_.size(); }
    /// Number of triangles kept (the mesh's minus the degenerate ones).
    std::size_t triangle_count() const { return slot_vertices_.size(); }
    /// Number of degenerate triangles dropped at build (Triangle::is_degenerate()).
    std::size_t degenerate_count() const { return mesh_triangle_count() - triangle_count(); }
    /// True when mesh triangle `index` was kept (in range and not degenerate).
    bool has_triangle(std::uint32_t index) const;
    /// The kept mesh triangle `index` with its vertices exactly as given. Throws
    /// trackphys::Error when the index is out of range or the triangle was dropped.
    Triangle triangle(std::uint32_t index) const;
    /// The NormalizedTriangle of kept triangle `index`, built on demand (see class notes).
    NormalizedTriangle normalized_triangle(std::uint32_t index) const;

    /// The surface id of mesh triangle `index` (TriangleMesh::surfaces, 0 when the mesh gave
    /// none), kept or dropped. Throws trackphys::Error past mesh_triangle_count().
    SurfaceId surface(std::uint32_t index) const;
    /// Every mesh triangle's surface id, by mesh index; empty when all are 0 (a mesh without
    /// ids). The world reads it at each sub-step for the triangle under each wheel.
    std::span<const SurfaceId> surfaces() const { return surfaces_; }
    /// The highest surface id of a kept triangle (0 when none): a World refuses a surface
    /// table that does not reach it.
    SurfaceId highest_surface() const;

    /// A fingerprint of the mesh as kept: a hash of the mesh triangle count and of every kept
    /// triangle's index and vertex bits, in mesh order, and of their surface ids when any is
    /// not 0. Equal meshes give equal hashes; a moved vertex, another triangle, another order
    /// or another surface id give another. Computed at build (a small share of building the
    /// collider), so a world snapshot can tell whether it belongs to these colliders without
    /// copying them.
    std::uint64_t content_hash() const { return content_hash_; }

    /// Box around every kept triangle (empty when none was kept).
    const Aabb& bounds() const { return bounds_; }
    /// The eight-wide BVH nodes: root at 0 (when there is a triangle), covering leaf slots
    /// [0, triangle_count()).
    const std::vector<BvhNode>& nodes() const { return nodes_; }
    /// Bytes of every structure the collider keeps (vector capacities included).
    std::size_t bytes_used() const;

  private:
    // Map files (src/io/map_codec.cpp) store these arrays as they are and fill them back.
    friend struct detail::MapCodec;
    StaticCollider() = default;

    // A world's box query starts loading the first lines of every collider it will query
    // (root node, its grids, the first slot blocks) before it queries the first, so that
    // their cache and TLB misses overlap instead of following one another.
    friend class StaticWorld;
    void prefetch_box_query() const;

    // Leaf slot s holds mesh triangle slot_triangle(s); its vertices are
    // vertices_[slot_vertices_[s][k]], in the mesh's order (winding kept).
    template <class Sink>
    void visit_aabb(const Aabb& box, Sink& sink) const;
    template <class Predicate>
    void visit_box_filtered(const Aabb& box, Predicate&& keep,
                            std::vector<std::uint32_t>& out) const;
    bool triangle_box_overlaps(std::uint32_t slot, const Aabb& box) const;
    void quantize_slot_boxes();
    // The quantized boxes of the block of eight slots from s (a multiple of 8).
    const std::int16_t* block(std::uint32_t s) const {
        return slot_blocks_[s / BvhSlotBlock::kLanes].box[0];
    }
    std::uint32_t slot_triangle(std::uint32_t s) const {
        return slot_blocks_[s / BvhSlotBlock::kLanes].triangle[s % BvhSlotBlock::kLanes];
    }

    std::vector<glm::dvec3> vertices_;
    std::vector<std::array<std::uint32_t, 3>> slot_vertices_;
    std::vector<std::uint32_t> triangle_to_slot_;
    // Slot boxes, quantized in their leaf's grid, and mesh indices, eight slots a block.
    std::vector<BvhSlotBlock> slot_blocks_;
    std::vector<BvhNode> nodes_;
    std::vector<BvhNodeGrid> grids_;        // the grids of the slot boxes, shared by node groups
    std::vector<std::uint32_t> node_grid_;  // per node with leaf lanes: its grids_ index
    double inside_extent_[3] = {0.0, 0.0, 0.0};  // box extents to look for whole lanes from
    std::vector<SurfaceId> surfaces_;            // by mesh index; empty when all are 0
    Aabb bounds_;
    std::uint64_t content_hash_ = 0;
};

}  // namespace trackphys
