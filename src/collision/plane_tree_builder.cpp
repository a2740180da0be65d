#include "trackphys/detail/plane_tree_builder.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "collision/plane_tree_shapes.hpp"
#include "core/parallel_items.hpp"
#include "trackphys/collision/static_collider.hpp"
#include "trackphys/error.hpp"
#include "trackphys/math/symmetric_eigen.hpp"

namespace trackphys {
namespace {

using collision_detail::float_down;
using collision_detail::float_up;

// A float toward zero: |result| <= |x|.
float float_toward_zero(double x) { return x < 0.0 ? float_up(x) : float_down(x); }

// The unit direction of v rounded to float toward zero, so that its length is at most 1:
// a sphere test that treats it as unit (n.c - r) is then conservative. Zero when v is.
glm::dvec3 float_direction(const glm::dvec3& v) {
    const double length = glm::length(v);
    if (!(length > 0.0) || !std::isfinite(length)) return glm::dvec3(0.0);
    const glm::dvec3 u = v / length;
    return {float_toward_zero(u.x), float_toward_zero(u.y), float_toward_zero(u.z)};
}

// Two doubles in one vector (GCC's vector extension, an SSE2 register on x86-64): the
// binned pass takes the candidate directions two at a time.
using DirectionPair = double __attribute__((vector_size(16)));

// std::min and std::max lane by lane, returning the same operand on ties as they do.
DirectionPair lanes_min(DirectionPair a, DirectionPair b) { return b < a ? b : a; }
DirectionPair lanes_max(DirectionPair a, DirectionPair b) { return a < b ? b : a; }

// sum (x - mean)(x - mean)^T over the centroids, lower triangle enough for symmetric_eigen.
glm::dmat3 outer(const glm::dvec3& a, const glm::dvec3& b) {
    glm::dmat3 m;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) m[c][r] = a[r] * b[c];
    return m;
}

}  // namespace

void PlaneTreeBuilder::build(std::span<const NormalizedTriangle> triangles,
                             std::span<const std::uint32_t> ids, const PlaneTreeSettings& settings,
                             PlaneTree& tree, unsigned threads) {
    build_nodes(triangles, ids, settings, tree, threads);
    copy_frames(triangles, tree);
    tree.boxes_.reserve(order_.size());
    for (const std::uint32_t item : order_) {
        const auto& v = items_[item].vertices;
        tree.boxes_.push_back(collision_detail::float_box(Triangle(v[0], v[1], v[2])));
    }
}

void PlaneTreeBuilder::copy_frames(std::span<const NormalizedTriangle> triangles,
                                   PlaneTree& tree) const {
    tree.frames_.reserve(order_.size());
    for (const std::uint32_t item : order_) tree.frames_.push_back(triangles[item]);
}

void PlaneTreeBuilder::build_nodes(std::span<const NormalizedTriangle> triangles,
                                   std::span<const std::uint32_t> ids,
                                   const PlaneTreeSettings& settings, PlaneTree& tree,
                                   unsigned threads) {
    if (triangles.size() != ids.size())
        throw Error("PlaneTreeBuilder::build: " + std::to_string(triangles.size()) +
                    " triangles but " + std::to_string(ids.size()) + " ids");
    if (triangles.size() > PlaneTreeNode::kCountMask)
        throw Error("PlaneTreeBuilder::build: too many triangles (" +
                    std::to_string(triangles.size()) + "), at most 2^30 - 1");
    if (std::string why = settings.validate(); !why.empty()) throw Error(why);
    settings_ = settings;
    tree_ = &tree;

    const std::size_t n = triangles.size();
    items_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        Item& item = items_[i];
        for (int k = 0; k < 3; ++k) item.vertices[std::size_t(k)] = triangles[i].vertex(k);
        const auto& v = item.vertices;
        item.centroid = (v[0] + v[1] + v[2]) / 3.0;
        item.area_normal = glm::cross(v[1] - v[0], v[2] - v[0]);
    }
    order_.resize(n);
    std::iota(order_.begin(), order_.end(), 0u);

    tree.nodes_.clear();
    tree.depth_ = 0;
    if (n > 0) {
        constexpr float kInf = std::numeric_limits<float>::infinity();
        tree.nodes_.push_back({{0.0f, 0.0f, 0.0f}, kInf, 0, 0});
        if (detail::resolved_thread_count(threads) == 1 || n <= kSplitApartAbove)
            tree.depth_ = build_node(scratch_, tree.nodes_, 0, 0, n, 0);
        else
            build_nodes_in_parallel(threads);
    }
    tree.slabs_.clear();
    if (n > 0 && settings.slab_thickness > 0.0) {
        node_slabs_.resize(tree.nodes_.size());
        mark_slabs(0, 0, n);
        for (std::size_t node = 0; node < tree.nodes_.size(); ++node)
            if (tree.nodes_[node].has_slab()) tree.slabs_.push_back(node_slabs_[node]);
    }
    tree.rank_slabs();
    tree.frames_.clear();
    tree.boxes_.clear();
    tree.ids_.clear();
    tree.collider_ = nullptr;
    tree.ids_.reserve(n);
    for (const std::uint32_t item : order_) tree.ids_.push_back(ids[item]);
    tree_ = nullptr;
}

void PlaneTreeBuilder::make_leaf(PlaneTreeNode& node, std::size_t begin, std::size_t end) {
    node.first = static_cast<std::uint32_t>(begin);
    node.packed = PlaneTreeNode::kLeafBit | static_cast<std::uint32_t>(end - begin);
}

std::uint32_t PlaneTreeBuilder::adopt(Nodes& nodes, std::uint32_t node, std::size_t count,
                                      const Children& children) {
    const auto child = static_cast<std::uint32_t>(nodes.size());
    nodes.insert(nodes.end(), children.nodes.begin(), children.nodes.end());
    nodes[node].first = child;
    nodes[node].packed = static_cast<std::uint32_t>(count);
    return child;
}

int PlaneTreeBuilder::build_node(Scratch& scratch, Nodes& nodes, std::uint32_t node,
                                 std::size_t begin, std::size_t end, int depth) {
    Children children;
    if (!split(scratch, begin, end, depth, children)) {
        make_leaf(nodes[node], begin, end);
        return depth;
    }
    const std::uint32_t child = adopt(nodes, node, end - begin, children);
    const std::size_t mid = begin + children.left_count;
    // The left subtree's nodes first, then the right one's: the order the layout follows.
    const int left_depth = build_node(scratch, nodes, child, begin, mid, depth + 1);
    return std::max(left_depth, build_node(scratch, nodes, child + 1, mid, end, depth + 1));
}

bool PlaneTreeBuilder::split(Scratch& scratch, std::size_t begin, std::size_t end, int depth,
                             Children& children) {
    Split split;
    if (depth >= PlaneTreeSettings::kMaxDepth || !choose_split(scratch, begin, end, split))
        return false;
    order_along(scratch, begin, end, split.normal, split.left_count);
    const std::size_t mid = begin + split.left_count;
    children.left_count = split.left_count;
    set_plane(children.nodes[0], begin, mid, split.normal);
    set_plane(children.nodes[1], mid, end, -split.normal);
    return true;
}

void PlaneTreeBuilder::build_nodes_in_parallel(unsigned threads) {
    threads = detail::resolved_thread_count(threads);
    // A node of more items than this is split in a wave of its level's nodes, one node a
    // thread; below it each subtree is built whole by one thread. A few subtrees a thread
    // even out their sizes (a cost-based cut can be far from the middle).
    const std::size_t n = order_.size();
    const std::size_t subtree_at_most = std::max(kSplitApartAbove, n / (8 * std::size_t{threads}));

    struct Pending {
        std::uint32_t node;  ///< in `top`
        std::size_t begin, end;
        int depth;
    };
    Nodes top = std::move(tree_->nodes_);  // the root, placed by build
    std::vector<Pending> wave = {{0, 0, n, 0}}, subtrees;
    int depth = 0;  // of the deepest leaf
    while (!wave.empty()) {
        std::vector<Children> children(wave.size());
        std::vector<char> did_split(wave.size());  // not bool: a byte a task, no shared word
        detail::run_items_in_parallel(wave.size(), threads, [&](std::size_t i) {
            Scratch scratch;
            const Pending& p = wave[i];
            did_split[i] = split(scratch, p.begin, p.end, p.depth, children[i]);
        });
        std::vector<Pending> next;
        for (std::size_t i = 0; i < wave.size(); ++i) {
            const Pending& p = wave[i];
            if (!did_split[i]) {
                depth = std::max(depth, p.depth);
                make_leaf(top[p.node], p.begin, p.end);
                continue;
            }
            const std::uint32_t child = adopt(top, p.node, p.end - p.begin, children[i]);
            const std::size_t mid = p.begin + children[i].left_count;
            for (const Pending& c : {Pending{child, p.begin, mid, p.depth + 1},
                                     Pending{child + 1, mid, p.end, p.depth + 1}})
                (c.end - c.begin > subtree_at_most ? next : subtrees).push_back(c);
        }
        wave = std::move(next);
    }

    std::vector<Nodes> built(subtrees.size());
    std::vector<int> depths(subtrees.size());
    detail::run_items_in_parallel(subtrees.size(), threads, [&](std::size_t i) {
        const Pending& p = subtrees[i];
        Scratch scratch;
        built[i] = {top[p.node]};
        depths[i] = build_node(scratch, built[i], 0, p.begin, p.end, p.depth);
    });

    // Lay the nodes out as build_node does on one thread: a split node's two children side
    // by side, then the left child's subtree, then the right one's. A subtree built apart
    // has that layout already, its root at index 0.
    std::vector<std::int64_t> subtree_of(top.size(), -1);
    for (std::size_t i = 0; i < subtrees.size(); ++i)
        subtree_of[subtrees[i].node] = std::int64_t(i);
    Nodes& out = tree_->nodes_;
    out.clear();
    out.reserve(top.size() + [&] {
        std::size_t sum = 0;
        for (const Nodes& b : built) sum += b.size();
        return sum;
    }());
    out.push_back(top[0]);
    const auto lay_out = [&](const auto& self, std::uint32_t from, std::uint32_t to) -> void {
        if (subtree_of[from] >= 0) {
            const Nodes& subtree = built[std::size_t(subtree_of[from])];
            // Subtree index k > 0 lands at base + k; a leaf's first is an item slot.
            const auto base = static_cast<std::uint32_t>(out.size() - 1);
            const auto placed = [&](PlaneTreeNode node) {
                if (!node.is_leaf()) node.first += base;
                return node;
            };
            out[to] = placed(subtree[0]);
            for (std::size_t k = 1; k < subtree.size(); ++k) out.push_back(placed(subtree[k]));
            return;
        }
        out[to] = top[from];
        if (top[from].is_leaf()) return;
        const auto child = static_cast<std::uint32_t>(out.size());
        out[to].first = child;
        out.resize(out.size() + 2);
        self(self, top[from].first, child);
        self(self, top[from].first + 1, child + 1);
    };
    lay_out(lay_out, 0, 0);

    for (const int d : depths) depth = std::max(depth, d);
    tree_->depth_ = depth;
}

void PlaneTreeBuilder::mark_slabs(std::uint32_t node, std::size_t begin, std::size_t end) {
    glm::dvec3 area_sum(0.0);
    for (std::size_t i = begin; i < end; ++i) area_sum += items_[order_[i]].area_normal;
    const glm::dvec3 normal = float_direction(area_sum);
    PlaneTreeNode& n = tree_->nodes_[node];
    if (normal != glm::dvec3(0.0)) {
        double low = std::numeric_limits<double>::infinity(), high = -low;
        for (std::size_t i = begin; i < end; ++i)
            for (const glm::dvec3& v : items_[order_[i]].vertices) {
                const double d = glm::dot(normal, v);
                low = std::min(low, d);
                high = std::max(high, d);
            }
        if (high - low <= settings_.slab_thickness) {
            PlaneTreeSlab& slab = node_slabs_[node];
            for (int k = 0; k < 3; ++k) slab.normal[k] = static_cast<float>(normal[k]);
            slab.low = float_down(low);
            slab.high = float_up(high);
            n.packed |= PlaneTreeNode::kSlabBit;
            return;  // one slab a path: the slabs below are barely thinner
        }
    }
    if (n.is_leaf()) return;
    const std::size_t mid = begin + tree_->nodes_[n.first].count();
    const std::uint32_t left = n.first;
    mark_slabs(left, begin, mid);
    mark_slabs(left + 1, mid, end);
}

bool PlaneTreeBuilder::choose_split(Scratch& scratch, std::size_t begin, std::size_t end,
                                    Split& split) {
    const std::size_t count = end - begin;
    if (count <= 1) return false;
    if (settings_.rule == PlaneSplitRule::pca_median) {
        if (count <= std::size_t(settings_.max_leaf_size)) return false;
        split = pca_median_split(begin, end);
        return true;
    }
    return cost_based_split(scratch, begin, end, split);
}

PlaneTreeBuilder::Split PlaneTreeBuilder::pca_median_split(std::size_t begin, std::size_t end) {
    // The write-up's rule: n = primary eigenvector of the centroids' covariance.
    const double count = double(end - begin);
    glm::dvec3 mean(0.0);
    for (std::size_t i = begin; i < end; ++i) mean += items_[order_[i]].centroid;
    mean /= count;
    glm::dmat3 covariance(0.0);
    for (std::size_t i = begin; i < end; ++i) {
        const glm::dvec3 d = items_[order_[i]].centroid - mean;
        covariance += outer(d, d);
    }
    const SymmetricEigen3 eigen = symmetric_eigen(covariance);
    Split split;
    split.normal = float_direction(eigen.vectors[0]);
    // All centroids equal gives the identity basis, so the normal is never zero here; a cut
    // in half is valid whatever the direction (the planes bound whatever lands on each side).
    if (split.normal == glm::dvec3(0.0)) split.normal = {1.0, 0.0, 0.0};
    split.left_count = (end - begin) / 2;
    return split;
}

bool PlaneTreeBuilder::cost_based_split(Scratch& scratch, std::size_t begin, std::size_t end,
                                        Split& split) {
    const std::size_t count = end - begin;
    // Small nodes try the centroids' axes and the coordinate axes only: the two directions
    // fitted to the surface cost two more decompositions a node there, and made the trees
    // no better (the mid-phase counts in docs/benchmarks.md).
    const bool fit_surface = count > kSweepAtMost;
    glm::dvec3 mean(0.0);
    for (std::size_t i = begin; i < end; ++i) mean += items_[order_[i]].centroid;
    mean /= double(count);
    glm::dmat3 covariance(0.0), normals(0.0);
    for (std::size_t i = begin; i < end; ++i) {
        const Item& item = items_[order_[i]];
        const glm::dvec3 d = item.centroid - mean;
        covariance += outer(d, d);
        // area * n n^T: the dominant surface normal is its primary eigenvector, whichever
        // way the triangles face (a road and the tops of its walls agree on it).
        const double area2 = glm::length(item.area_normal);
        if (fit_surface && area2 > 0.0)
            normals += outer(item.area_normal, item.area_normal) * (1.0 / area2);
    }
    const SymmetricEigen3 centroid_axes = symmetric_eigen(covariance);
    glm::dvec3 surface_normal(0.0);  // a zero candidate is skipped
    SymmetricEigen3 surface_axes{glm::dvec3(0.0), glm::dmat3(0.0)};
    if (fit_surface) {
        surface_normal = glm::normalize(symmetric_eigen(normals).vectors[0]);
        // The centroids' spread within the surface: P C P with P = I - N N^T. For a road
        // patch its two principal directions are the road's local tangent and width.
        const glm::dmat3 project = glm::dmat3(1.0) - outer(surface_normal, surface_normal);
        surface_axes = symmetric_eigen(project * covariance * project);
    }

    const Directions candidates = {
        centroid_axes.vectors[0], centroid_axes.vectors[1], centroid_axes.vectors[2],
        {1.0, 0.0, 0.0},          {0.0, 1.0, 0.0},          {0.0, 0.0, 1.0},
        surface_normal,           surface_axes.vectors[0],  surface_axes.vectors[1],
    };
    Split best;
    best.cost = std::numeric_limits<double>::infinity();
    if (count > kSweepAtMost) evaluate_directions_binned(begin, end, candidates, best);
    // Small nodes, and large ones whose centroids coincide along every candidate (no bin
    // boundary falls between them), get the full sweep over every cut position.
    if (!(best.cost < std::numeric_limits<double>::infinity()))
        for (const glm::dvec3& direction : candidates)
            evaluate_direction(scratch, begin, end, direction, best);
    if (!(best.cost < std::numeric_limits<double>::infinity())) return false;
    // Small nodes split only when the model predicts less work than testing them all.
    if (count <= std::size_t(settings_.max_leaf_size) && !(best.cost < double(count))) return false;
    split = best;
    return true;
}

void PlaneTreeBuilder::evaluate_direction(Scratch& scratch, std::size_t begin, std::size_t end,
                                          const glm::dvec3& direction, Split& best) {
    const glm::dvec3 n = float_direction(direction);
    if (n == glm::dvec3(0.0)) return;
    const std::size_t count = end - begin;
    scratch.sweep.resize(count);
    scratch.suffix_low.resize(count + 1);
    double node_low = std::numeric_limits<double>::infinity();
    double node_high = -node_low;
    for (std::size_t i = 0; i < count; ++i) {
        const std::uint32_t item_index = order_[begin + i];
        const Item& item = items_[item_index];
        double lo = glm::dot(n, item.vertices[0]), hi = lo;
        for (int k = 1; k < 3; ++k) {
            const double d = glm::dot(n, item.vertices[std::size_t(k)]);
            lo = std::min(lo, d);
            hi = std::max(hi, d);
        }
        scratch.sweep[i] = {glm::dot(n, item.centroid), lo, hi, item_index};
        node_low = std::min(node_low, lo);
        node_high = std::max(node_high, hi);
    }
    // Order by centroid along n, ties by item index, as order_along does. The entries carry
    // their key and interval, so the sort compares without looking anything up.
    std::sort(scratch.sweep.begin(), scratch.sweep.end(), ByKeyThenItem{});
    scratch.suffix_low[count] = std::numeric_limits<double>::infinity();
    for (std::size_t k = count; k-- > 0;)
        scratch.suffix_low[k] = std::min(scratch.suffix_low[k + 1], scratch.sweep[k].low);

    // A query that reaches this node is taken as uniform along n over [low - r, high + r];
    // it reaches the left half-space (n.x <= left_high) with probability
    // (left_high - low + 2r) / (high - low + 2r), the right one likewise.
    const double r2 = 2.0 * settings_.query_radius;
    const double span = node_high - node_low + r2;
    double left_high = -std::numeric_limits<double>::infinity();
    for (std::size_t k = 1; k < count; ++k) {
        left_high = std::max(left_high, scratch.sweep[k - 1].high);
        consider_cut(best, n, k, count, (left_high - node_low + r2) / span,
                     (node_high - scratch.suffix_low[k] + r2) / span);
    }
}

void PlaneTreeBuilder::consider_cut(Split& best, const glm::dvec3& normal, std::size_t left_count,
                                    std::size_t count, double p_left, double p_right) const {
    // Equal costs (triangles that all overlap, duplicates) go to the most balanced cut,
    // which keeps such nodes from degenerating into a chain.
    const double imbalance = std::abs(2.0 * double(left_count) - double(count));
    const double cost = 2.0 * settings_.node_cost + double(left_count) * std::min(1.0, p_left) +
                        double(count - left_count) * std::min(1.0, p_right) + 1e-9 * imbalance;
    if (cost < best.cost) best = {normal, left_count, cost};
}

void PlaneTreeBuilder::evaluate_directions_binned(std::size_t begin, std::size_t end,
                                                  const Directions& directions, Split& best) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    constexpr std::size_t kCount = kCandidateDirections;
    constexpr std::size_t kPairs = (kCount + 1) / 2;
    std::array<glm::dvec3, 2 * kPairs> normals{};  // a zero direction pads the last pair
    for (std::size_t d = 0; d < kCount; ++d) normals[d] = float_direction(directions[d]);

    // Two passes over the node's items, each reading an item once for every direction: the
    // first finds the centroid keys' range along each, the second bins (the keys made again:
    // kept between the passes, they were 216 bytes a triangle at the root, more than the
    // items). The directions go two to a vector, each lane making glm::dot's products and
    // sums in its order, so the keys are the same.
    std::array<DirectionPair, kPairs> nx, ny, nz, key_min, key_max;
    for (std::size_t p = 0; p < kPairs; ++p) {
        for (std::size_t lane = 0; lane < 2; ++lane) {
            const glm::dvec3& n = normals[2 * p + lane];
            nx[p][lane] = n.x;
            ny[p][lane] = n.y;
            nz[p][lane] = n.z;
        }
        key_min[p] = DirectionPair{kInf, kInf};
        key_max[p] = -key_min[p];
    }
    // The same expression as order_along's key, so the cut found is the cut made.
    const auto keys_along = [&](std::size_t p, const glm::dvec3& x) {
        return nx[p] * x.x + ny[p] * x.y + nz[p] * x.z;
    };
    for (std::size_t i = begin; i < end; ++i) {
        const Item& item = items_[order_[i]];
        for (std::size_t p = 0; p < kPairs; ++p) {
            const DirectionPair keys = keys_along(p, item.centroid);
            key_min[p] = lanes_min(key_min[p], keys);
            key_max[p] = lanes_max(key_max[p], keys);
        }
    }

    // Bins of equal width over the centroid keys. The bin index never decreases with the
    // key (subtracting, scaling and truncating are monotone in floating point), so the items
    // of the bins left of a boundary are exactly the smallest ones along n: each boundary is
    // one of the full sweep's cuts, its cost computed exactly from per-bin extremes.
    struct Bin {
        std::size_t count = 0;
        double low = kInf, high = -kInf;
    };
    std::array<std::array<Bin, kBins>, kCount> bins{};
    const auto lane_of = [](const std::array<DirectionPair, kPairs>& pairs, std::size_t d) {
        return pairs[d / 2][d % 2];  // direction d's lane
    };
    const auto binned = [&](std::size_t d) {
        return normals[d] != glm::dvec3(0.0) && lane_of(key_max, d) > lane_of(key_min, d);
    };
    std::array<DirectionPair, kPairs> scale{};  // 0 for a direction not binned: all in bin 0
    for (std::size_t d = 0; d < kCount; ++d)
        if (binned(d))
            scale[d / 2][d % 2] = double(kBins) / (lane_of(key_max, d) - lane_of(key_min, d));
    for (std::size_t i = begin; i < end; ++i) {
        const Item& item = items_[order_[i]];
        // Every direction's bin position and vertex interval in vectors, then the bins,
        // whose scattered updates stay scalar.
        std::array<DirectionPair, kPairs> position, low, high;
        for (std::size_t p = 0; p < kPairs; ++p) {
            position[p] = (keys_along(p, item.centroid) - key_min[p]) * scale[p];
            low[p] = DirectionPair{kInf, kInf};
            high[p] = -low[p];
            for (const glm::dvec3& v : item.vertices) {
                const DirectionPair along = keys_along(p, v);
                low[p] = lanes_min(low[p], along);
                high[p] = lanes_max(high[p], along);
            }
        }
        for (std::size_t d = 0; d < kCount; ++d) {
            const auto at = std::size_t(lane_of(position, d));
            Bin& bin = bins[d][std::min(kBins - 1, at)];
            bin.count += 1;
            bin.low = std::min(bin.low, lane_of(low, d));
            bin.high = std::max(bin.high, lane_of(high, d));
        }
    }

    const std::size_t count = end - begin;
    const double r2 = 2.0 * settings_.query_radius;
    for (std::size_t d = 0; d < kCount; ++d) {
        if (!binned(d)) continue;
        std::array<double, kBins + 1> suffix_low;
        suffix_low[kBins] = kInf;
        double high = -kInf;
        for (std::size_t b = kBins; b-- > 0;) {
            suffix_low[b] = std::min(suffix_low[b + 1], bins[d][b].low);
            high = std::max(high, bins[d][b].high);
        }
        const double low = suffix_low[0];
        const double span = high - low + r2;
        double left_high = -kInf;
        std::size_t left_count = 0;
        for (std::size_t b = 1; b < kBins; ++b) {
            left_count += bins[d][b - 1].count;
            left_high = std::max(left_high, bins[d][b - 1].high);
            // An empty bin repeats the cut at its right boundary.
            if (left_count == 0 || bins[d][b].count == 0) continue;
            consider_cut(best, normals[d], left_count, count, (left_high - low + r2) / span,
                         (high - suffix_low[b] + r2) / span);
        }
    }
}

void PlaneTreeBuilder::order_along(Scratch& scratch, std::size_t begin, std::size_t end,
                                   const glm::dvec3& normal, std::size_t left_count) {
    // Keys computed once, not at each comparison; nth_element makes the same moves on the
    // entries as it would on the indices, so order_ ends in the same order either way.
    scratch.sweep.resize(end - begin);
    for (std::size_t i = begin; i < end; ++i) {
        const std::uint32_t item = order_[i];
        scratch.sweep[i - begin] = {glm::dot(normal, items_[item].centroid), 0.0, 0.0, item};
    }
    // Only the cut matters: the smallest left_count items along n go left.
    std::nth_element(scratch.sweep.begin(), scratch.sweep.begin() + std::ptrdiff_t(left_count),
                     scratch.sweep.end(), ByKeyThenItem{});
    for (std::size_t i = begin; i < end; ++i) order_[i] = scratch.sweep[i - begin].item;
}

void PlaneTreeBuilder::set_plane(PlaneTreeNode& node, std::size_t begin, std::size_t end,
                                 const glm::dvec3& normal) const {
    double high = -std::numeric_limits<double>::infinity();
    for (std::size_t i = begin; i < end; ++i)
        for (const glm::dvec3& v : items_[order_[i]].vertices)
            high = std::max(high, glm::dot(normal, v));
    for (int k = 0; k < 3; ++k) node.normal[k] = static_cast<float>(normal[k]);
    node.offset = float_up(high);
}

std::size_t PlaneTreeBuilder::bytes_used() const {
    return items_.capacity() * sizeof(Item) + order_.capacity() * sizeof(std::uint32_t) +
           scratch_.sweep.capacity() * sizeof(SweepEntry) +
           scratch_.suffix_low.capacity() * sizeof(double) +
           node_slabs_.capacity() * sizeof(PlaneTreeSlab);
}

PlaneTree make_collider_plane_tree(const StaticCollider& collider,
                                   const PlaneTreeSettings& settings, PlaneTreeFrames frames,
                                   unsigned threads) {
    std::vector<NormalizedTriangle> triangles;
    std::vector<std::uint32_t> ids;
    triangles.reserve(collider.triangle_count());
    ids.reserve(collider.triangle_count());
    for (std::size_t i = 0; i < collider.mesh_triangle_count(); ++i) {
        const auto index = static_cast<std::uint32_t>(i);
        if (!collider.has_triangle(index)) continue;
        triangles.push_back(collider.normalized_triangle(index));
        ids.push_back(index);
    }
    PlaneTree tree;
    {
        PlaneTreeBuilder builder;
        builder.build_nodes(triangles, ids, settings, tree, threads);
        // Only a tree that keeps its frames takes the builder's (the collider's, in leaf
        // order); the boxes, which build() would make too, only a tree that builds its
        // frames keeps, made from the collider. Copied and dropped, they were 144 bytes a
        // triangle at the peak.
        if (frames == PlaneTreeFrames::kept) builder.copy_frames(triangles, tree);
    }  // the builder's scratch freed before the boxes are made
    tree.use_collider_frames(collider, frames);
    tree.shrink_to_fit();
    return tree;
}

std::string PlaneTreeSettings::validate() const {
    if (max_leaf_size < 1 || max_leaf_size > 64)
        return "PlaneTreeSettings.max_leaf_size must be in [1, 64], got " +
               std::to_string(max_leaf_size);
    if (!std::isfinite(query_radius) || !(query_radius > 0.0))
        return "PlaneTreeSettings.query_radius must be finite and > 0, got " +
               exact_text(query_radius);
    if (!std::isfinite(node_cost) || !(node_cost > 0.0))
        return "PlaneTreeSettings.node_cost must be finite and > 0, got " + exact_text(node_cost);
    if (!std::isfinite(slab_thickness) || !(slab_thickness >= 0.0))
        return "PlaneTreeSettings.slab_thickness must be finite and >= 0, got " +
               exact_text(slab_thickness);
    return {};
}

}  // namespace trackphys
