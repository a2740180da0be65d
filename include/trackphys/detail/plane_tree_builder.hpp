#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "trackphys/collision/plane_tree.hpp"
#include "trackphys/export.hpp"
#include "trackphys/geometry/normalized_triangle.hpp"
#include "trackphys/math/types.hpp"

namespace trackphys {

/// Builds PlaneTrees: the engine of make_collider_plane_tree and of MidPhase's per-update
/// tree, in an installed header only because MidPhase holds one by value. Keeps its scratch
/// between builds, and the target tree keeps its storage, so rebuilding per update over a
/// similar number of triangles on one thread does not allocate.
/// Deterministic: same triangles, ids and settings -> the same tree, bit for bit.
class TRACKPHYS_API PlaneTreeBuilder {
  public:
    /// Rebuilds `tree` over `triangles` (non-degenerate, finite), each tagged with the
    /// matching entry of `ids` (reported back by PlaneTree::id). Throws trackphys::Error when
    /// the spans differ in size, there are 2^30 triangles or more, or a setting is out of
    /// range (naming it). With `threads` other than 1 (0: one per core), a large build splits
    /// its first levels' nodes side by side and then builds the subtrees below them on that
    /// many threads; the tree is the one a single thread builds, bit for bit.
    void build(std::span<const NormalizedTriangle> triangles, std::span<const std::uint32_t> ids,
               const PlaneTreeSettings& settings, PlaneTree& tree, unsigned threads = 1);

    /// Bytes of scratch held between builds.
    std::size_t bytes_used() const;

  private:
    friend PlaneTree make_collider_plane_tree(const StaticCollider&, const PlaneTreeSettings&,
                                              PlaneTreeFrames, unsigned);
    // build() but the frames and boxes: the nodes, slabs, ids and depth.
    void build_nodes(std::span<const NormalizedTriangle> triangles,
                     std::span<const std::uint32_t> ids, const PlaneTreeSettings& settings,
                     PlaneTree& tree, unsigned threads);
    // The triangles' frames into `tree` in leaf order, after build_nodes.
    void copy_frames(std::span<const NormalizedTriangle> triangles, PlaneTree& tree) const;

    struct Item {
        std::array<glm::dvec3, 3> vertices;
        glm::dvec3 centroid;
        glm::dvec3 area_normal;  ///< cross(b - a, c - a)
    };
    struct Split {
        glm::dvec3 normal{0.0};  ///< float-exact direction
        std::size_t left_count = 0;
        double cost = 0.0;
    };

    // cost_based sweep scratch
    struct SweepEntry {
        double key;        ///< centroid along the direction
        double low, high;  ///< vertices along it
        std::uint32_t item;
    };
    // Written with < alone: a user header compiled with -Wfloat-equal must not warn. An
    // object rather than a function, which the sorts would call through a pointer.
    struct ByKeyThenItem {
        bool operator()(const SweepEntry& a, const SweepEntry& b) const {
            return a.key < b.key || (!(b.key < a.key) && a.item < b.item);
        }
    };
    /// What one thread splitting nodes writes besides its nodes' ranges of order_.
    struct Scratch {
        std::vector<SweepEntry> sweep;  ///< a node's items along one direction
        std::vector<double> suffix_low;
    };
    /// A split node's two children: the left one holds the range's first `left_count`
    /// items (in order_, once split), each child the plane that bounds its side.
    struct Children {
        std::size_t left_count = 0;
        std::array<PlaneTreeNode, 2> nodes{};
    };
    using Nodes = std::vector<PlaneTreeNode>;

    static void make_leaf(PlaneTreeNode& node, std::size_t begin, std::size_t end);
    // Appends the children to `nodes` as those of `node` (of `count` items); returns the
    // index of the left one.
    static std::uint32_t adopt(Nodes& nodes, std::uint32_t node, std::size_t count,
                               const Children& children);
    // The depth of the deepest leaf below `node`, whose subtree it builds into `nodes`.
    int build_node(Scratch& scratch, Nodes& nodes, std::uint32_t node, std::size_t begin,
                   std::size_t end, int depth);
    void build_nodes_in_parallel(unsigned threads);
    // Only builds of more triangles than this take several threads, and their nodes of at
    // most this many are always built whole by one.
    static constexpr std::size_t kSplitApartAbove = 4096;
    bool split(Scratch& scratch, std::size_t begin, std::size_t end, int depth, Children& children);
    void mark_slabs(std::uint32_t node, std::size_t begin, std::size_t end);
    bool choose_split(Scratch& scratch, std::size_t begin, std::size_t end, Split& split);
    Split pca_median_split(std::size_t begin, std::size_t end);
    bool cost_based_split(Scratch& scratch, std::size_t begin, std::size_t end, Split& split);
    // cost_based: nodes above kSweepAtMost triangles try only the kBins - 1 bin boundaries
    // along each candidate direction (linear time); smaller ones try every cut (a sort).
    static constexpr std::size_t kSweepAtMost = 32;
    static constexpr std::size_t kBins = 64;
    static constexpr std::size_t kCandidateDirections = 9;
    using Directions = std::array<glm::dvec3, kCandidateDirections>;
    void evaluate_direction(Scratch& scratch, std::size_t begin, std::size_t end,
                            const glm::dvec3& direction, Split& best);
    void evaluate_directions_binned(std::size_t begin, std::size_t end,
                                    const Directions& directions, Split& best);
    // Makes the cut `best` when it costs less.
    void consider_cut(Split& best, const glm::dvec3& normal, std::size_t left_count,
                      std::size_t count, double p_left, double p_right) const;
    void order_along(Scratch& scratch, std::size_t begin, std::size_t end, const glm::dvec3& normal,
                     std::size_t left_count);
    void set_plane(PlaneTreeNode& node, std::size_t begin, std::size_t end,
                   const glm::dvec3& normal) const;

    PlaneTreeSettings settings_;
    PlaneTree* tree_ = nullptr;
    std::vector<Item> items_;
    std::vector<std::uint32_t> order_;       ///< item indices; each node owns a range
    Scratch scratch_;                        ///< a single thread's
    std::vector<PlaneTreeSlab> node_slabs_;  ///< per node while marking, kept by slab nodes
};

}  // namespace trackphys
