#include "bvh_builder.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

#include "trackphys/assert.hpp"

namespace trackphys::collision_detail {
namespace {

constexpr int kBins = 16;
constexpr std::uint32_t kMaxLeafSize = 8;
// SAH costs in units of one triangle test. Measured on the 300k banked loop
// (bench_collision_bvh): traversal cost 1 -> 1.06 nodes and 66 bytes per triangle, 3 ->
// 0.43 nodes and 46 bytes, car-box and ray query times unchanged; 5 slows rays by 60%.
constexpr double kTraversalCost = 3.0;
constexpr double kTriangleCost = 1.0;

constexpr float kInf = std::numeric_limits<float>::infinity();

// Four float lanes (x, y, z, unused) in GCC/Clang vector extensions: box unions become one
// packed min and one packed max, and all three bin indices come from one packed multiply.
using Float4 = float __attribute__((vector_size(16)));
using Int4 = std::int32_t __attribute__((vector_size(16)));

Float4 load(const float (&v)[4]) {
    Float4 r;
    std::memcpy(&r, v, sizeof r);
    return r;
}
Float4 min4(Float4 a, Float4 b) { return b < a ? b : a; }
Float4 max4(Float4 a, Float4 b) { return b > a ? b : a; }

struct VBox {
    Float4 lo = {kInf, kInf, kInf, 0.0f};
    Float4 hi = {-kInf, -kInf, -kInf, 0.0f};

    static VBox of(const BuildPrimitive& p) { return {load(p.box.lo), load(p.box.hi)}; }
    void grow(const VBox& other) {
        lo = min4(lo, other.lo);
        hi = max4(hi, other.hi);
    }
    void grow(Float4 point) {
        lo = min4(lo, point);
        hi = max4(hi, point);
    }
    Float4 centroid() const { return (lo + hi) * 0.5f; }
};

// Half the surface area (the SAH only compares ratios), in double so that costs of boxes
// up to 1e18 m times millions of triangles stay finite.
double half_area(const VBox& box) {
    if (box.lo[0] > box.hi[0]) return 0.0;
    const double x = double(box.hi[0]) - box.lo[0];
    const double y = double(box.hi[1]) - box.lo[1];
    const double z = double(box.hi[2]) - box.lo[2];
    return x * y + y * z + z * x;
}

Float4 centroid(const BuildPrimitive& p) { return (load(p.box.lo) + load(p.box.hi)) * 0.5f; }

struct Bin {
    VBox box;
    std::uint32_t count = 0;
};

// Maps centroids to bins along all three axes at once. The partition re-evaluates exactly
// this, so the counts the SAH saw are the counts the children get.
struct BinMap {
    Float4 origin = {0, 0, 0, 0};
    Float4 scale = {0, 0, 0, 0};  // 0 on an axis without extent: it cannot be split
    int bins = kBins;
    Int4 operator()(Float4 c) const {
        Int4 b = __builtin_convertvector((c - origin) * scale, Int4);
        const Int4 zero = {0, 0, 0, 0};
        const Int4 last = {bins - 1, bins - 1, bins - 1, bins - 1};
        b = b < zero ? zero : b;
        return b > last ? last : b;
    }
};

struct Split {
    int axis = -1;
    int last_left_bin = 0;
    double cost = std::numeric_limits<double>::infinity();  // SAH sum, unnormalised
    VBox left_box, right_box;
    std::uint32_t left_count = 0;
};

struct WorkItem {
    std::uint32_t node;
    std::uint32_t begin, end;
    int depth;
    VBox box;        // bounds of the primitives' boxes
    VBox centroids;  // bounds of their centroids
};

Split best_binned_split(const std::vector<BuildPrimitive>& prims, const WorkItem& item,
                        BinMap& map) {
    // Small nodes get one bin per primitive at most: the per-node cost of clearing and
    // sweeping bins dominates near the leaves otherwise.
    const int bins = static_cast<int>(std::min<std::uint32_t>(kBins, item.end - item.begin));
    std::array<std::array<Bin, kBins>, 3> bin{};
    bool splittable[3];
    map.origin = item.centroids.lo;
    map.bins = bins;
    for (int a = 0; a < 3; ++a) {
        const float extent = item.centroids.hi[a] - item.centroids.lo[a];
        const float scale = static_cast<float>(bins) / extent;
        // A zero (or denormal, whose scale overflows) extent cannot be binned.
        splittable[a] = extent > 0.0f && std::isfinite(scale);
        map.scale[a] = splittable[a] ? scale : 0.0f;
    }
    Split best;
    if (!splittable[0] && !splittable[1] && !splittable[2]) return best;

    // One pass bins every primitive along all three axes.
    for (std::uint32_t i = item.begin; i < item.end; ++i) {
        const VBox box = VBox::of(prims[i]);
        const Int4 b = map(box.centroid());
        for (int a = 0; a < 3; ++a) {
            Bin& target = bin[a][b[a]];
            target.box.grow(box);
            ++target.count;
        }
    }

    // Sweep: right-to-left suffix areas, then left-to-right costs A_L N_L + A_R N_R.
    const std::uint32_t total = item.end - item.begin;
    for (int a = 0; a < 3; ++a) {
        if (!splittable[a]) continue;
        std::array<double, kBins> right_area{};
        VBox right;
        for (int b = bins - 1; b > 0; --b) {
            right.grow(bin[a][b].box);
            right_area[b] = half_area(right);
        }
        VBox left;
        std::uint32_t left_count = 0;
        for (int b = 0; b < bins - 1; ++b) {
            left.grow(bin[a][b].box);
            left_count += bin[a][b].count;
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
    for (int b = 0; b < bins; ++b)
        (b <= best.last_left_bin ? best.left_box : best.right_box).grow(bin[best.axis][b].box);
    return best;
}

// Hoare partition of [begin, end) by `is_left`, accumulating each side's centroid bounds
// on the way (the children's binning ranges) so that no extra pass is needed.
template <class IsLeft>
std::uint32_t partition(std::vector<BuildPrimitive>& prims, std::uint32_t begin,
                        std::uint32_t end, IsLeft&& is_left, VBox& left_centroids,
                        VBox& right_centroids) {
    left_centroids = right_centroids = VBox{};
    std::uint32_t i = begin, j = end;
    for (;;) {
        while (i < j && is_left(prims[i])) left_centroids.grow(centroid(prims[i++]));
        while (i < j && !is_left(prims[j - 1])) right_centroids.grow(centroid(prims[--j]));
        if (i >= j) return i;
        std::swap(prims[i], prims[j - 1]);
    }
}

void bounds_of(const std::vector<BuildPrimitive>& prims, std::uint32_t begin, std::uint32_t end,
               VBox& box, VBox& centroids) {
    box = centroids = VBox{};
    for (std::uint32_t i = begin; i < end; ++i) {
        box.grow(VBox::of(prims[i]));
        centroids.grow(centroid(prims[i]));
    }
}

// Object median along the widest centroid axis (by position, ties by index for
// determinism): always halves the count, the fallback when SAH cannot or may not split.
std::uint32_t median_split(std::vector<BuildPrimitive>& prims, const WorkItem& item) {
    int axis = 0;
    for (int a = 1; a < 3; ++a)
        if (item.centroids.hi[a] - item.centroids.lo[a] >
            item.centroids.hi[axis] - item.centroids.lo[axis])
            axis = a;
    const std::uint32_t middle = item.begin + (item.end - item.begin) / 2;
    std::nth_element(prims.begin() + item.begin, prims.begin() + middle, prims.begin() + item.end,
                     [axis](const BuildPrimitive& l, const BuildPrimitive& r) {
                         const float cl = l.box.lo[axis] + l.box.hi[axis];
                         const float cr = r.box.lo[axis] + r.box.hi[axis];
                         return cl < cr || (cl == cr && l.index < r.index);
                     });
    return middle;
}

void set_box(BvhNode& node, const VBox& box) {
    for (int a = 0; a < 3; ++a) {
        node.min[a] = box.lo[a];
        node.max[a] = box.hi[a];
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

    BinMap map;
    while (!work.empty()) {
        const WorkItem item = work.back();
        work.pop_back();
        TP_ASSERT(item.depth < kMaxTreeDepth, "BVH deeper than the traversal stacks allow");
        const std::uint32_t n = item.end - item.begin;
        set_box(result.nodes[item.node], item.box);

        std::uint32_t middle = 0;
        VBox left_box, right_box, left_centroids, right_centroids;
        bool split = false;
        if (n > 1 && item.depth < kMaxSahDepth) {
            const Split best = best_binned_split(prims, item, map);
            const double split_cost =
                kTraversalCost + kTriangleCost * best.cost / std::max(half_area(item.box), 1e-300);
            const double leaf_cost = kTriangleCost * n;
            if (best.axis >= 0 && (n > kMaxLeafSize || split_cost < leaf_cost)) {
                const int axis = best.axis;
                const int last = best.last_left_bin;
                middle = partition(
                    prims, item.begin, item.end,
                    [&](const BuildPrimitive& p) { return map(centroid(p))[axis] <= last; },
                    left_centroids, right_centroids);
                TP_ASSERT(middle - item.begin == best.left_count, "partition disagrees with bins");
                left_box = best.left_box;
                right_box = best.right_box;
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
