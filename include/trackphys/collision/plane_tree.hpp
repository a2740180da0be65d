#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "trackphys/assert.hpp"
#include "trackphys/collision/static_collider.hpp"
#include "trackphys/export.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/geometry/normalized_triangle.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

class PlaneTreeFrameCache;
namespace detail {
struct MapCodec;
}

/// One node of a PlaneTree: the half-space {x : dot(normal, x) <= offset} that holds every
/// triangle of its subtree. Nodes live in one vector, root at 0, the two children of an
/// inner node adjacent at `first` and `first + 1` (the BVH layout,
/// docs/design.md#data-layouts). The root's half-space is all of space (normal 0, offset +inf).
///
/// The normal is stored in float and the offset is computed in double over the triangles'
/// vertices with exactly that float normal, then rounded up to float: the stored plane never
/// cuts into its triangles, only grows outward by at most one float ulp of the offset.
struct PlaneTreeNode {
    static constexpr std::uint32_t kLeafBit = 0x8000'0000u;
    static constexpr std::uint32_t kSlabBit = 0x4000'0000u;
    static constexpr std::uint32_t kCountMask = 0x3fff'ffffu;

    float normal[3];       ///< 12 bytes: unit normal of the bounding plane (outward)
    float offset;          ///<  4 bytes: dot(normal, x) <= offset on every triangle (m)
    std::uint32_t first;   ///<  4 bytes: leaf: first triangle slot; inner: left child index
    std::uint32_t packed;  ///<  4 bytes: kLeafBit | kSlabBit | triangles in the subtree

    bool is_leaf() const { return (packed & kLeafBit) != 0; }
    /// True when PlaneTree::slab(this node) holds a slab to test (see PlaneTreeSettings).
    bool has_slab() const { return (packed & kSlabBit) != 0; }
    /// Number of triangles in the subtree (a leaf's own triangles).
    std::uint32_t count() const { return packed & kCountMask; }
};
static_assert(sizeof(PlaneTreeNode) == 24, "PlaneTreeNode is 24 bytes: a sibling pair is 48");

/// The slab {low <= dot(normal, x) <= high} that holds every triangle of a node's subtree,
/// for nodes whose triangles are nearly coplanar (a stretch of road, a wall face). Same
/// rounding as the node planes: normal in float (length <= 1), bounds rounded outward.
struct PlaneTreeSlab {
    float normal[3];  ///< 12 bytes: the subtree's mean surface normal
    float low;        ///<  4 bytes (m), rounded down
    float high;       ///<  4 bytes (m), rounded up
};
static_assert(sizeof(PlaneTreeSlab) == 20, "PlaneTreeSlab is 20 bytes");

/// The box of one leaf slot's triangle, in float rounded outward: the cheap first test of
/// the per-triangle filter, which reads the triangle's double frame only for the slots whose
/// box the query shape's box reaches.
struct PlaneTreeBox {
    float low[3];   ///< 12 bytes (m), rounded down
    float high[3];  ///< 12 bytes (m), rounded up
};
static_assert(sizeof(PlaneTreeBox) == 24, "PlaneTreeBox is 24 bytes");

/// Where a collider's PlaneTree gets its triangles' frames (NormalizedTriangle, 120 bytes)
/// for the per-triangle filter: a memory-for-speed choice that leaves every query's result
/// unchanged (the frames are the same, bit for bit).
enum class PlaneTreeFrames {
    /// Built by the queries from the collider's vertices for the slots whose float box the
    /// query shape's box meets, and kept in the caller's PlaneTreeFrameCache: ~51 bytes a
    /// triangle for a track collider's tree.
    built,
    /// Kept by the tree in leaf order (~147 bytes a triangle): the filter reads them in
    /// place, with no box test and no cache lookup.
    kept,
};

/// The frame bytes a world's collider plane trees may keep (64 MiB): a generated track's
/// trees keep theirs, shared by every car; a map of millions of triangles has its frames
/// built by the queries, within the memory a big map is allowed (docs/benchmarks.md).
inline constexpr std::size_t kPlaneTreeFrameBudget = std::size_t{64} << 20;

/// The frame source of the plane trees of a world of `triangles` kept triangles: kept when
/// their frames fit in `budget_bytes`, else built.
inline PlaneTreeFrames plane_tree_frames_within(std::size_t triangles, std::size_t budget_bytes) {
    return triangles <= budget_bytes / sizeof(NormalizedTriangle) ? PlaneTreeFrames::kept
                                                                  : PlaneTreeFrames::built;
}

/// How a PlaneTree chooses its splitting planes.
enum class PlaneSplitRule {
    /// The write-up's rule: the primary eigenvector n of the triangle centroids' covariance
    /// (PCA), triangles ordered along n and cut in half at the median centroid. Fast enough
    /// to run per update over a few hundred broad-phase candidates.
    pca_median,
    /// For trees built once per collider: the cut that minimises the expected query work
    /// (see PlaneTreeSettings::query_radius) over candidate directions (the three PCA axes
    /// of the centroids, the three coordinate axes, the dominant surface normal from the PCA
    /// of the area-weighted triangle normals, and the centroids' two principal directions
    /// within that surface, i.e. the road's local tangent and width direction) and every
    /// cut position along each; in nodes of more than 32 triangles, the boundaries of 64
    /// equal-width bins of the centroids along each (a binned sweep: linear time, not a
    /// sort per direction).
    cost_based,
};

/// Build settings of a PlaneTree. Use the named presets; the builder validates them.
struct PlaneTreeSettings {
    /// The deepest a node can sit (root depth 0); a node there becomes a leaf whatever its
    /// size. Queries use a fixed stack of kMaxDepth + 1 entries.
    static constexpr int kMaxDepth = 48;

    PlaneSplitRule rule = PlaneSplitRule::pca_median;
    /// pca_median: nodes with at most this many triangles are leaves. cost_based: nodes
    /// with more are always split; smaller ones are split only when that is predicted to
    /// be cheaper. In [1, 64].
    int max_leaf_size = 4;
    /// cost_based only: the typical query sphere radius (m, > 0). A query that reaches a node
    /// is assumed uniformly placed along the split direction over the node's extent grown
    /// by this radius on both sides, so a child is reached with probability
    /// (child extent + 2 r) / (node extent + 2 r) along that direction; the cost of a split
    /// is 2 node_cost (the two child planes) + sum(child triangles * that probability), in
    /// units of one triangle filter: the SAH with the plane test's own geometry. A node is
    /// a leaf when that is not below its triangle count.
    double query_radius = 0.5;
    /// cost_based only: cost of testing one child plane relative to one triangle filter
    /// (> 0).
    double node_cost = 0.5;
    /// Slabs (m, finite, >= 0; 0 = none): the first node on each path from the root whose
    /// triangles lie within a slab this thick along their mean surface normal (the
    /// normalised sum of their area normals) keeps that slab, and a query that misses it
    /// skips the node. Split planes alone cannot exclude a shape that hovers over a surface
    /// (every split runs across the road), so without slabs a car body above the road
    /// descends to the leaves; with them it stops at the first flat stretch.
    double slab_thickness = 0.0;

    /// Empty when a tree can be built with these settings; else the first problem, naming
    /// the field ("PlaneTreeSettings.node_cost must be finite and > 0, got nan").
    TRACKPHYS_API std::string validate() const;

    /// The write-up's per-update tree: PCA median splits, leaves of up to 4 triangles.
    static PlaneTreeSettings per_update() { return {}; }
    /// The precomputed per-collider tree: cost-based splits, leaves of up to 4 triangles,
    /// slabs 0.2 m thick (a body ellipsoid rides ~0.4 m above the road).
    static PlaneTreeSettings precomputed() {
        PlaneTreeSettings s;
        s.rule = PlaneSplitRule::cost_based;
        s.slab_thickness = 0.2;
        return s;
    }
};

/// What one query did: nodes whose plane was tested and triangles run through the
/// per-triangle filter (the work), and triangles reported.
struct PlaneTreeQueryCounts {
    std::size_t planes_tested = 0;
    std::size_t triangles_filtered = 0;
    std::size_t triangles_reported = 0;
};

/// A plane tree over a set of triangles (docs/design.md#mid-phase-plane-trees): each inner
/// node splits its triangles in two and each child keeps the plane that bounds its side,
/// so a query visits a child only if its shape reaches that child's half-space. Built by
/// PlaneTreeBuilder (per update, reusing storage) or make_collider_plane_tree (once per
/// collider). Immutable between builds; queries are const and thread-safe.
///
/// Storage: two vectors as the BVH, nodes (24 bytes) and per leaf slot its caller id
/// (4 bytes), plus, when built with slabs, a 20-byte slab per slab node, and the frame
/// source (PlaneTreeFrames). A collider's tree built with PlaneTreeFrames::built keeps per
/// slot its triangle's box (PlaneTreeBox, 24 bytes; ~51 bytes a triangle in all for a track
/// collider) and no frames: its queries build the frames of the few slots whose box they
/// reach from the collider's vertices, exactly the frames StaticCollider::normalized_triangle
/// gives. With PlaneTreeFrames::kept it keeps those frames in leaf order instead of the
/// boxes. A tree built from frames (PlaneTreeBuilder) keeps a copy of them and the boxes.
/// Queries append leaf slots in ascending order to a caller-owned vector and use a fixed
/// stack: no allocation once the vector has grown.
///
/// The per-triangle filter, and why the tree is exact with it. A query shape S (sphere,
/// swept sphere, swept ellipsoid) reports slot s if and only if S touches the triangle:
/// - sphere: the distance from the center to the triangle is <= radius;
/// - swept sphere: the distance from the segment to the triangle is <= radius;
/// - swept ellipsoid: the triangle mapped into the ellipsoid's unit-ball frame
///   (x -> D^-1 Q^T (x - start)) lies within 1 of the mapped segment, which is exactly
///   "the ellipsoid moving along the segment touches the triangle".
/// Each is computed in double in the triangle's own frame, after cheap rejections that are
/// lower bounds of the distance to convex sets holding the triangle (its plane, its local
/// box, its edges' half-planes), which can only reject what the exact test rejects too, and
/// sure accepts (a vertex or an over-the-face endpoint within reach); before all of them, in
/// a tree that keeps boxes, the slot's float box against the shape's box (a triangle the
/// shape touches lies in both).
/// Because a node's half-space (and slab) contains each of its triangles, a shape that
/// touches a triangle reaches every half-space above it: the tree never prunes a triangle
/// the filter would report, so a query returns exactly the slots a brute-force scan with the
/// same filter returns (plane and box tests are made with the shape grown by a slack of
/// 1e-10 of its coordinate scale, which covers the rounding of both tests). A box-based cull
/// such as NormalizedTriangle::may_touch_sphere as the filter would not give this equality:
/// it keeps triangles whose box corner the sphere reaches while some node plane through the
/// triangle's vertex already excludes the sphere.
class TRACKPHYS_API PlaneTree {
  public:
    /// An empty tree (every query reports nothing).
    PlaneTree() = default;

    /// Appends every slot whose triangle is within `radius` (m, finite, >= 0) of `center`.
    /// Throws trackphys::Error on a non-finite center or a bad radius.
    /// Every query can start at `from_node` instead of the root: pass entry_node(box) for a
    /// box that holds the query's shape and the result is the same with fewer planes tested.
    /// Given `frames`, the filter of a tree that keeps no frames reads them from that cache
    /// (building the missing ones into it), and with any tree frames->reported() holds the
    /// reported slots' frames afterwards, in the order of the slots appended to `out`.
    PlaneTreeQueryCounts query_sphere(const glm::dvec3& center, double radius,
                                      std::vector<std::uint32_t>& out, std::uint32_t from_node = 0,
                                      PlaneTreeFrameCache* frames = nullptr) const;
    /// Appends every slot whose triangle is within `radius` of the segment [start, end]: the
    /// triangles a sphere of that radius touches while it moves from start to end.
    PlaneTreeQueryCounts query_swept_sphere(const glm::dvec3& start, const glm::dvec3& end,
                                            double radius, std::vector<std::uint32_t>& out,
                                            std::uint32_t from_node = 0,
                                            PlaneTreeFrameCache* frames = nullptr) const;
    /// Appends every slot whose triangle the ellipsoid touches while its center moves from
    /// ellipsoid.center() to `end` with its orientation fixed. A car's ellipsoid also turns
    /// during a step: pass a `margin` (m, finite, >= 0) that bounds how far any of its points
    /// moves beyond the translation; the query then uses the ellipsoid scaled about its center
    /// by 1 + margin / (smallest semi-axis), which holds the ellipsoid grown by margin.
    PlaneTreeQueryCounts query_swept_ellipsoid(const Ellipsoid& ellipsoid, const glm::dvec3& end,
                                               double margin, std::vector<std::uint32_t>& out,
                                               std::uint32_t from_node = 0,
                                               PlaneTreeFrameCache* frames = nullptr) const;

    /// Where queries inside `box` can start (a car's update box, once per update): the
    /// first node on the path from the root at which the box reaches both children. The
    /// sibling subtrees left behind lie beyond planes the box does not reach, so no shape
    /// inside the box touches their triangles; starting below the root skips only tests,
    /// never a result. 0 (the root) for an empty tree or an empty box.
    std::uint32_t entry_node(const Aabb& box) const;

    /// Number of triangles (slots are 0 .. triangle_count() - 1).
    std::size_t triangle_count() const { return ids_.size(); }
    /// The frame of the triangle in leaf slot `slot` (TP_ASSERT on range): the tree's copy,
    /// or, for a collider's tree that keeps none, built from the collider's vertices.
    NormalizedTriangle triangle(std::uint32_t slot) const {
        TP_ASSERT(slot < ids_.size(), "plane tree slot out of range");
        return frames_.empty() ? collider_->normalized_triangle(ids_[slot]) : frames_[slot];
    }
    /// True when the tree keeps its triangles' frames (PlaneTreeFrames::kept, or a tree
    /// built from frames): queries read them in place.
    bool keeps_frames() const { return !frames_.empty(); }
    /// The caller's id of the triangle in slot `slot`, as given to the builder.
    std::uint32_t id(std::uint32_t slot) const {
        TP_ASSERT(slot < ids_.size(), "plane tree slot out of range");
        return ids_[slot];
    }
    /// The nodes, root at 0.
    const std::vector<PlaneTreeNode>& nodes() const { return nodes_; }
    /// The slab of node `node`, which has_slab() (TP_ASSERT).
    const PlaneTreeSlab& slab(std::uint32_t node) const {
        TP_ASSERT(node < nodes_.size() && nodes_[node].has_slab(), "plane tree node has no slab");
        return slabs_[slab_index(node)];
    }
    /// Number of nodes with a slab.
    std::size_t slab_count() const { return slabs_.size(); }
    /// Depth of the deepest leaf (0 for a single leaf).
    int depth() const { return depth_; }
    /// Bytes of every structure the tree keeps (vector capacities included).
    std::size_t bytes_used() const;
    /// Releases spare capacity (for a tree kept for long; per-update trees keep it).
    void shrink_to_fit();

  private:
    friend class PlaneTreeBuilder;
    friend struct detail::MapCodec;  // map files (src/io/map_codec.cpp)
    friend PlaneTree make_collider_plane_tree(const StaticCollider&, const PlaneTreeSettings&,
                                              PlaneTreeFrames, unsigned);

    template <class Shape>
    PlaneTreeQueryCounts visit(const Shape& shape, std::vector<std::uint32_t>& out,
                               std::uint32_t from_node, PlaneTreeFrameCache* frames) const;
    // The per-triangle filter over leaf slots [first, end), in slot order.
    template <class Shape>
    void filter_leaf(const Shape& shape, std::uint32_t first, std::uint32_t end,
                     std::vector<std::uint32_t>& out, PlaneTreeFrameCache* frames,
                     PlaneTreeQueryCounts& counts) const;
    // Makes the tree a tree of `collider` (ids_ are its mesh indices) with that frame
    // source: kept, the frames built from the collider's vertices in leaf order (or the
    // builder's, the same ones) and no boxes; built, no frames and the boxes from the
    // collider's vertices. The same frames and boxes whether the tree was just built or
    // loaded from a map file.
    void use_collider_frames(const StaticCollider& collider, PlaneTreeFrames frames);
    // Slabs are kept for the nodes that have one only (about one node in four on a track),
    // in node order; a node's slab is the one after those of the slab nodes before it,
    // counted with a bit per node and a running count per 64 nodes.
    struct SlabRank {
        std::uint64_t bits = 0;    ///< bit k: node 64 i + k has a slab
        std::uint64_t before = 0;  ///< slab nodes below 64 i
    };
    void rank_slabs();
    std::size_t slab_index(std::uint32_t node) const {
        const SlabRank& r = slab_ranks_[node / 64];
        return static_cast<std::size_t>(r.before) +
               static_cast<std::size_t>(
                   std::popcount(r.bits & ((std::uint64_t{1} << (node % 64)) - 1)));
    }

    std::vector<PlaneTreeNode> nodes_;
    std::vector<PlaneTreeSlab> slabs_;          ///< per slab node, in node order
    std::vector<SlabRank> slab_ranks_;          ///< per 64 nodes, derived from the nodes
    std::vector<PlaneTreeBox> boxes_;           ///< leaf order; empty: no box test
    std::vector<std::uint32_t> ids_;            ///< leaf order
    std::vector<NormalizedTriangle> frames_;    ///< leaf order; empty: built from collider_
    const StaticCollider* collider_ = nullptr;  ///< a collider's tree: its collider
    int depth_ = 0;
};

/// The precomputed plane tree of a collider: every kept triangle, cost-based splits
/// (PlaneTreeSettings::precomputed() unless given), ids = mesh triangle indices, so that
/// PlaneTree::id(slot) is what StaticCollider::triangle() takes, and the frame source
/// `frames` (a world's trees choose it with plane_tree_frames_within). Built from the
/// collider rather than stored in it: StaticCollider stays the broad phase's compact
/// structure (~48 bytes a triangle) and worlds that use no precomputed mid phase pay
/// nothing. The tree reads the collider's vertices: `collider` must outlive it (a
/// StaticWorld's colliders do, as long as the world lives). Built on up to `threads`
/// threads (0: one per core; PlaneTreeBuilder::build), the same tree whatever their count.
TRACKPHYS_API PlaneTree
make_collider_plane_tree(const StaticCollider& collider,
                         const PlaneTreeSettings& settings = PlaneTreeSettings::precomputed(),
                         PlaneTreeFrames frames = PlaneTreeFrames::built, unsigned threads = 1);

}  // namespace trackphys
