#include "trackphys/collision/static_collider.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <limits>
#include <string>

#include "bvh_builder.hpp"
#include "bvh_lanes.hpp"
#include "core/fnv1a.hpp"
#include "lane_compaction.hpp"
#include "quantized_boxes.hpp"
#include "trackphys/assert.hpp"
#include "trackphys/error.hpp"
#include "triangle_predicates.hpp"

namespace trackphys {

using collision_detail::AxisGrid;
using collision_detail::BoxLanes;
using collision_detail::kMaxTraversalStack;
using collision_detail::QuantizedBlock;
using collision_detail::QuantizedQuery;
using collision_detail::QueryLanes;

namespace {

constexpr std::uint32_t kNoSlot = std::numeric_limits<std::uint32_t>::max();
// Slots up to which a subtree's nodes share one set of grids (quantize_slot_boxes), so that
// a query quantizes its box once for all of those it visits: larger groups reuse more, but
// their steps, a few mm, leave more slots near a query bound to the exact test: 4096 was the
// fastest of 1024, 4096 and 16384 on default-track car boxes.
constexpr std::uint32_t kGridGroupSlots = 4096;
// Box queries look for whole lanes inside the box (reported without testing their
// triangles) only when the box spans this many mean leaf lanes on every axis: a smaller box
// rarely holds a whole lane, and the test costs more than it saves (car boxes, about 2.7
// mean leaves across, are faster without it; boxes padded by 5 or 20 m, which use it, take
// the same time).
constexpr double kInsideShortcutLeaves = 4.0;
// Slot blocks of a collider small enough that a world's box query prefetches them all (a
// 98-triangle tile has 13: 26 lines).
constexpr std::size_t kPrefetchBlocks = 16;
// Slots in one block.
constexpr std::uint32_t kBlockSlots = QuantizedBlock::kLanes;
static_assert(BvhSlotBlock::kLanes == kBlockSlots &&
              sizeof(BvhSlotBlock::box) == sizeof(QuantizedBlock));

// Calls visit(s, lanes) for each block of eight slots from s (a multiple of 8) that the
// slot range [first, end) (first < end) touches, `lanes` its lanes inside the range: all
// eight but in the first block and the last, so the bounds cost a select per block, not
// two clamped shifts (car boxes test ~37 blocks each).
template <class Visit>
void for_each_block(std::uint32_t first, std::uint32_t end, Visit&& visit) {
    unsigned lanes = (0xffu << (first % kBlockSlots)) & 0xffu;
    const unsigned last_lanes = 0xffu >> (kBlockSlots - 1 - (end - 1) % kBlockSlots);
    for (std::uint32_t s = first & ~(kBlockSlots - 1);; s += kBlockSlots) {
        const bool last = end - s <= kBlockSlots;
        visit(s, lanes & (last ? last_lanes : 0xffu));
        if (last) return;
        lanes = 0xffu;
    }
}
int lowest_lane(unsigned mask) { return std::countr_zero(mask); }
int highest_lane(unsigned mask) { return 31 - std::countl_zero(mask); }

glm::dvec3 lane_min(const BvhNode& n, int i) { return {n.min[0][i], n.min[1][i], n.min[2][i]}; }
glm::dvec3 lane_max(const BvhNode& n, int i) { return {n.max[0][i], n.max[1][i], n.max[2][i]}; }

template <class T>
std::size_t capacity_bytes(const std::vector<T>& v) {
    return v.capacity() * sizeof(T);
}

}  // namespace

void StaticCollider::check(const TriangleMesh& mesh) {
    static_cast<void>(collision_detail::validate_and_keep(mesh));
}

StaticCollider::StaticCollider(const TriangleMesh& mesh) {
    const std::vector<std::uint32_t> kept = collision_detail::validate_and_keep(mesh);

    std::vector<collision_detail::BuildPrimitive> primitives(kept.size());
    for (std::size_t i = 0; i < kept.size(); ++i) {
        const auto& tri = mesh.triangles[kept[i]];
        const Aabb box = collision_detail::triangle_box(
            mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]);
        bounds_.expand(box);
        primitives[i] = {collision_detail::outward_float_box(box), static_cast<std::uint32_t>(i)};
    }
    collision_detail::BuiltBvh bvh = collision_detail::build_bvh(std::move(primitives));
    nodes_ = std::move(bvh.nodes);

    // Permute the triangles into leaf order, and the vertices into the order in which the
    // leaves first use them, so that neighbouring leaves read neighbouring memory.
    const std::size_t n = kept.size();
    slot_vertices_.resize(n);
    slot_blocks_.assign((n + kBlockSlots - 1) / kBlockSlots, BvhSlotBlock{});
    triangle_to_slot_.assign(mesh.triangles.size(), kNoSlot);
    std::vector<std::uint32_t> vertex_remap(mesh.vertices.size(), kNoSlot);
    std::uint32_t used_vertices = 0;
    for (std::size_t slot = 0; slot < n; ++slot) {
        const std::uint32_t triangle = kept[bvh.order[slot]];
        slot_blocks_[slot / kBlockSlots].triangle[slot % kBlockSlots] = triangle;
        triangle_to_slot_[triangle] = static_cast<std::uint32_t>(slot);
        for (int k = 0; k < 3; ++k) {
            std::uint32_t& remapped = vertex_remap[mesh.triangles[triangle][k]];
            if (remapped == kNoSlot) remapped = used_vertices++;
            slot_vertices_[slot][k] = remapped;
        }
    }
    vertices_.resize(used_vertices);
    for (std::size_t v = 0; v < vertex_remap.size(); ++v)
        if (vertex_remap[v] != kNoSlot) vertices_[vertex_remap[v]] = mesh.vertices[v];

    // All zeros is stored as none: the queries and the world then skip the lookup.
    if (std::any_of(mesh.surfaces.begin(), mesh.surfaces.end(), [](SurfaceId s) { return s != 0; }))
        surfaces_ = mesh.surfaces;
    core::WordHash hash;
    hash.add(static_cast<std::uint64_t>(mesh.triangles.size()));
    for (const std::uint32_t triangle : kept) {
        hash.add(static_cast<std::uint64_t>(triangle));
        for (const std::uint32_t v : mesh.triangles[triangle]) hash.add(mesh.vertices[v]);
    }
    // The kept triangles' ids, where there are any: a world of other surfaces is another
    // world to a snapshot, and no ids and all zeros, stored alike, hash alike.
    if (!surfaces_.empty())
        for (const std::uint32_t triangle : kept)
            hash.add(static_cast<std::uint64_t>(surfaces_[triangle]));
    content_hash_ = hash.value;
    quantize_slot_boxes();
}

SurfaceId StaticCollider::surface(std::uint32_t index) const {
    if (index >= mesh_triangle_count())
        throw Error("StaticCollider::surface: triangle " + std::to_string(index) +
                    " is past the mesh's " + std::to_string(mesh_triangle_count()));
    return surfaces_.empty() ? SurfaceId{0} : surfaces_[index];
}

SurfaceId StaticCollider::highest_surface() const {
    SurfaceId highest = 0;
    for (std::uint32_t t = 0; t < surfaces_.size(); ++t)
        if (triangle_to_slot_[t] != kNoSlot) highest = std::max(highest, surfaces_[t]);
    return highest;
}

// The grids, and each slot's float box (rounded outward, as the builder saw it, so inside
// its leaf lane's box) quantized outward in its node's grids, in blocks of eight slots. The
// nodes of a subtree of at most kGridGroupSlots slots share the grids over its root's lanes
// (the highest such subtree: a group); a node above the groups with leaf lanes gets grids
// of its own, over its leaf lanes.
void StaticCollider::quantize_slot_boxes() {
    const auto n = static_cast<std::uint32_t>(slot_vertices_.size());
    grids_.clear();
    node_grid_.assign(nodes_.size(), kNoSlot);
    if (nodes_.empty()) return;
    struct Entry {
        std::uint32_t node, end, grid;
    };
    // The grids over the lanes of `node` selected by `lanes` (one at least, not empty),
    // appended.
    auto add_grids = [this](const BvhNode& node, unsigned lanes) {
        constexpr float kInf = std::numeric_limits<float>::infinity();
        float lo[3] = {kInf, kInf, kInf}, hi[3] = {-kInf, -kInf, -kInf};
        for (int i = 0; i < BvhNode::kWidth; ++i) {
            if (node.is_empty(i) || ((lanes >> i) & 1u) == 0) continue;
            for (int a = 0; a < 3; ++a) {
                lo[a] = std::min(lo[a], node.min[a][i]);
                hi[a] = std::max(hi[a], node.max[a][i]);
            }
        }
        const AxisGrid grid[3] = {collision_detail::axis_grid(lo[0], hi[0]),
                                  collision_detail::axis_grid(lo[1], hi[1]),
                                  collision_detail::axis_grid(lo[2], hi[2])};
        grids_.push_back(collision_detail::node_grid(grid));
        return static_cast<std::uint32_t>(grids_.size() - 1);
    };
    double leaf_extent_sum[3] = {0.0, 0.0, 0.0};
    std::size_t leaf_count = 0;
    std::vector<Entry> stack{{0, n, kNoSlot}};
    while (!stack.empty()) {
        Entry e = stack.back();
        stack.pop_back();
        const BvhNode& node = nodes_[e.node];
        unsigned leaf_lanes = 0;
        for (int i = 0; i < BvhNode::kWidth; ++i)
            if (!node.is_empty(i) && node.is_leaf(i)) leaf_lanes |= 1u << i;
        if (e.grid == kNoSlot && e.end - node.first[0] <= kGridGroupSlots)
            e.grid = add_grids(node, (1u << BvhNode::kWidth) - 1u);
        for (int i = 0; i < BvhNode::kWidth; ++i)
            if (!node.is_empty(i) && !node.is_leaf(i))
                stack.push_back({node.child[i], node.end(i, e.end), e.grid});
        for (int i = 0; i < BvhNode::kWidth; ++i) {
            if (((leaf_lanes >> i) & 1u) == 0) continue;
            for (int a = 0; a < 3; ++a)
                leaf_extent_sum[a] += double(node.max[a][i]) - double(node.min[a][i]);
            ++leaf_count;
        }
        if (leaf_lanes == 0) continue;
        const std::uint32_t grid_index = e.grid != kNoSlot ? e.grid : add_grids(node, leaf_lanes);
        node_grid_[e.node] = grid_index;
        const BvhNodeGrid& node_grid = grids_[grid_index];
        const AxisGrid grid[3] = {collision_detail::axis_of(node_grid, 0),
                                  collision_detail::axis_of(node_grid, 1),
                                  collision_detail::axis_of(node_grid, 2)};
        for (int i = 0; i < BvhNode::kWidth; ++i) {
            if (((leaf_lanes >> i) & 1u) == 0) continue;
            for (std::uint32_t slot = node.first[i]; slot < node.end(i, e.end); ++slot) {
                const auto& tri = slot_vertices_[slot];
                const collision_detail::FloatBox box =
                    collision_detail::outward_float_box(collision_detail::triangle_box(
                        vertices_[tri[0]], vertices_[tri[1]], vertices_[tri[2]]));
                BvhSlotBlock& block = slot_blocks_[slot / kBlockSlots];
                const std::uint32_t lane = slot % kBlockSlots;
                for (int a = 0; a < 3; ++a) {
                    const int qlo = collision_detail::quantize_down(box.min[a], grid[a]);
                    const int qhi = collision_detail::quantize_up(box.max[a], grid[a]);
                    TP_ASSERT(qlo >= 1 && qhi <= collision_detail::kIndexLimit - 1 && qlo <= qhi,
                              "slot box outside its node's grid");
                    block.box[a][lane] =
                        static_cast<std::int16_t>(qlo - collision_detail::kIndexBias);
                    block.box[3 + a][lane] =
                        static_cast<std::int16_t>(qhi - collision_detail::kIndexBias);
                }
            }
        }
    }
    grids_.shrink_to_fit();
    for (int a = 0; a < 3; ++a)
        inside_extent_[a] = kInsideShortcutLeaves * leaf_extent_sum[a] / double(leaf_count);
}

inline bool StaticCollider::triangle_box_overlaps(std::uint32_t slot, const Aabb& box) const {
    const auto& tri = slot_vertices_[slot];
    return collision_detail::triangle_box(vertices_[tri[0]], vertices_[tri[1]], vertices_[tri[2]])
        .overlaps(box);
}

// Depth-first traversal of the lanes whose boxes may overlap `box` (QueryLanes' outward
// test: a superset). When the box is large enough to hold whole lanes
// (kInsideShortcutLeaves), a lane surely inside it goes to sink.range whole: its triangles'
// boxes lie in the lane's box, so each of them overlaps. Any other hit leaf lane tests its
// slots' 16-bit boxes a block of eight at a time, in its node's grids (the query is
// quantized once per group of nodes sharing them); a slot that may overlap but not surely
// (a bound within about two grid steps of the box's) gets the exact double test. Inner
// lanes are visited in lane order, so that slots come out roughly in leaf order: the first
// straight away, the others stacked last to first, and all prefetched: the loads overlap
// the rest of this node's work.
template <class Sink>
void StaticCollider::visit_aabb(const Aabb& box, Sink& sink) const {
    if (nodes_.empty()) return;
    // Rounded once: the node lanes and the leaf grids test the same float bounds.
    collision_detail::FloatBox outward, inward;
    collision_detail::round_both_ways(box, outward, inward);
    const QueryLanes q(outward, inward);
    const collision_detail::QueryBounds bounds(outward, inward);
    const glm::dvec3 extent = box.extent();
    const bool inside_shortcut = extent.x >= inside_extent_[0] && extent.y >= inside_extent_[1] &&
                                 extent.z >= inside_extent_[2];
    struct Entry {
        std::uint32_t node, end;
    };
    std::array<Entry, kMaxTraversalStack> stack;
    int top = 0;
    std::uint32_t node = 0, end = static_cast<std::uint32_t>(triangle_count());
    QuantizedQuery qq;  // the query in grids_[qq_grid], kept while the next nodes share them
    std::uint32_t qq_grid = kNoSlot;
    for (;;) {
        const BvhNode& n = nodes_[node];
        const BoxLanes lanes = BoxLanes::of(n);
        const unsigned hit = collision_detail::may_overlap(lanes, q);
        unsigned inner = 0;
        if (hit != 0) {
            const unsigned inside =
                inside_shortcut ? collision_detail::surely_inside(lanes, q) & hit : 0u;
            const unsigned leaves = collision_detail::leaf_lanes(n) & hit & ~inside;
            inner = hit & ~inside & ~leaves;
            // Stacked without branches: every lane is written, only inner ones but the first
            // are kept (the first is visited next, straight from this node's registers).
            const unsigned stacked = inner & (inner - 1);
            if (stacked != 0) {
                for (int i = BvhNode::kWidth - 1; i >= 0; --i) {
                    stack[top] = {n.child[i], n.end(i, end)};
                    top += static_cast<int>((stacked >> i) & 1u);
                }
            }
            for (unsigned m = inner; m != 0; m &= m - 1) {
                const char* child = reinterpret_cast<const char*>(&nodes_[n.child[lowest_lane(m)]]);
                for (std::size_t line = 0; line < sizeof(BvhNode); line += 64)
                    _mm_prefetch(child + line, _MM_HINT_T0);
            }
            for (unsigned m = inside; m != 0; m &= m - 1) {
                const int i = lowest_lane(m);
                sink.range(n.first[i], n.end(i, end));
            }
            if (leaves != 0 && node_grid_[node] != qq_grid) {
                qq_grid = node_grid_[node];
                qq = collision_detail::quantize_query(bounds, grids_[qq_grid]);
            }
            // Neighbouring hit leaf lanes cover neighbouring slots in the same grids: each
            // run of them is tested as one range, so a block they share is tested once.
            for (unsigned m = leaves; m != 0;) {
                const int i = lowest_lane(m);
                const int run = std::countr_one(m >> i);
                m &= ~(((1u << run) - 1u) << i);
                const std::uint32_t leaf_first = n.first[i], leaf_end = n.end(i + run - 1, end);
                // The run's output cursor stays in a register (as the sink's member it was
                // stored and reloaded around every block's stores, which may alias it).
                auto* to = sink.reserve_run(leaf_first, leaf_end);
                for_each_block(leaf_first, leaf_end, [&](std::uint32_t s, unsigned in_run) {
                    const unsigned tested = collision_detail::test_block(block(s), qq);
                    const unsigned maybe = tested & in_run;
                    unsigned keep = (tested >> kBlockSlots) & maybe;
                    for (unsigned k = maybe & ~keep; k != 0; k &= k - 1) [[unlikely]] {
                            const int lane = lowest_lane(k);
                            if (triangle_box_overlaps(s + static_cast<std::uint32_t>(lane), box))
                                keep |= 1u << lane;
                        }
                    to = sink.slots(to, s, keep);
                });
                sink.commit(to);
            }
        }
        if (inner != 0) {
            const int i = lowest_lane(inner);
            node = n.child[i];
            end = n.end(i, end);
            continue;
        }
        if (top == 0) return;
        --top;
        node = stack[top].node;
        end = stack[top].end;
    }
}

namespace {

// The elements the box queries report, made from mesh triangle indices one at a time, or
// four at a time from an SSE vector of them (stored at `to`, unaligned).
struct IndexElement {
    using T = std::uint32_t;
    T make(std::uint32_t triangle) const { return triangle; }
    void store_four(T* to, __m128i triangles) const {
        _mm_storeu_si128(reinterpret_cast<__m128i*>(to), triangles);
    }
};
struct RefElement {
    using T = TriangleRef;
    static_assert(sizeof(TriangleRef) == 8 && offsetof(TriangleRef, triangle) == 4);
    std::uint32_t collider;
    T make(std::uint32_t triangle) const { return {collider, triangle}; }
    void store_four(T* to, __m128i triangles) const {
        const __m128i id = _mm_set1_epi32(static_cast<int>(collider));
        auto* out = reinterpret_cast<__m128i*>(to);
        _mm_storeu_si128(out, _mm_unpacklo_epi32(id, triangles));
        _mm_storeu_si128(out + 1, _mm_unpackhi_epi32(id, triangles));
    }
};

// A query's output gathered in a fixed local buffer and appended to the caller's vector in
// bulk: a reported triangle costs a store, not a push_back.
template <class Element>
class BufferedOutput {
  public:
    using T = typename Element::T;
    BufferedOutput(std::vector<T>& out, const BvhSlotBlock* blocks, Element element)
        : out_(out), blocks_(blocks), element_(element) {}
    BufferedOutput(const BufferedOutput&) = delete;
    BufferedOutput& operator=(const BufferedOutput&) = delete;
    ~BufferedOutput() { flush(); }

    /// Room for the blocks of slots [first, end) (a run of leaf lanes), flushing first if
    /// need be: the blocks' slots() then need no check each.
    T* reserve_run(std::uint32_t first, std::uint32_t end) {
        const std::uint32_t lanes =
            ((end + kBlockSlots - 1) & ~(kBlockSlots - 1)) - (first & ~(kBlockSlots - 1));
        if (used_ + lanes > kSize) flush();
        return buffer_ + used_;
    }
    /// The run's elements end at `to` (the last slots() result).
    void commit(T* to) { used_ = static_cast<unsigned>(to - buffer_); }
    /// Writes the slots s + i for the set bits i of `mask` (the block of eight slots from s,
    /// in a reserved run) at `to`, in increasing order; returns their end. Eight elements
    /// are written, set lanes first (lane_compaction.hpp), and `to` advances by the count:
    /// no branch on the mask.
    T* slots(T* to, std::uint32_t s, unsigned mask) const {
        const std::uint32_t* from = blocks_[s / kBlockSlots].triangle;
#if defined(__SSSE3__)
        const auto* halves = reinterpret_cast<const __m128i*>(from);
        const unsigned low = mask & 0xfu, high = mask >> 4;
        element_.store_four(to, collision_detail::pack_four_lanes(_mm_load_si128(halves), low));
        to += std::popcount(low);
        element_.store_four(to,
                            collision_detail::pack_four_lanes(_mm_load_si128(halves + 1), high));
        return to + std::popcount(high);
#else
        const collision_detail::CompactedLanes& c = collision_detail::kCompactedLanes[mask];
        for (unsigned k = 0; k < kBlockSlots; ++k) to[k] = element_.make(from[c.lane[k]]);
        return to + c.count;
#endif
    }
    /// Slots [first, end).
    void range(std::uint32_t first, std::uint32_t end) {
        if (end - first > kSize - used_) {
            flush();
            for (std::uint32_t s = first; s < end; ++s) out_.push_back(element_.make(triangle(s)));
            return;
        }
        T* to = buffer_ + used_;
        for (std::uint32_t s = first; s < end; ++s) *to++ = element_.make(triangle(s));
        used_ += end - first;
    }

  private:
    // A run of leaf lanes (at most a node's worth) fits after a flush: room is checked per
    // run rather than per block, and flushes are fewer, which car-box queries feel.
    static constexpr unsigned kSize =
        BvhNode::kWidth * collision_detail::kMaxLeafLaneSize + 2 * kBlockSlots;
    std::uint32_t triangle(std::uint32_t s) const {
        return blocks_[s / kBlockSlots].triangle[s % kBlockSlots];
    }
    void flush() {
        out_.insert(out_.end(), buffer_, buffer_ + used_);
        used_ = 0;
    }

    std::vector<T>& out_;
    const BvhSlotBlock* blocks_;
    Element element_;
    unsigned used_ = 0;
    T buffer_[kSize];
};

}  // namespace

void StaticCollider::prefetch_box_query() const {
    if (nodes_.empty()) return;
    const auto lines = [](const void* from, std::size_t bytes) {
        for (std::size_t line = 0; line < bytes; line += 64)
            _mm_prefetch(static_cast<const char*>(from) + line, _MM_HINT_T0);
    };
    lines(nodes_.data(), sizeof(BvhNode));
    lines(node_grid_.data(), 1);
    lines(grids_.data(), 1);
    // A large collider's first blocks are no likelier to be read than any others.
    if (slot_blocks_.size() <= kPrefetchBlocks)
        lines(slot_blocks_.data(), slot_blocks_.size() * sizeof(BvhSlotBlock));
}

void StaticCollider::query_aabb(const Aabb& box, std::vector<std::uint32_t>& out) const {
    BufferedOutput sink(out, slot_blocks_.data(), IndexElement{});
    visit_aabb(box, sink);
}

void StaticCollider::query_aabb_refs(const Aabb& box, std::uint32_t collider_id,
                                     std::vector<TriangleRef>& out) const {
    BufferedOutput sink(out, slot_blocks_.data(), RefElement{collider_id});
    visit_aabb(box, sink);
}

// The traversal of visit_aabb without the inside shortcut (being inside the query's box
// says nothing about the distance test): leaf slots whose 16-bit boxes may overlap `box`
// go to `keep` with their double vertices.
template <class Predicate>
void StaticCollider::visit_box_filtered(const Aabb& box, Predicate&& keep,
                                        std::vector<std::uint32_t>& out) const {
    if (nodes_.empty()) return;
    collision_detail::FloatBox outward, inward;
    collision_detail::round_both_ways(box, outward, inward);
    const QueryLanes q(outward, inward);
    const collision_detail::QueryBounds bounds(outward, inward);
    struct Entry {
        std::uint32_t node, end;
    };
    std::array<Entry, kMaxTraversalStack> stack;
    int top = 0;
    std::uint32_t node = 0, end = static_cast<std::uint32_t>(triangle_count());
    QuantizedQuery qq;  // the query in grids_[qq_grid], kept while the next nodes share them
    std::uint32_t qq_grid = kNoSlot;
    for (;;) {
        const BvhNode& n = nodes_[node];
        const unsigned hit = collision_detail::may_overlap(BoxLanes::of(n), q);
        const unsigned leaves = collision_detail::leaf_lanes(n) & hit;
        if (leaves != 0 && node_grid_[node] != qq_grid) {
            qq_grid = node_grid_[node];
            qq = collision_detail::quantize_query(bounds, grids_[qq_grid]);
        }
        for (unsigned m = leaves; m != 0;) {  // runs of neighbouring leaf lanes, as above
            const int i = lowest_lane(m);
            const int run = std::countr_one(m >> i);
            m &= ~(((1u << run) - 1u) << i);
            const std::uint32_t leaf_first = n.first[i], leaf_end = n.end(i + run - 1, end);
            for_each_block(leaf_first, leaf_end, [&](std::uint32_t s, unsigned in_run) {
                const unsigned maybe = collision_detail::test_block(block(s), qq) & in_run;
                for (unsigned k = maybe; k != 0; k &= k - 1) {
                    const auto slot = s + static_cast<std::uint32_t>(lowest_lane(k));
                    const auto& tri = slot_vertices_[slot];
                    if (keep(vertices_[tri[0]], vertices_[tri[1]], vertices_[tri[2]]))
                        out.push_back(slot_triangle(slot));
                }
            });
        }
        for (unsigned m = hit & ~leaves; m != 0; m &= ~(1u << highest_lane(m))) {
            const int i = highest_lane(m);
            stack[top++] = {n.child[i], n.end(i, end)};
        }
        if (top == 0) return;
        --top;
        node = stack[top].node;
        end = stack[top].end;
    }
}

void StaticCollider::query_sphere(const glm::dvec3& center, double radius,
                                  std::vector<std::uint32_t>& out) const {
    const collision_detail::CapsuleQuery q =
        collision_detail::make_capsule_query(center, center, radius);
    visit_box_filtered(
        q.box,
        [&q](const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
            return collision_detail::sphere_keeps(q, a, b, c);
        },
        out);
}

void StaticCollider::query_capsule(const glm::dvec3& start, const glm::dvec3& end, double radius,
                                   std::vector<std::uint32_t>& out) const {
    const collision_detail::CapsuleQuery q =
        collision_detail::make_capsule_query(start, end, radius);
    visit_box_filtered(
        q.box,
        [&q](const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
            return collision_detail::capsule_keeps(q, a, b, c);
        },
        out);
}

// Closest-hit traversal: a node's hit lanes (leaves and inner children alike) are stacked
// farthest first with their entry distances, so the nearest is taken next, and an entry
// popped beyond the best hit is dropped. A triangle's reported distance is never below its
// box's entry distance, which is never below its lanes' (the span test is monotone in the
// box), so pruning at "entry > best" loses no hit, ties included.
std::optional<RayHit> StaticCollider::raycast(const glm::dvec3& origin, const glm::dvec3& unit_dir,
                                              double max_distance) const {
    const collision_detail::RayQuery ray =
        collision_detail::make_ray_query(origin, unit_dir, max_distance);
    if (nodes_.empty()) return std::nullopt;
    double best_t = ray.max_distance;
    std::uint32_t best_triangle = kNoSlot, best_slot = kNoSlot;
    struct Entry {
        std::uint32_t child, first, end;  // child: a node index, or kLeaf for slots [first, end)
        std::uint32_t node;               // leaf: its node (for its grids)
        double t_near, t_far;
    };
    std::array<Entry, kMaxTraversalStack> stack;
    int top = 0;
    Entry entry{0, 0, static_cast<std::uint32_t>(triangle_count()), 0, 0.0, best_t};
    for (;;) {
        if ((entry.child & BvhNode::kLeaf) != 0) {
            const BvhNodeGrid& node_grid = grids_[node_grid_[entry.node]];
            const AxisGrid grid[3] = {collision_detail::axis_of(node_grid, 0),
                                      collision_detail::axis_of(node_grid, 1),
                                      collision_detail::axis_of(node_grid, 2)};
            // A hit in this lane lies on the ray within the lane's span (its box holds the
            // triangle's), so a slot whose 16-bit box misses the box around that part of the
            // ray holds none: one block test culls a leaf lane's slots eight at a time.
            const std::optional<Aabb> segment =
                collision_detail::ray_segment_box(ray, entry.t_near, std::min(entry.t_far, best_t));
            QuantizedQuery qq;
            if (segment) {
                collision_detail::FloatBox outward, inward;
                collision_detail::round_both_ways(*segment, outward, inward);
                qq = collision_detail::quantize_query(
                    collision_detail::QueryBounds(outward, inward), node_grid);
            }
            // The slot's quantized box holds the triangle's box, so its span holds the hit.
            auto test_slot = [&](std::uint32_t slot) {
                const BvhSlotBlock& block = slot_blocks_[slot / kBlockSlots];
                const std::uint32_t lane = slot % kBlockSlots;
                glm::dvec3 lo, hi;
                for (int a = 0; a < 3; ++a) {
                    lo[a] = collision_detail::grid_value(
                        block.box[a][lane] + collision_detail::kIndexBias, grid[a]);
                    hi[a] = collision_detail::grid_value(
                        block.box[3 + a][lane] + collision_detail::kIndexBias, grid[a]);
                }
                double t_near, t_far;
                if (!collision_detail::ray_box_span(ray, lo, hi, best_t, t_near, t_far)) return;
                const auto& tri = slot_vertices_[slot];
                const std::optional<double> t = collision_detail::ray_triangle(
                    ray, vertices_[tri[0]], vertices_[tri[1]], vertices_[tri[2]]);
                if (t &&
                    collision_detail::better_hit(*t, block.triangle[lane], best_t, best_triangle)) {
                    best_t = *t;
                    best_triangle = block.triangle[lane];
                    best_slot = slot;
                }
            };
            for_each_block(entry.first, entry.end, [&](std::uint32_t s, unsigned in_run) {
                const unsigned maybe =
                    segment ? collision_detail::test_block(block(s), qq) & in_run : in_run;
                for (unsigned m = maybe; m != 0; m &= m - 1)
                    test_slot(s + static_cast<std::uint32_t>(lowest_lane(m)));
            });
        } else {
            const BvhNode& n = nodes_[entry.child];
            Entry hits[BvhNode::kWidth];
            int count = 0;
            for (int i = 0; i < BvhNode::kWidth; ++i) {
                double t_near, t_far;
                if (n.is_empty(i) ||
                    !collision_detail::ray_box_span(ray, lane_min(n, i), lane_max(n, i), best_t,
                                                    t_near, t_far))
                    continue;
                // Insertion by decreasing entry distance (of equal ones, the lower lane is
                // taken first).
                int at = count++;
                for (; at > 0 && hits[at - 1].t_near <= t_near; --at) hits[at] = hits[at - 1];
                hits[at] = {n.child[i],  n.first[i], n.end(i, entry.end),
                            entry.child, t_near,     t_far};
            }
            for (int k = 0; k < count; ++k) stack[top++] = hits[k];
        }
        do {
            if (top == 0) {
                if (best_slot == kNoSlot) return std::nullopt;
                const auto& tri = slot_vertices_[best_slot];
                return RayHit{best_t, best_triangle,
                              collision_detail::unit_normal(vertices_[tri[0]], vertices_[tri[1]],
                                                            vertices_[tri[2]])};
            }
            --top;
        } while (stack[top].t_near > best_t);
        entry = stack[top];
    }
}

bool StaticCollider::has_triangle(std::uint32_t index) const {
    return index < triangle_to_slot_.size() && triangle_to_slot_[index] != kNoSlot;
}

Triangle StaticCollider::triangle(std::uint32_t index) const {
    if (!has_triangle(index))
        throw Error("collider triangle " + std::to_string(index) +
                    (index < triangle_to_slot_.size() ? " is degenerate and was dropped"
                                                      : " is out of range"));
    const auto& tri = slot_vertices_[triangle_to_slot_[index]];
    return {vertices_[tri[0]], vertices_[tri[1]], vertices_[tri[2]]};
}

NormalizedTriangle StaticCollider::normalized_triangle(std::uint32_t index) const {
    return NormalizedTriangle(triangle(index));
}

std::size_t StaticCollider::bytes_used() const {
    return sizeof(*this) + capacity_bytes(vertices_) + capacity_bytes(slot_vertices_) +
           capacity_bytes(triangle_to_slot_) + capacity_bytes(slot_blocks_) +
           capacity_bytes(nodes_) + capacity_bytes(grids_) + capacity_bytes(node_grid_) +
           capacity_bytes(surfaces_);
}

}  // namespace trackphys
