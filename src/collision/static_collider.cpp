#include "trackphys/collision/static_collider.hpp"

#include <array>
#include <limits>
#include <string>

#include "bvh_builder.hpp"
#include "core/fnv1a.hpp"
#include "trackphys/error.hpp"
#include "triangle_predicates.hpp"

namespace trackphys {

using collision_detail::kMaxTreeDepth;

namespace {

constexpr std::uint32_t kNoSlot = std::numeric_limits<std::uint32_t>::max();

// Node boxes are float; comparing float with double converts the float exactly, so these
// tests see the outward-rounded box as it is.
bool node_overlaps(const BvhNode& n, const Aabb& box) {
    return n.min[0] <= box.max.x && box.min.x <= n.max[0] && n.min[1] <= box.max.y &&
           box.min.y <= n.max[1] && n.min[2] <= box.max.z && box.min.z <= n.max[2];
}

bool node_inside(const BvhNode& n, const Aabb& box) {
    return box.min.x <= n.min[0] && n.max[0] <= box.max.x && box.min.y <= n.min[1] &&
           n.max[1] <= box.max.y && box.min.z <= n.min[2] && n.max[2] <= box.max.z;
}

glm::dvec3 node_min(const BvhNode& n) { return {n.min[0], n.min[1], n.min[2]}; }
glm::dvec3 node_max(const BvhNode& n) { return {n.max[0], n.max[1], n.max[2]}; }

template <class T, class A>
std::size_t capacity_bytes(const std::vector<T, A>& v) {
    return v.capacity() * sizeof(T);
}

}  // namespace

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
    nodes_.shrink_to_fit();

    // Permute the triangles into leaf order, and the vertices into the order in which the
    // leaves first use them, so that neighbouring leaves read neighbouring memory.
    const std::size_t n = kept.size();
    slot_vertices_.resize(n);
    slot_to_triangle_.resize(n);
    triangle_to_slot_.assign(mesh.triangles.size(), kNoSlot);
    std::vector<std::uint32_t> vertex_remap(mesh.vertices.size(), kNoSlot);
    std::uint32_t used_vertices = 0;
    for (std::size_t slot = 0; slot < n; ++slot) {
        const std::uint32_t triangle = kept[bvh.order[slot]];
        slot_to_triangle_[slot] = triangle;
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

    core::WordHash hash;
    hash.add(static_cast<std::uint64_t>(mesh.triangles.size()));
    for (const std::uint32_t triangle : kept) {
        hash.add(static_cast<std::uint64_t>(triangle));
        for (const std::uint32_t v : mesh.triangles[triangle]) hash.add(mesh.vertices[v]);
    }
    content_hash_ = hash.value;
}

inline bool StaticCollider::triangle_box_overlaps(std::uint32_t slot, const Aabb& box) const {
    const auto& tri = slot_vertices_[slot];
    return collision_detail::triangle_box(vertices_[tri[0]], vertices_[tri[1]], vertices_[tri[2]])
        .overlaps(box);
}

// Depth-first traversal of the nodes whose boxes overlap `box`, carrying each node's first
// leaf slot (a left child starts where its parent does, the right one after the left's
// count). A node inside the box goes to sink.range whole: its triangles' boxes lie in the
// node box, so each of them overlaps. Leaves on the boundary test each triangle's box.
template <class Sink>
void StaticCollider::visit_aabb(const Aabb& box, Sink&& sink) const {
    if (nodes_.empty() || !node_overlaps(nodes_[0], box)) return;
    struct Entry {
        std::uint32_t node, first;
    };
    std::array<Entry, kMaxTreeDepth + 1> stack;
    int top = 0;
    std::uint32_t node = 0, first = 0;
    for (;;) {
        const BvhNode& n = nodes_[node];
        if (node_inside(n, box)) {
            sink.range(first, n.count());
        } else if (n.is_leaf()) {
            for (std::uint32_t s = first; s < first + n.count(); ++s)
                if (triangle_box_overlaps(s, box)) sink.one(s);
        } else {
            const BvhNode& left = nodes_[n.first];
            const bool hit_left = node_overlaps(left, box);
            const bool hit_right = node_overlaps(nodes_[n.first + 1], box);
            if (hit_left) {
                if (hit_right) stack[top++] = {n.first + 1, first + left.count()};
                node = n.first;
                continue;
            }
            if (hit_right) {
                node = n.first + 1;
                first += left.count();
                continue;
            }
        }
        if (top == 0) return;
        --top;
        node = stack[top].node;
        first = stack[top].first;
    }
}

void StaticCollider::query_aabb(const Aabb& box, std::vector<std::uint32_t>& out) const {
    struct Sink {
        const StaticCollider& self;
        std::vector<std::uint32_t>& out;
        void one(std::uint32_t slot) { out.push_back(self.slot_to_triangle_[slot]); }
        void range(std::uint32_t first, std::uint32_t count) {
            const auto begin = self.slot_to_triangle_.begin() + first;
            out.insert(out.end(), begin, begin + count);
        }
    };
    visit_aabb(box, Sink{*this, out});
}

void StaticCollider::query_aabb_refs(const Aabb& box, std::uint32_t collider_id,
                                     std::vector<TriangleRef>& out) const {
    struct Sink {
        const StaticCollider& self;
        std::uint32_t collider;
        std::vector<TriangleRef>& out;
        void one(std::uint32_t slot) { out.push_back({collider, self.slot_to_triangle_[slot]}); }
        void range(std::uint32_t first, std::uint32_t count) {
            for (std::uint32_t s = first; s < first + count; ++s) one(s);
        }
    };
    visit_aabb(box, Sink{*this, collider_id, out});
}

// The traversal of visit_aabb without the inside shortcut: being inside the query's box
// says nothing about the distance test.
template <class Predicate>
void StaticCollider::visit_box_filtered(const Aabb& box, Predicate&& keep,
                                        std::vector<std::uint32_t>& out) const {
    if (nodes_.empty() || !node_overlaps(nodes_[0], box)) return;
    std::array<std::uint32_t, kMaxTreeDepth + 1> stack;
    int top = 0;
    std::uint32_t node = 0;
    for (;;) {
        const BvhNode& n = nodes_[node];
        if (n.is_leaf()) {
            for (std::uint32_t s = n.first; s < n.first + n.count(); ++s) {
                const auto& tri = slot_vertices_[s];
                if (keep(vertices_[tri[0]], vertices_[tri[1]], vertices_[tri[2]]))
                    out.push_back(slot_to_triangle_[s]);
            }
        } else {
            const bool hit_left = node_overlaps(nodes_[n.first], box);
            const bool hit_right = node_overlaps(nodes_[n.first + 1], box);
            if (hit_left) {
                if (hit_right) stack[top++] = n.first + 1;
                node = n.first;
                continue;
            }
            if (hit_right) {
                node = n.first + 1;
                continue;
            }
        }
        if (top == 0) return;
        node = stack[--top];
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

// Closest-hit traversal: nearer child first, the farther one stacked with its entry
// distance and dropped when popped beyond the best hit. A triangle's reported distance is
// never below its box's entry distance, which is never below its nodes' (the span test is
// monotone in the box), so pruning at "entry > best" loses no hit, ties included.
std::optional<RayHit> StaticCollider::raycast(const glm::dvec3& origin, const glm::dvec3& unit_dir,
                                              double max_distance) const {
    const collision_detail::RayQuery ray =
        collision_detail::make_ray_query(origin, unit_dir, max_distance);
    if (nodes_.empty()) return std::nullopt;
    double best_t = ray.max_distance;
    std::uint32_t best_triangle = kNoSlot, best_slot = kNoSlot;
    double t_near, t_far;
    if (!collision_detail::ray_box_span(ray, node_min(nodes_[0]), node_max(nodes_[0]), best_t,
                                        t_near, t_far))
        return std::nullopt;
    struct Entry {
        std::uint32_t node;
        double t_near;
    };
    std::array<Entry, kMaxTreeDepth + 1> stack;
    int top = 0;
    std::uint32_t node = 0;
    for (;;) {
        const BvhNode& n = nodes_[node];
        if (n.is_leaf()) {
            for (std::uint32_t s = n.first; s < n.first + n.count(); ++s) {
                const auto& tri = slot_vertices_[s];
                const std::optional<double> t = collision_detail::ray_triangle(
                    ray, vertices_[tri[0]], vertices_[tri[1]], vertices_[tri[2]]);
                if (t && collision_detail::better_hit(*t, slot_to_triangle_[s], best_t,
                                                      best_triangle)) {
                    best_t = *t;
                    best_triangle = slot_to_triangle_[s];
                    best_slot = s;
                }
            }
        } else {
            const BvhNode& left = nodes_[n.first];
            const BvhNode& right = nodes_[n.first + 1];
            double near_left, near_right;
            const bool hit_left = collision_detail::ray_box_span(
                ray, node_min(left), node_max(left), best_t, near_left, t_far);
            const bool hit_right = collision_detail::ray_box_span(
                ray, node_min(right), node_max(right), best_t, near_right, t_far);
            if (hit_left && hit_right) {
                const bool left_first = near_left <= near_right;
                stack[top++] = left_first ? Entry{n.first + 1, near_right}
                                          : Entry{n.first, near_left};
                node = left_first ? n.first : n.first + 1;
                continue;
            }
            if (hit_left || hit_right) {
                node = hit_left ? n.first : n.first + 1;
                continue;
            }
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
        node = stack[top].node;
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
           capacity_bytes(slot_to_triangle_) + capacity_bytes(triangle_to_slot_) +
           capacity_bytes(nodes_);
}

}  // namespace trackphys
