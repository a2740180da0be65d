#include "trackphys/collision/plane_tree.hpp"

#include "collision/plane_tree_shapes.hpp"
#include "trackphys/assert.hpp"

namespace trackphys {

using collision_detail::EllipsoidShape;
using collision_detail::SphereShape;

template <class Shape>
PlaneTreeQueryCounts PlaneTree::visit(const Shape& shape, std::vector<std::uint32_t>& out) const {
    PlaneTreeQueryCounts counts;
    if (nodes_.empty()) return counts;
    // A popped node at depth k leaves at most one pending sibling per level above it, and
    // pushes two children of depth k + 1 <= kMaxDepth: never more than kMaxDepth + 1 entries.
    std::uint32_t stack[PlaneTreeSettings::kMaxDepth + 1];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const std::uint32_t index = stack[--top];
        const PlaneTreeNode& node = nodes_[index];
        if (node.has_slab()) {
            ++counts.planes_tested;
            if (!shape.reaches_slab(slabs_[index])) continue;
        }
        if (node.is_leaf()) {
            const std::uint32_t end = node.first + node.count();
            counts.triangles_filtered += node.count();
            for (std::uint32_t slot = node.first; slot < end; ++slot) {
                if (shape.touches(triangles_[slot])) {
                    out.push_back(slot);
                    ++counts.triangles_reported;
                }
            }
            continue;
        }
        counts.planes_tested += 2;
        // Right first onto the stack so the left subtree (lower slots) comes out first and
        // the output is in ascending slot order.
        if (shape.reaches(nodes_[node.first + 1])) stack[top++] = node.first + 1;
        if (shape.reaches(nodes_[node.first])) stack[top++] = node.first;
        TP_ASSERT(top <= PlaneTreeSettings::kMaxDepth + 1, "plane tree deeper than kMaxDepth");
    }
    return counts;
}

PlaneTreeQueryCounts PlaneTree::query_sphere(const glm::dvec3& center, double radius,
                                             std::vector<std::uint32_t>& out) const {
    return visit(SphereShape<false>(center, center, radius), out);
}

PlaneTreeQueryCounts PlaneTree::query_swept_sphere(const glm::dvec3& start, const glm::dvec3& end,
                                                   double radius,
                                                   std::vector<std::uint32_t>& out) const {
    return visit(SphereShape<true>(start, end, radius), out);
}

PlaneTreeQueryCounts PlaneTree::query_swept_ellipsoid(const Ellipsoid& ellipsoid,
                                                      const glm::dvec3& end, double margin,
                                                      std::vector<std::uint32_t>& out) const {
    return visit(EllipsoidShape(ellipsoid, end, margin), out);
}

const NormalizedTriangle& PlaneTree::triangle(std::uint32_t slot) const {
    TP_ASSERT(slot < triangles_.size(), "plane tree slot out of range");
    return triangles_[slot];
}

std::uint32_t PlaneTree::id(std::uint32_t slot) const {
    TP_ASSERT(slot < ids_.size(), "plane tree slot out of range");
    return ids_[slot];
}

std::size_t PlaneTree::bytes_used() const {
    return nodes_.capacity() * sizeof(PlaneTreeNode) +
           slabs_.capacity() * sizeof(PlaneTreeSlab) +
           triangles_.capacity() * sizeof(NormalizedTriangle) +
           ids_.capacity() * sizeof(std::uint32_t);
}

void PlaneTree::shrink_to_fit() {
    nodes_.shrink_to_fit();
    slabs_.shrink_to_fit();
    triangles_.shrink_to_fit();
    ids_.shrink_to_fit();
}

}  // namespace trackphys
