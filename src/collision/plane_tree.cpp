#include "trackphys/collision/plane_tree.hpp"

#include <algorithm>
#include <bit>
#include <cstddef>
#include <type_traits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "collision/ellipsoid_filter_lanes.hpp"
#include "collision/plane_tree_shapes.hpp"
#include "core/cpu_features.hpp"
#include "trackphys/assert.hpp"
#include "trackphys/collision/plane_tree_frame_cache.hpp"

namespace trackphys {

using collision_detail::EllipsoidFilterLanes;
using collision_detail::EllipsoidShape;
using collision_detail::SphereShape;

namespace {

// The swept ellipsoid's filter on kept frames, N at a time: of the `count` candidate slots,
// keeps those the shape touches, in order and in place, and returns how many. A last block
// of fewer than N repeats its last frame in the lanes left over.
template <int N>
[[gnu::always_inline]] inline std::size_t filter_in_lanes(const EllipsoidShape& shape,
                                                          const NormalizedTriangle* frames,
                                                          std::uint32_t* slots, std::size_t count) {
    const EllipsoidFilterLanes<N> lanes(shape);
    std::size_t kept = 0;
    for (std::size_t k = 0; k < count; k += N) {
        const std::size_t block = std::min<std::size_t>(N, count - k);
        const NormalizedTriangle* triangles[N];
        for (std::size_t j = 0; j < N; ++j)
            triangles[j] = frames + slots[k + std::min(j, block - 1)];
        const auto decided = lanes.decide(triangles);
        for (std::size_t j = 0; j < block; ++j) {
            const unsigned bit = 1u << j;
            if ((decided.touched & bit) != 0 ||
                ((decided.undecided & bit) != 0 && shape.touches_exactly(*triangles[j])))
                slots[kept++] = slots[k + j];
        }
    }
    return kept;
}

#if defined(__x86_64__) || defined(__i386__)
// Four lanes, compiled for AVX2 whatever the library's x86-64 level (no FMA: the lanes must
// round as the scalar filter does). Call it only where cpu_has_avx2().
[[gnu::target("avx2")]] std::size_t filter_in_four_lanes(const EllipsoidShape& shape,
                                                         const NormalizedTriangle* frames,
                                                         std::uint32_t* slots, std::size_t count) {
    return filter_in_lanes<4>(shape, frames, slots, count);
}
#endif

// filter_in_lanes in the widest lanes this CPU runs: four with AVX2, else two (SSE2).
std::size_t filter_in_widest_lanes(const EllipsoidShape& shape, const NormalizedTriangle* frames,
                                   std::uint32_t* slots, std::size_t count) {
#if defined(__x86_64__) || defined(__i386__)
    if (detail::use_four_lanes()) return filter_in_four_lanes(shape, frames, slots, count);
#endif
    return filter_in_lanes<2>(shape, frames, slots, count);
}

}  // namespace

// Inlined into visit: a query filters a handful of small leaves, so a call would cost about
// as much as the work.
template <class Shape>
[[gnu::always_inline]] inline void PlaneTree::filter_leaf(const Shape& shape, std::uint32_t first,
                                                          std::uint32_t end,
                                                          std::vector<std::uint32_t>& out,
                                                          PlaneTreeFrameCache* frames,
                                                          PlaneTreeQueryCounts& counts) const {
    for (std::uint32_t run = first; run < end; run += PlaneTreeFrameCache::kMaxRun) {
        const std::uint32_t count = std::min(end - run, PlaneTreeFrameCache::kMaxRun);
        // The slots the filter runs on (bit k: slot run + k): those whose box the shape's box
        // meets, in a tree that keeps boxes (a leaf whose slots all fail costs no lookup, and
        // only the slots that pass pay for their frames), else all of them.
        std::uint64_t near = ~std::uint64_t{0} >> (64 - count);
        if (!boxes_.empty()) {
            near = 0;
            for (std::uint32_t k = 0; k < count; ++k)
                if (shape.reaches_box(boxes_[run + k])) near |= std::uint64_t{1} << k;
            if (near == 0) continue;
        }
        // The run's frames: the tree's own, the cache's, or none (each built in turn).
        const NormalizedTriangle* run_frames = !frames_.empty() ? frames_.data() + run
                                               : frames != nullptr
                                                   ? frames->run(*this, run, count, near)
                                                   : nullptr;
        for (; near != 0; near &= near - 1) {
            const auto k = static_cast<std::uint32_t>(std::countr_zero(near));
            const std::uint32_t slot = run + k;
            const bool touched = run_frames != nullptr
                                     ? shape.touches(run_frames[k])
                                     : shape.touches(collider_->normalized_triangle(ids_[slot]));
            if (!touched) continue;
            out.push_back(slot);
            if (frames != nullptr) frames->reported_.push_back(run_frames + k);
            ++counts.triangles_reported;
        }
    }
}

template <class Shape>
PlaneTreeQueryCounts PlaneTree::visit(const Shape& shape, std::vector<std::uint32_t>& out,
                                      std::uint32_t from_node, PlaneTreeFrameCache* frames) const {
    PlaneTreeQueryCounts counts;
    if (frames != nullptr) frames->reported_.clear();
    if (nodes_.empty()) return counts;
    TP_ASSERT(from_node < nodes_.size(), "plane tree query: start node out of range");
    // A swept ellipsoid on kept frames gathers its leaves' slots and filters them a batch at
    // a time in lanes (usually the whole query in one); only the kept ones reach `out`, so
    // a caller's storage grows no more than with the scalar filter.
    constexpr bool in_lanes = std::is_same_v<Shape, EllipsoidShape>;
    const bool lanes = in_lanes && !frames_.empty();
    constexpr std::size_t kBatch = 64;
    std::uint32_t batch[kBatch];
    std::size_t batched = 0;
    auto filter_batch = [&] {
        if constexpr (in_lanes) {
            const std::size_t kept = filter_in_widest_lanes(shape, frames_.data(), batch, batched);
            for (std::size_t k = 0; k < kept; ++k) {
                out.push_back(batch[k]);
                if (frames != nullptr) frames->reported_.push_back(frames_.data() + batch[k]);
            }
            counts.triangles_reported += kept;
        }
        batched = 0;
    };
    // A popped node at depth k leaves at most one pending sibling per level above it, and
    // pushes two children of depth k + 1 <= kMaxDepth: never more than kMaxDepth + 1 entries.
    std::uint32_t stack[PlaneTreeSettings::kMaxDepth + 1];
    int top = 0;
    stack[top++] = from_node;
    while (top > 0) {
        const std::uint32_t index = stack[--top];
        const PlaneTreeNode& node = nodes_[index];
        if (node.has_slab()) {
            ++counts.planes_tested;
            if (!shape.reaches_slab(slabs_[slab_index(index)])) continue;
        }
        if (node.is_leaf()) {
            counts.triangles_filtered += node.count();
            if (lanes)
                for (std::uint32_t slot = node.first; slot < node.first + node.count(); ++slot) {
                    if (batched == kBatch) filter_batch();
                    batch[batched++] = slot;
                }
            else
                filter_leaf(shape, node.first, node.first + node.count(), out, frames, counts);
            continue;
        }
        counts.planes_tested += 2;
        // Right first onto the stack so the left subtree (lower slots) comes out first and
        // the output is in ascending slot order.
        if (shape.reaches(nodes_[node.first + 1])) stack[top++] = node.first + 1;
        if (shape.reaches(nodes_[node.first])) stack[top++] = node.first;
        TP_ASSERT(top <= PlaneTreeSettings::kMaxDepth + 1, "plane tree deeper than kMaxDepth");
    }
    if (batched > 0) filter_batch();
    return counts;
}

PlaneTreeQueryCounts PlaneTree::query_sphere(const glm::dvec3& center, double radius,
                                             std::vector<std::uint32_t>& out,
                                             std::uint32_t from_node,
                                             PlaneTreeFrameCache* frames) const {
    return visit(SphereShape<false>(center, center, radius), out, from_node, frames);
}

PlaneTreeQueryCounts PlaneTree::query_swept_sphere(const glm::dvec3& start, const glm::dvec3& end,
                                                   double radius, std::vector<std::uint32_t>& out,
                                                   std::uint32_t from_node,
                                                   PlaneTreeFrameCache* frames) const {
    return visit(SphereShape<true>(start, end, radius), out, from_node, frames);
}

PlaneTreeQueryCounts PlaneTree::query_swept_ellipsoid(const Ellipsoid& ellipsoid,
                                                      const glm::dvec3& end, double margin,
                                                      std::vector<std::uint32_t>& out,
                                                      std::uint32_t from_node,
                                                      PlaneTreeFrameCache* frames) const {
    return visit(EllipsoidShape(ellipsoid, end, margin), out, from_node, frames);
}

std::uint32_t PlaneTree::entry_node(const Aabb& box) const {
    if (nodes_.empty() || box.empty()) return 0;
    const glm::dvec3 center = box.center(), half = 0.5 * box.extent();
    const double slack = collision_detail::kPlaneSlack * (1.0 + collision_detail::max_abs(center) +
                                                          collision_detail::max_abs(half));
    // The box reaches {n.x <= offset} when its lowest corner along n does.
    auto reaches = [&](const PlaneTreeNode& node) {
        const glm::dvec3 n = collision_detail::node_normal(node);
        return glm::dot(n, center) - glm::dot(glm::abs(n), half) - slack <= double(node.offset);
    };
    std::uint32_t index = 0;
    for (int depth = 0; depth < PlaneTreeSettings::kMaxDepth; ++depth) {
        const PlaneTreeNode& node = nodes_[index];
        if (node.is_leaf()) break;
        const bool left = reaches(nodes_[node.first]), right = reaches(nodes_[node.first + 1]);
        if (left == right) break;  // both reached (or, for a box off the tree, neither)
        index = left ? node.first : node.first + 1;
    }
    return index;
}

void PlaneTree::rank_slabs() {
    slab_ranks_.assign((nodes_.size() + 63) / 64, SlabRank{});
    std::uint64_t slabs = 0;
    for (std::size_t node = 0; node < nodes_.size(); ++node) {
        SlabRank& r = slab_ranks_[node / 64];
        if (node % 64 == 0) r.before = slabs;
        if (!nodes_[node].has_slab()) continue;
        r.bits |= std::uint64_t{1} << (node % 64);
        ++slabs;
    }
}

void PlaneTree::use_collider_frames(const StaticCollider& collider, PlaneTreeFrames frames) {
    collider_ = &collider;
    if (frames == PlaneTreeFrames::kept) {
        boxes_.clear();
        boxes_.shrink_to_fit();
        if (frames_.size() == ids_.size()) return;  // the builder's, from the same vertices
        frames_.clear();
        frames_.reserve(ids_.size());
        for (const std::uint32_t id : ids_) frames_.push_back(collider.normalized_triangle(id));
        return;
    }
    frames_.clear();
    frames_.shrink_to_fit();
    boxes_.resize(ids_.size());
    for (std::size_t slot = 0; slot < ids_.size(); ++slot)
        boxes_[slot] = collision_detail::float_box(collider.triangle(ids_[slot]));
}

std::size_t PlaneTree::bytes_used() const {
    return nodes_.capacity() * sizeof(PlaneTreeNode) + slabs_.capacity() * sizeof(PlaneTreeSlab) +
           slab_ranks_.capacity() * sizeof(SlabRank) + boxes_.capacity() * sizeof(PlaneTreeBox) +
           ids_.capacity() * sizeof(std::uint32_t) +
           frames_.capacity() * sizeof(NormalizedTriangle);
}

void PlaneTree::shrink_to_fit() {
    nodes_.shrink_to_fit();
    slabs_.shrink_to_fit();
    slab_ranks_.shrink_to_fit();
    boxes_.shrink_to_fit();
    ids_.shrink_to_fit();
    frames_.shrink_to_fit();
}

}  // namespace trackphys
