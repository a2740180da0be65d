#include "bvh_builder.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "trackphys/assert.hpp"

namespace trackphys::collision_detail {
namespace {

constexpr int kBins = 16;
constexpr std::uint32_t kMaxLeafSize = 8;
// SAH costs in units of one triangle test. Visiting a node (two child boxes, a stack
// operation) costs about as much as a triangle's box test.
constexpr double kTraversalCost = 1.0;
constexpr double kTriangleCost = 1.0;

constexpr float kInf = std::numeric_limits<float>::infinity();

FloatBox empty_box() { return {{kInf, kInf, kInf}, {-kInf, -kInf, -kInf}}; }

void grow(FloatBox& box, const FloatBox& other) {
    for (int a = 0; a < 3; ++a) {
        box.min[a] = std::min(box.min[a], other.min[a]);
        box.max[a] = std::max(box.max[a], other.max[a]);
    }
}

void grow(FloatBox& box, const float (&point)[3]) {
    for (int a = 0; a < 3; ++a) {
        box.min[a] = std::min(box.min[a], point[a]);
        box.max[a] = std::max(box.max[a], point[a]);
    }
}

// Half the surface area (the SAH only compares ratios), in double so that costs of boxes
// up to 1e18 m times millions of triangles stay finite.
double half_area(const FloatBox& box) {
    if (box.min[0] > box.max[0]) return 0.0;
    const double x = double(box.max[0]) - box.min[0];
    const double y = double(box.max[1]) - box.min[1];
    const double z = double(box.max[2]) - box.min[2];
    return x * y + y * z + z * x;
}

struct Centroid {
    float c[3];
};
Centroid centroid(const FloatBox& box) {
    return {{0.5f * (box.min[0] + box.max[0]), 0.5f * (box.min[1] + box.max[1]),
             0.5f * (box.min[2] + box.max[2])}};
}

struct Bin {
    FloatBox box = empty_box();       // the primitives' boxes
    FloatBox centroids = empty_box();  // their centroids (the child's binning range)
    std::uint32_t count = 0;
};

// Maps a centroid coordinate to its bin along one axis. The partition re-evaluates exactly
// this, so the counts the SAH saw are the counts the children get.
struct BinMap {
    float origin = 0.0f;
    float scale = 0.0f;  // 0: the axis has no extent and cannot be split
    int operator()(float c) const {
        const int b = static_cast<int>((c - origin) * scale);
        return std::clamp(b, 0, kBins - 1);
    }
};

struct Split {
    int axis = -1;
    int last_left_bin = 0;
    double cost = std::numeric_limits<double>::infinity();  // SAH sum, unnormalised
    FloatBox left_box, right_box, left_centroids, right_centroids;
    std::uint32_t left_count = 0;
};

struct WorkItem {
    std::uint32_t node;
    std::uint32_t begin, end;
    int depth;
    FloatBox box;        // bounds of the primitives' boxes
    FloatBox centroids;  // bounds of their centroids
};

Split best_binned_split(const std::vector<BuildPrimitive>& prims, const WorkItem& item,
                        std::array<BinMap, 3>& maps) {
    std::array<std::array<Bin, kBins>, 3> bins{};
    bool any_axis = false;
    for (int a = 0; a < 3; ++a) {
        const float extent = item.centroids.max[a] - item.centroids.min[a];
        maps[a].origin = item.centroids.min[a];
        const float scale = static_cast<float>(kBins) / extent;
        // A zero (or denormal, whose scale overflows) extent cannot be binned.
        maps[a].scale = extent > 0.0f && std::isfinite(scale) ? scale : 0.0f;
        any_axis = any_axis || maps[a].scale > 0.0f;
    }
    Split best;
    if (!any_axis) return best;

    // One pass bins every primitive along all three axes.
    for (std::uint32_t i = item.begin; i < item.end; ++i) {
        const FloatBox& box = prims[i].box;
        const Centroid c = centroid(box);
        for (int a = 0; a < 3; ++a) {
            if (maps[a].scale == 0.0f) continue;
            Bin& bin = bins[a][maps[a](c.c[a])];
            grow(bin.box, box);
            grow(bin.centroids, c.c);
            ++bin.count;
        }
    }

    // Sweep: right-to-left suffix areas, then left-to-right costs A_L N_L + A_R N_R.
    for (int a = 0; a < 3; ++a) {
        if (maps[a].scale == 0.0f) continue;
        std::array<double, kBins> right_area{};
        FloatBox right = empty_box();
        for (int b = kBins - 1; b > 0; --b) {
            grow(right, bins[a][b].box);
            right_area[b] = half_area(right);
        }
        FloatBox left = empty_box();
        std::uint32_t left_count = 0;
        const std::uint32_t total = item.end - item.begin;
        for (int b = 0; b < kBins - 1; ++b) {
            grow(left, bins[a][b].box);
            left_count += bins[a][b].count;
            if (left_count == 0 || left_count == total) continue;
            const double cost = half_area(left) * left_count +
                                right_area[b + 1] * (total - left_count);
            if (cost < best.cost) {
                best.cost = cost;
                best.axis = a;
                best.last_left_bin = b;
                best.left_count = left_count;
            }
        }
    }
    if (best.axis < 0) return best;
    best.left_box = best.right_box = best.left_centroids = best.right_centroids = empty_box();
    for (int b = 0; b < kBins; ++b) {
        const Bin& bin = bins[best.axis][b];
        grow(b <= best.last_left_bin ? best.left_box : best.right_box, bin.box);
        grow(b <= best.last_left_bin ? best.left_centroids : best.right_centroids, bin.centroids);
    }
    return best;
}

void bounds_of(const std::vector<BuildPrimitive>& prims, std::uint32_t begin, std::uint32_t end,
               FloatBox& box, FloatBox& centroids) {
    box = centroids = empty_box();
    for (std::uint32_t i = begin; i < end; ++i) {
        grow(box, prims[i].box);
        grow(centroids, centroid(prims[i].box).c);
    }
}

// Object median along the widest centroid axis (by position, ties by index for
// determinism): always halves the count, the fallback when SAH cannot or may not split.
std::uint32_t median_split(std::vector<BuildPrimitive>& prims, const WorkItem& item) {
    int axis = 0;
    for (int a = 1; a < 3; ++a)
        if (item.centroids.max[a] - item.centroids.min[a] >
            item.centroids.max[axis] - item.centroids.min[axis])
            axis = a;
    const std::uint32_t middle = item.begin + (item.end - item.begin) / 2;
    std::nth_element(prims.begin() + item.begin, prims.begin() + middle, prims.begin() + item.end,
                     [axis](const BuildPrimitive& l, const BuildPrimitive& r) {
                         const float cl = l.box.min[axis] + l.box.max[axis];
                         const float cr = r.box.min[axis] + r.box.max[axis];
                         return cl < cr || (cl == cr && l.index < r.index);
                     });
    return middle;
}

void set_box(BvhNode& node, const FloatBox& box) {
    for (int a = 0; a < 3; ++a) {
        node.min[a] = box.min[a];
        node.max[a] = box.max[a];
    }
}

}  // namespace

FloatBox outward_float_box(const Aabb& box) {
    FloatBox out;
    for (int a = 0; a < 3; ++a) {
        float lo = static_cast<float>(box.min[a]);
        if (static_cast<double>(lo) > box.min[a]) lo = std::nextafter(lo, -kInf);
        float hi = static_cast<float>(box.max[a]);
        if (static_cast<double>(hi) < box.max[a]) hi = std::nextafter(hi, kInf);
        out.min[a] = lo;
        out.max[a] = hi;
    }
    return out;
}

BuiltBvh build_bvh(std::vector<BuildPrimitive> prims) {
    BuiltBvh result;
    const auto count = static_cast<std::uint32_t>(prims.size());
    if (count == 0) return result;
    // A binary tree over n primitives has at most 2n - 1 nodes, plus the unused node 1.
    result.nodes.reserve(2 * std::size_t{count});
    result.nodes.resize(2, BvhNode{});

    std::vector<WorkItem> work;
    WorkItem root{0, 0, count, 0, {}, {}};
    bounds_of(prims, 0, count, root.box, root.centroids);
    work.push_back(root);

    std::array<BinMap, 3> maps;
    while (!work.empty()) {
        const WorkItem item = work.back();
        work.pop_back();
        TP_ASSERT(item.depth < kMaxTreeDepth, "BVH deeper than the traversal stacks allow");
        const std::uint32_t n = item.end - item.begin;
        set_box(result.nodes[item.node], item.box);

        std::uint32_t middle = 0;
        FloatBox left_box{}, right_box{}, left_centroids{}, right_centroids{};
        bool split = false;
        if (n > 1 && item.depth < kMaxSahDepth) {
            const Split best = best_binned_split(prims, item, maps);
            const double split_cost =
                kTraversalCost + kTriangleCost * best.cost / std::max(half_area(item.box), 1e-300);
            const double leaf_cost = kTriangleCost * n;
            if (best.axis >= 0 && (n > kMaxLeafSize || split_cost < leaf_cost)) {
                const BinMap map = maps[best.axis];
                const int axis = best.axis;
                const int last = best.last_left_bin;
                const auto mid = std::partition(
                    prims.begin() + item.begin, prims.begin() + item.end,
                    [&](const BuildPrimitive& p) { return map(centroid(p.box).c[axis]) <= last; });
                middle = static_cast<std::uint32_t>(mid - prims.begin());
                TP_ASSERT(middle - item.begin == best.left_count, "partition disagrees with bins");
                left_box = best.left_box;
                right_box = best.right_box;
                left_centroids = best.left_centroids;
                right_centroids = best.right_centroids;
                split = true;
            }
        }
        if (!split && n > kMaxLeafSize) {
            // Coincident centroids, or too deep for SAH: halve by the median.
            middle = median_split(prims, item);
            bounds_of(prims, item.begin, middle, left_box, left_centroids);
            bounds_of(prims, middle, item.end, right_box, right_centroids);
            split = true;
        }

        BvhNode& node = result.nodes[item.node];
        if (!split) {
            node.first = item.begin;
            node.packed = n | BvhNode::kLeafBit;
            continue;
        }
        const auto left = static_cast<std::uint32_t>(result.nodes.size());
        node.first = left;
        node.packed = n;
        result.nodes.resize(result.nodes.size() + 2, BvhNode{});
        // Right pushed first so the left subtree is built (and laid out) first.
        work.push_back({left + 1, middle, item.end, item.depth + 1, right_box, right_centroids});
        work.push_back({left, item.begin, middle, item.depth + 1, left_box, left_centroids});
    }

    result.order.resize(count);
    for (std::uint32_t i = 0; i < count; ++i) result.order[i] = prims[i].index;
    return result;
}

}  // namespace trackphys::collision_detail
