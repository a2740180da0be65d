#include "trackphys/detail/plane_tree_builder.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "collision/plane_tree_shapes.hpp"
#include "trackphys/collision/static_collider.hpp"
#include "trackphys/error.hpp"
#include "trackphys/math/symmetric_eigen.hpp"

namespace trackphys {
namespace {

using collision_detail::float_down;
using collision_detail::float_up;

// A float toward zero: |result| <= |x|.
float float_toward_zero(double x) {
    float f = static_cast<float>(x);
    if (std::abs(double(f)) > std::abs(x)) f = std::nextafter(f, 0.0f);
    return f;
}

// The unit direction of v rounded to float toward zero, so that its length is at most 1:
// a sphere test that treats it as unit (n.c - r) is then conservative. Zero when v is.
glm::dvec3 float_direction(const glm::dvec3& v) {
    const double length = glm::length(v);
    if (!(length > 0.0) || !std::isfinite(length)) return glm::dvec3(0.0);
    const glm::dvec3 u = v / length;
    return {float_toward_zero(u.x), float_toward_zero(u.y), float_toward_zero(u.z)};
}

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
                             PlaneTree& tree) {
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
        build_node(0, 0, n, 0);
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
    for (const std::uint32_t item : order_) {
        tree.frames_.push_back(triangles[item]);
        const auto& v = items_[item].vertices;
        tree.boxes_.push_back(collision_detail::float_box(Triangle(v[0], v[1], v[2])));
        tree.ids_.push_back(ids[item]);
    }
    tree_ = nullptr;
}

void PlaneTreeBuilder::build_node(std::uint32_t node, std::size_t begin, std::size_t end,
                                  int depth) {
    const std::size_t count = end - begin;
    tree_->depth_ = std::max(tree_->depth_, depth);
    Split split;
    if (depth >= PlaneTreeSettings::kMaxDepth || !choose_split(begin, end, split)) {
        tree_->nodes_[node].first = static_cast<std::uint32_t>(begin);
        tree_->nodes_[node].packed = PlaneTreeNode::kLeafBit | static_cast<std::uint32_t>(count);
        return;
    }
    order_along(begin, end, split.normal, split.left_count);
    const std::size_t mid = begin + split.left_count;
    const auto child = static_cast<std::uint32_t>(tree_->nodes_.size());
    tree_->nodes_.resize(tree_->nodes_.size() + 2);
    set_plane(tree_->nodes_[child], begin, mid, split.normal);
    set_plane(tree_->nodes_[child + 1], mid, end, -split.normal);
    tree_->nodes_[node].first = child;
    tree_->nodes_[node].packed = static_cast<std::uint32_t>(count);
    build_node(child, begin, mid, depth + 1);
    build_node(child + 1, mid, end, depth + 1);
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

bool PlaneTreeBuilder::choose_split(std::size_t begin, std::size_t end, Split& split) {
    const std::size_t count = end - begin;
    if (count <= 1) return false;
    if (settings_.rule == PlaneSplitRule::pca_median) {
        if (count <= std::size_t(settings_.max_leaf_size)) return false;
        split = pca_median_split(begin, end);
        return true;
    }
    return cost_based_split(begin, end, split);
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

bool PlaneTreeBuilder::cost_based_split(std::size_t begin, std::size_t end, Split& split) {
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
            evaluate_direction(begin, end, direction, best);
    if (!(best.cost < std::numeric_limits<double>::infinity())) return false;
    // Small nodes split only when the model predicts less work than testing them all.
    if (count <= std::size_t(settings_.max_leaf_size) && !(best.cost < double(count))) return false;
    split = best;
    return true;
}

void PlaneTreeBuilder::evaluate_direction(std::size_t begin, std::size_t end,
                                          const glm::dvec3& direction, Split& best) {
    const glm::dvec3 n = float_direction(direction);
    if (n == glm::dvec3(0.0)) return;
    const std::size_t count = end - begin;
    sweep_.resize(count);
    suffix_low_.resize(count + 1);
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
        sweep_[i] = {glm::dot(n, item.centroid), lo, hi, item_index};
        node_low = std::min(node_low, lo);
        node_high = std::max(node_high, hi);
    }
    // Order by centroid along n, ties by item index, as order_along does. The entries carry
    // their key and interval, so the sort compares without looking anything up.
    std::sort(sweep_.begin(), sweep_.end(), by_key_then_item);
    suffix_low_[count] = std::numeric_limits<double>::infinity();
    for (std::size_t k = count; k-- > 0;)
        suffix_low_[k] = std::min(suffix_low_[k + 1], sweep_[k].low);

    // A query that reaches this node is taken as uniform along n over [low - r, high + r];
    // it reaches the left half-space (n.x <= left_high) with probability
    // (left_high - low + 2r) / (high - low + 2r), the right one likewise.
    const double r2 = 2.0 * settings_.query_radius;
    const double span = node_high - node_low + r2;
    double left_high = -std::numeric_limits<double>::infinity();
    for (std::size_t k = 1; k < count; ++k) {
        left_high = std::max(left_high, sweep_[k - 1].high);
        best = cheaper_cut(best, n, k, count, (left_high - node_low + r2) / span,
                           (node_high - suffix_low_[k] + r2) / span);
    }
}

PlaneTreeBuilder::Split PlaneTreeBuilder::cheaper_cut(const Split& best, const glm::dvec3& normal,
                                                      std::size_t left_count, std::size_t count,
                                                      double p_left, double p_right) const {
    // Equal costs (triangles that all overlap, duplicates) go to the most balanced cut,
    // which keeps such nodes from degenerating into a chain.
    const double imbalance = std::abs(2.0 * double(left_count) - double(count));
    const double cost = 2.0 * settings_.node_cost + double(left_count) * std::min(1.0, p_left) +
                        double(count - left_count) * std::min(1.0, p_right) + 1e-9 * imbalance;
    if (!(cost < best.cost)) return best;
    return {normal, left_count, cost};
}

void PlaneTreeBuilder::evaluate_directions_binned(std::size_t begin, std::size_t end,
                                                  const Directions& directions, Split& best) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    constexpr std::size_t kCount = kCandidateDirections;
    struct Along {
        glm::dvec3 n;
        double key_min = kInf, key_max = -kInf;  // centroids
        double low = kInf, high = -kInf;         // vertices
    };
    std::array<Along, kCount> along;
    for (std::size_t d = 0; d < kCount; ++d) along[d].n = float_direction(directions[d]);

    // One pass over the node's items for every direction (each item is read once), keeping
    // each item's centroid key and vertex interval along each. The directions lie in one
    // array per coordinate, so that the compiler runs them side by side in vector lanes:
    // each lane makes glm::dot's products and sums in its order, so the keys are the same.
    std::array<double, kCount> nx, ny, nz, key_min, key_max, low, high;
    for (std::size_t d = 0; d < kCount; ++d) {
        nx[d] = along[d].n.x;
        ny[d] = along[d].n.y;
        nz[d] = along[d].n.z;
        key_min[d] = low[d] = kInf;
        key_max[d] = high[d] = -kInf;
    }
    const auto dot = [&](std::size_t d, const glm::dvec3& v) {
        return nx[d] * v.x + ny[d] * v.y + nz[d] * v.z;
    };
    const std::size_t count = end - begin;
    keys_.resize(count * kCount);
    lows_.resize(count * kCount);
    highs_.resize(count * kCount);
    for (std::size_t i = 0; i < count; ++i) {
        const Item& item = items_[order_[begin + i]];
        double* keys = &keys_[i * kCount];
        double* lows = &lows_[i * kCount];
        double* highs = &highs_[i * kCount];
        for (std::size_t d = 0; d < kCount; ++d) {
            // The same expression as order_along's key, so the cut found is the cut made.
            const double key = dot(d, item.centroid);
            const double v0 = dot(d, item.vertices[0]), v1 = dot(d, item.vertices[1]),
                         v2 = dot(d, item.vertices[2]);
            const double lo = std::min(std::min(v0, v1), v2), hi = std::max(std::max(v0, v1), v2);
            keys[d] = key;
            lows[d] = lo;
            highs[d] = hi;
            key_min[d] = std::min(key_min[d], key);
            key_max[d] = std::max(key_max[d], key);
            low[d] = std::min(low[d], lo);
            high[d] = std::max(high[d], hi);
        }
    }
    for (std::size_t d = 0; d < kCount; ++d) {
        along[d].key_min = key_min[d];
        along[d].key_max = key_max[d];
        along[d].low = low[d];
        along[d].high = high[d];
    }

    // Bins of equal width over the centroid keys. The bin index never decreases with the
    // key (subtracting, scaling and truncating are monotone in floating point), so the items
    // of the bins left of a boundary are exactly the smallest ones along n: each boundary is
    // one of the full sweep's cuts, its cost computed exactly from per-bin extremes.
    struct Bin {
        std::size_t count = 0;
        double low = kInf, high = -kInf;
    };
    const double r2 = 2.0 * settings_.query_radius;
    for (std::size_t d = 0; d < kCount; ++d) {
        const Along& a = along[d];
        if (a.n == glm::dvec3(0.0) || !(a.key_max > a.key_min)) continue;
        std::array<Bin, kBins> bins{};
        const double scale = double(kBins) / (a.key_max - a.key_min);
        for (std::size_t i = 0; i < count; ++i) {
            const std::size_t at = i * kCount + d;
            Bin& bin = bins[std::min(kBins - 1, std::size_t((keys_[at] - a.key_min) * scale))];
            bin.count += 1;
            bin.low = std::min(bin.low, lows_[at]);
            bin.high = std::max(bin.high, highs_[at]);
        }
        std::array<double, kBins + 1> suffix_low;
        suffix_low[kBins] = kInf;
        for (std::size_t b = kBins; b-- > 0;)
            suffix_low[b] = std::min(suffix_low[b + 1], bins[b].low);
        const double span = a.high - a.low + r2;
        double left_high = -kInf;
        std::size_t left_count = 0;
        for (std::size_t b = 1; b < kBins; ++b) {
            left_count += bins[b - 1].count;
            left_high = std::max(left_high, bins[b - 1].high);
            // An empty bin repeats the cut at its right boundary.
            if (left_count == 0 || bins[b].count == 0) continue;
            best = cheaper_cut(best, a.n, left_count, count, (left_high - a.low + r2) / span,
                               (a.high - suffix_low[b] + r2) / span);
        }
    }
}

void PlaneTreeBuilder::order_along(std::size_t begin, std::size_t end, const glm::dvec3& normal,
                                   std::size_t left_count) {
    // Keys computed once, not at each comparison; nth_element makes the same moves on the
    // entries as it would on the indices, so order_ ends in the same order either way.
    sweep_.resize(end - begin);
    for (std::size_t i = begin; i < end; ++i) {
        const std::uint32_t item = order_[i];
        sweep_[i - begin] = {glm::dot(normal, items_[item].centroid), 0.0, 0.0, item};
    }
    // Only the cut matters: the smallest left_count items along n go left.
    std::nth_element(sweep_.begin(), sweep_.begin() + std::ptrdiff_t(left_count), sweep_.end(),
                     by_key_then_item);
    for (std::size_t i = begin; i < end; ++i) order_[i] = sweep_[i - begin].item;
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
           sweep_.capacity() * sizeof(SweepEntry) +
           (keys_.capacity() + lows_.capacity() + highs_.capacity() + suffix_low_.capacity()) *
               sizeof(double) +
           node_slabs_.capacity() * sizeof(PlaneTreeSlab);
}

PlaneTree make_collider_plane_tree(const StaticCollider& collider,
                                   const PlaneTreeSettings& settings, PlaneTreeFrames frames) {
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
    PlaneTreeBuilder().build(triangles, ids, settings, tree);
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
