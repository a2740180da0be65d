#pragma once

// A BvhNode's child boxes against one query box, four at a time, in SSE2 (private; every
// x86-64 level has it). The boxes are stored lane by lane in float;
// the query box is double. (Leaf triangles are tested in 16 bits, eight at a time:
// quantized_boxes.hpp.)
//
// Comparing float bounds with a double box exactly would need double lanes (twice the
// work); instead the query box is rounded to float both ways, and each test uses the
// rounding that keeps its answer safe:
// - "may overlap" uses the outward box: a float bound beyond it is beyond the double box
//   too, so a rejected box surely misses (child and triangle boxes are rounded outward, so
//   nothing they contain is lost).
// - "inside" uses the inward box: the child box lies within the inward box, so within the
//   double box, and every triangle below it overlaps the query.
// NaN bounds (empty node lanes) fail every comparison.

#include <emmintrin.h>

#include "float_bounds.hpp"
#include "trackphys/detail/bvh_node.hpp"

namespace trackphys::collision_detail {

/// Lanes in one SSE2 vector, and vectors per node.
inline constexpr int kVectorLanes = 4;
inline constexpr int kNodeVectors = BvhNode::kWidth / kVectorLanes;
static_assert(BvhNode::kWidth % kVectorLanes == 0);

/// A query box rounded to float both ways, each bound in all four lanes.
struct QueryLanes {
    __m128 out_min[3], out_max[3];  ///< outward: holds the double box
    __m128 in_min[3], in_max[3];    ///< inward: inside the double box

    /// From the query box rounded outward (out) and inward (in).
    QueryLanes(const FloatBox& out, const FloatBox& in) {
        for (int a = 0; a < 3; ++a) {
            out_min[a] = _mm_set1_ps(out.min[a]);
            out_max[a] = _mm_set1_ps(out.max[a]);
            in_min[a] = _mm_set1_ps(in.min[a]);
            in_max[a] = _mm_set1_ps(in.max[a]);
        }
    }
};

/// A node's child boxes as lane vectors: min x, y, z, then max x, y, z, four lanes each.
struct BoxLanes {
    __m128 min[kNodeVectors][3], max[kNodeVectors][3];

    /// From a BvhNode, or any node that stores its lane boxes as it does (aligned
    /// min[axis][lane] and max[axis][lane], BvhNode::kWidth lanes).
    template <class Node>
    static BoxLanes of(const Node& n) {
        BoxLanes b;
        for (int v = 0; v < kNodeVectors; ++v)
            for (int a = 0; a < 3; ++a) {
                b.min[v][a] = _mm_load_ps(n.min[a] + kVectorLanes * v);
                b.max[v][a] = _mm_load_ps(n.max[a] + kVectorLanes * v);
            }
        return b;
    }
};

/// Bit i set: box i may overlap the query (closed intervals; never clear when it does).
inline unsigned may_overlap(const BoxLanes& b, const QueryLanes& q) {
    unsigned mask = 0;
    for (int v = 0; v < kNodeVectors; ++v) {
        __m128 m = _mm_and_ps(_mm_cmple_ps(b.min[v][0], q.out_max[0]),
                              _mm_cmple_ps(q.out_min[0], b.max[v][0]));
        m = _mm_and_ps(m, _mm_and_ps(_mm_cmple_ps(b.min[v][1], q.out_max[1]),
                                     _mm_cmple_ps(q.out_min[1], b.max[v][1])));
        m = _mm_and_ps(m, _mm_and_ps(_mm_cmple_ps(b.min[v][2], q.out_max[2]),
                                     _mm_cmple_ps(q.out_min[2], b.max[v][2])));
        mask |= static_cast<unsigned>(_mm_movemask_ps(m)) << (kVectorLanes * v);
    }
    return mask;
}

/// Bit i set: box i surely lies inside the query (never set when it does not).
inline unsigned surely_inside(const BoxLanes& b, const QueryLanes& q) {
    unsigned mask = 0;
    for (int v = 0; v < kNodeVectors; ++v) {
        __m128 m = _mm_and_ps(_mm_cmple_ps(q.in_min[0], b.min[v][0]),
                              _mm_cmple_ps(b.max[v][0], q.in_max[0]));
        m = _mm_and_ps(m, _mm_and_ps(_mm_cmple_ps(q.in_min[1], b.min[v][1]),
                                     _mm_cmple_ps(b.max[v][1], q.in_max[1])));
        m = _mm_and_ps(m, _mm_and_ps(_mm_cmple_ps(q.in_min[2], b.min[v][2]),
                                     _mm_cmple_ps(b.max[v][2], q.in_max[2])));
        mask |= static_cast<unsigned>(_mm_movemask_ps(m)) << (kVectorLanes * v);
    }
    return mask;
}

/// Bit i set: lane i is a leaf or empty (BvhNode::kLeaf is the sign bit).
inline unsigned leaf_lanes(const BvhNode& n) {
    unsigned mask = 0;
    for (int v = 0; v < kNodeVectors; ++v) {
        const __m128i child =
            _mm_load_si128(reinterpret_cast<const __m128i*>(n.child + kVectorLanes * v));
        mask |= static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(child)))
                << (kVectorLanes * v);
    }
    return mask;
}

}  // namespace trackphys::collision_detail
