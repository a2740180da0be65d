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
// kMaxLeafSize (bvh_builder.hpp): leaves are tested a block of slot boxes at a time
// (StaticCollider), so big leaves are cheap. On the default track's car boxes, leaves of 32
// with the traversal cost below were the fastest pair measured, with four- and eight-wide
// nodes alike: smaller leaves cost more node visits, larger ones or costs gained nothing.
// Large nodes choose their split from an evenly strided sample of about this many
// primitives: the SAH picks nearly the same plane, and binning stops dominating the
// top levels of 10M-triangle builds (the partition still sees every primitive).
constexpr std::uint32_t kSampleTarget = 8192;
// SAH costs in units of one triangle test: a node visit (a dependent load, then lane tests
// four at a time) costs about as much as 20 triangles tested a block at a time.
constexpr double kTraversalCost = 20.0;
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

    // One pass bins (a sample of) the primitives along all three axes.
    const std::uint32_t stride =
        std::max<std::uint32_t>(1, (item.end - item.begin) / kSampleTarget);
    std::uint32_t total = 0;
    for (std::uint32_t i = item.begin; i < item.end; i += stride, ++total) {
        const VBox box = VBox::of(prims[i]);
        const Int4 b = map(box.centroid());
        for (int a = 0; a < 3; ++a) {
            Bin& target = bin[a][b[a]];
            target.box.grow(box);
            ++target.count;
        }
    }

    // Sweep: right-to-left suffix areas, then left-to-right costs A_L N_L + A_R N_R (scaled
    // back from the sample so that the leaf-or-split decision compares like with like).
    const double weight = double(item.end - item.begin) / total;
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
            const double cost =
                weight * (half_area(left) * left_count + right_area[b + 1] * (total - left_count));
            if (cost < best.cost) {
                best.cost = cost;
                best.axis = a;
                best.last_left_bin = b;
            }
        }
    }
    return best;
}

// Hoare partition of [begin, end) by `is_left`, accumulating each side's box and centroid
// bounds on the way (the children's boxes and binning ranges): no extra pass is needed.
template <class IsLeft>
std::uint32_t partition(std::vector<BuildPrimitive>& prims, std::uint32_t begin, std::uint32_t end,
                        IsLeft&& is_left, VBox (&left)[2], VBox (&right)[2]) {
    left[0] = left[1] = right[0] = right[1] = VBox{};
    auto take = [&prims](std::uint32_t k, VBox(&side)[2]) {
        side[0].grow(VBox::of(prims[k]));
        side[1].grow(centroid(prims[k]));
    };
    std::uint32_t i = begin, j = end;
    for (;;) {
        while (i < j && is_left(prims[i])) take(i++, left);
        while (i < j && !is_left(prims[j - 1])) take(--j, right);
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

// The binary tree the SAH builds (children adjacent at `first` and `first + 1`), collapsed
// into eight-wide nodes once complete. 32 bytes.
struct BinaryNode {
    static constexpr std::uint32_t kLeafBit = 0x8000'0000u;
    float min[3], max[3];
    std::uint32_t first;   // leaf: first primitive slot; inner: left child index
    std::uint32_t packed;  // kLeafBit for a leaf | primitives in the subtree

    bool is_leaf() const { return (packed & kLeafBit) != 0; }
    std::uint32_t count() const { return packed & ~kLeafBit; }
    void set_box(const VBox& box) {
        for (int a = 0; a < 3; ++a) {
            min[a] = box.lo[a];
            max[a] = box.hi[a];
        }
    }
    double half_area() const {
        const double x = double(max[0]) - min[0], y = double(max[1]) - min[1],
                     z = double(max[2]) - min[2];
        return x * y + y * z + z * x;
    }
};
static_assert(sizeof(BinaryNode) == 32);

// The binned-SAH binary tree over prims (reordered into leaf order). Root at 0.
std::vector<BinaryNode> build_binary(std::vector<BuildPrimitive>& prims) {
    const auto count = static_cast<std::uint32_t>(prims.size());
    std::vector<BinaryNode> nodes;
    // A binary tree over n primitives has at most 2n - 1 nodes.
    nodes.reserve(2 * std::size_t{count});
    nodes.resize(1);

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
        nodes[item.node].set_box(item.box);

        std::uint32_t middle = 0;
        VBox left[2], right[2];  // box, centroid bounds
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
                    [&](const BuildPrimitive& p) { return map(centroid(p))[axis] <= last; }, left,
                    right);
                // Binned primitives lie on both sides of the chosen plane.
                TP_ASSERT(middle > item.begin && middle < item.end, "empty side after a split");
                split = true;
            }
        }
        if (!split && n > kMaxLeafSize) {
            // Coincident centroids, or too deep for SAH: halve by the median.
            middle = median_split(prims, item);
            bounds_of(prims, item.begin, middle, left[0], left[1]);
            bounds_of(prims, middle, item.end, right[0], right[1]);
            split = true;
        }

        BinaryNode& node = nodes[item.node];
        if (!split) {
            node.first = item.begin;
            node.packed = n | BinaryNode::kLeafBit;
            continue;
        }
        const auto first_child = static_cast<std::uint32_t>(nodes.size());
        node.first = first_child;
        node.packed = n;
        nodes.resize(nodes.size() + 2);
        // Right pushed first so the left subtree is built (and laid out) first.
        work.push_back({first_child + 1, middle, item.end, item.depth + 1, right[0], right[1]});
        work.push_back({first_child, item.begin, middle, item.depth + 1, left[0], left[1]});
    }
    return nodes;
}

// Eight-wide nodes from the binary tree, depth first in leaf order: each node starts from
// its binary node's two children (the root, if a leaf lane, is its own single lane) and opens
// the inner lane of largest area, in place so that lanes stay in leaf order, until it has
// eight lanes or only leaf lanes. A binary subtree of at most kMaxLeafLaneSize primitives
// is a leaf lane (never opened). The likeliest-hit boxes get opened, as SAH collapses do.
// A node's children get consecutive indices.
void collapse(const std::vector<BinaryNode>& binary, std::uint32_t count,
              std::vector<BvhNode>& wide) {
    constexpr int kWidth = BvhNode::kWidth;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    struct Item {
        std::uint32_t wide, binary, first, end;
    };
    // At most one wide node per inner binary node (and one for a leaf root).
    wide.reserve(binary.size() / 2 + 1);
    wide.resize(1);
    auto is_leaf_lane = [&binary](std::uint32_t b) {
        return binary[b].is_leaf() || binary[b].count() <= kMaxLeafLaneSize;
    };
    std::vector<Item> work{{0, 0, 0, count}};
    while (!work.empty()) {
        const Item item = work.back();
        work.pop_back();
        std::uint32_t lanes[kWidth];
        int used = 0;
        if (is_leaf_lane(item.binary)) {
            lanes[used++] = item.binary;
        } else {
            lanes[used++] = binary[item.binary].first;
            lanes[used++] = binary[item.binary].first + 1;
        }
        while (used < kWidth) {
            int open = -1;
            double largest = -1.0;
            for (int i = 0; i < used; ++i)
                if (!is_leaf_lane(lanes[i]) && binary[lanes[i]].half_area() > largest) {
                    open = i;
                    largest = binary[lanes[i]].half_area();
                }
            if (open < 0) break;
            for (int i = used; i > open + 1; --i) lanes[i] = lanes[i - 1];
            const std::uint32_t left = binary[lanes[open]].first;
            lanes[open] = left;
            lanes[open + 1] = left + 1;
            ++used;
        }

        BvhNode node;
        std::uint32_t first = item.first;
        for (int i = 0; i < kWidth; ++i) {
            node.first[i] = first;
            if (i >= used) {
                for (int a = 0; a < 3; ++a) node.min[a][i] = node.max[a][i] = nan;
                node.child[i] = BvhNode::kLeaf;
                continue;
            }
            const BinaryNode& b = binary[lanes[i]];
            for (int a = 0; a < 3; ++a) {
                node.min[a][i] = b.min[a];
                node.max[a][i] = b.max[a];
            }
            const bool leaf = is_leaf_lane(lanes[i]);
            node.child[i] = leaf ? BvhNode::kLeaf : static_cast<std::uint32_t>(wide.size());
            if (!leaf) wide.emplace_back();
            first += b.count();
        }
        TP_ASSERT(first == item.end, "collapsed lanes do not cover their node's range");
        wide[item.wide] = node;
        // Last lane pushed first: the tree is laid out depth first in leaf order.
        for (int i = used - 1; i >= 0; --i)
            if (!node.is_leaf(i))
                work.push_back({node.child[i], lanes[i], node.first[i], node.end(i, item.end)});
    }
    wide.shrink_to_fit();
}

}  // namespace

BuiltBvh build_bvh(std::vector<BuildPrimitive> prims) {
    BuiltBvh result;
    const auto count = static_cast<std::uint32_t>(prims.size());
    if (count == 0) return result;
    collapse(build_binary(prims), count, result.nodes);
    result.order.resize(count);
    for (std::uint32_t i = 0; i < count; ++i) result.order[i] = prims[i].index;
    return result;
}

}  // namespace trackphys::collision_detail
