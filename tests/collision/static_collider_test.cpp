#include "trackphys/collision/static_collider.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "collision/bvh_builder.hpp"
#include "collision/collision_meshes.hpp"
#include "trackphys/error.hpp"

namespace trackphys {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

TriangleMesh single_triangle() {
    TriangleMesh mesh;
    mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 0, -1}};  // CCW seen from +y: normal +y
    mesh.triangles = {{0, 1, 2}};
    return mesh;
}

std::string error_of(const TriangleMesh& mesh) {
    try {
        StaticCollider collider(mesh);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(StaticCollider, RejectsInvalidMeshesWithMessages) {
    TriangleMesh mesh = single_triangle();
    mesh.vertices.push_back({0, 0, 0});
    mesh.vertices[3].y = std::numeric_limits<double>::quiet_NaN();
    EXPECT_NE(error_of(mesh).find("vertex 3 is not finite"), std::string::npos) << error_of(mesh);

    mesh = single_triangle();
    mesh.vertices[1].x = kInf;
    EXPECT_NE(error_of(mesh).find("vertex 1"), std::string::npos);

    mesh = single_triangle();
    mesh.vertices[2].z = 2e18;
    EXPECT_NE(error_of(mesh).find("vertex 2"), std::string::npos);

    mesh = single_triangle();
    mesh.triangles.push_back({0, 1, 7});
    const std::string message = error_of(mesh);
    EXPECT_NE(message.find("triangle 1"), std::string::npos) << message;
    EXPECT_NE(message.find("vertex 7"), std::string::npos) << message;
}

std::string check_error_of(const TriangleMesh& mesh) {
    try {
        StaticCollider::check(mesh);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(StaticCollider, CheckRefusesWhatTheConstructorRefuses) {
    std::vector<TriangleMesh> refused(3, single_triangle());
    refused[0].vertices[1].x = std::numeric_limits<double>::quiet_NaN();
    refused[1].vertices[2].z = 2e18;
    refused[2].triangles.push_back({0, 1, 7});
    for (const TriangleMesh& mesh : refused) {
        EXPECT_NE(check_error_of(mesh), "");
        EXPECT_EQ(check_error_of(mesh), error_of(mesh));
    }
    TriangleMesh degenerate = single_triangle();
    degenerate.vertices[2] = {2, 0, 0};
    for (const TriangleMesh& mesh : {single_triangle(), degenerate, TriangleMesh{}})
        EXPECT_EQ(check_error_of(mesh), "");
}

TEST(StaticCollider, EmptyColliderAnswersNothing) {
    const StaticCollider collider{TriangleMesh{}};
    std::vector<std::uint32_t> out;
    collider.query_aabb({glm::dvec3(-1e9), glm::dvec3(1e9)}, out);
    collider.query_sphere(glm::dvec3(0.0), 1e9, out);
    collider.query_capsule(glm::dvec3(0.0), glm::dvec3(1.0), 1e9, out);
    EXPECT_TRUE(out.empty());
    EXPECT_FALSE(collider.raycast(glm::dvec3(0.0), {0, -1, 0}, kInf));
    EXPECT_TRUE(collider.bounds().empty());
    EXPECT_EQ(collider.triangle_count(), 0u);
}

TEST(StaticCollider, SingleTriangle) {
    const StaticCollider collider(single_triangle());
    std::vector<std::uint32_t> out;
    collider.query_aabb({{0.5, -1, -0.5}, {2, 1, 2}}, out);
    EXPECT_EQ(out, std::vector<std::uint32_t>{0});
    out.clear();
    collider.query_aabb({{1.0, 0.0, 0.0}, {2, 1, 2}}, out);  // touches at the vertex (1, 0, 0)
    EXPECT_EQ(out, std::vector<std::uint32_t>{0});
    out.clear();
    collider.query_aabb({{1.0 + 1e-12, 0.0, 0.0}, {2, 1, 2}}, out);
    EXPECT_TRUE(out.empty());

    collider.query_sphere({0.25, 0.5, -0.25}, 0.5, out);  // plane distance exactly 0.5
    EXPECT_EQ(out, std::vector<std::uint32_t>{0});
    out.clear();
    collider.query_sphere({0.25, 0.5, -0.25}, 0.49, out);
    EXPECT_TRUE(out.empty());
    // The segment passes the edge z = 0 at 0.3 * sqrt(2) = 0.42426 m.
    collider.query_capsule({-1, 0.3, 0.3}, {1, 0.3, 0.3}, 0.424, out);
    EXPECT_TRUE(out.empty());
    collider.query_capsule({-1, 0.3, 0.3}, {1, 0.3, 0.3}, 0.425, out);
    EXPECT_EQ(out, std::vector<std::uint32_t>{0});
    out.clear();
    collider.query_capsule({0.2, 1, -0.2}, {0.2, -1, -0.2}, 0.0, out);  // pierces it
    EXPECT_EQ(out, std::vector<std::uint32_t>{0});

    const auto hit = collider.raycast({0.25, 2.0, -0.25}, {0, -1, 0}, kInf);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->triangle, 0u);
    EXPECT_DOUBLE_EQ(hit->distance, 2.0);
    EXPECT_EQ(hit->normal, glm::dvec3(0, 1, 0));
    EXPECT_FALSE(collider.raycast({0.25, 2.0, -0.25}, {0, -1, 0}, 1.999));
    EXPECT_TRUE(collider.raycast({0.25, 2.0, -0.25}, {0, -1, 0}, 2.0));
    EXPECT_FALSE(collider.raycast({0.25, 2.0, -0.25}, {0, 1, 0}, kInf));   // pointing away
    EXPECT_FALSE(collider.raycast({0.75, 2.0, -0.75}, {0, -1, 0}, kInf));  // beside it
}

// A steep kerb triangle of c-speedway (15 m x 10 m, 4.8 m high) and a point 1.12 m in front
// of its plane and inside its box: the ray's line crosses the triangle 2.79 m behind the
// origin. Two-sided is about faces, not directions: cast away from the crossing it is a
// miss (not a hit at 0, the start of the ray's span through the box), cast towards it a hit
// at the crossing.
TEST(StaticCollider, RayMissesTheCrossingBehindItsOrigin) {
    TriangleMesh mesh;
    mesh.vertices = {{529.998, 4.8, -46.0011}, {529.998, 0.0, -56.0011}, {544.998, 4.8, -46.001}};
    mesh.triangles = {{0, 1, 2}};
    const StaticCollider collider(mesh);
    const glm::dvec3 origin(535.223739, 2.55347419, -48.0970454);
    const glm::dvec3 dir = glm::normalize(glm::dvec3(-0.539863, -0.681431, -0.494167));
    ASSERT_TRUE(collider.bounds().contains(origin));
    EXPECT_FALSE(collider.raycast(origin, dir, kInf));
    EXPECT_FALSE(collider.raycast(origin, dir, 200.0));
    const auto hit = collider.raycast(origin, -dir, kInf);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->distance, 2.79236, 1e-5);
    const glm::dvec3 on_plane = origin - dir * hit->distance;
    EXPECT_NEAR(glm::dot(on_plane - mesh.vertices[0], hit->normal), 0.0, 1e-12);
}

TEST(StaticCollider, QueriesFarOutsideFindNothing) {
    const StaticCollider collider(test::BankedLoop{}.mesh(100));
    std::vector<std::uint32_t> out;
    collider.query_aabb({glm::dvec3(1e6), glm::dvec3(1e6 + 10)}, out);
    collider.query_sphere(glm::dvec3(-1e7), 100.0, out);
    collider.query_capsule(glm::dvec3(0, 1e5, 0), glm::dvec3(0, 1e5, 10), 50.0, out);
    EXPECT_TRUE(out.empty());
    EXPECT_FALSE(collider.raycast(glm::dvec3(0, 1e6, 0), {0, 1, 0}, kInf));
    EXPECT_FALSE(collider.raycast(glm::dvec3(0, 1e6, 0), {0, -1, 0}, 1e5));
    // ...and a box around everything finds every triangle.
    collider.query_aabb(collider.bounds(), out);
    EXPECT_EQ(out.size(), collider.triangle_count());
}

TEST(StaticCollider, RejectsBadQueries) {
    const StaticCollider collider(single_triangle());
    std::vector<std::uint32_t> out;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(collider.query_sphere({0, 0, 0}, -1.0, out), Error);
    EXPECT_THROW(collider.query_sphere({nan, 0, 0}, 1.0, out), Error);
    EXPECT_THROW(collider.query_capsule({0, 0, 0}, {0, 0, 0}, kInf, out), Error);
    EXPECT_THROW(collider.raycast({0, 0, 0}, {0, 2, 0}, 1.0), Error);
    EXPECT_THROW(collider.raycast({0, 0, 0}, {0, 1, 0}, -1.0), Error);
    EXPECT_THROW(collider.raycast({0, 0, 0}, {0, 1, 0}, nan), Error);
}

TEST(StaticCollider, KeepsTrianglesAsGivenAndDropsDegenerateOnes) {
    std::size_t degenerate = 0;
    const TriangleMesh mesh = test::nasty_mesh(5, &degenerate);
    const StaticCollider collider(mesh);
    EXPECT_EQ(collider.degenerate_count(), degenerate);
    EXPECT_EQ(collider.mesh_triangle_count(), mesh.triangles.size());
    std::size_t kept = 0;
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
        const Triangle given(mesh.vertices[mesh.triangles[t][0]],
                             mesh.vertices[mesh.triangles[t][1]],
                             mesh.vertices[mesh.triangles[t][2]]);
        ASSERT_EQ(collider.has_triangle(t), !given.is_degenerate()) << "triangle " << t;
        if (!collider.has_triangle(t)) {
            EXPECT_THROW(collider.triangle(t), Error);
            continue;
        }
        ++kept;
        EXPECT_EQ(collider.triangle(t).vertices, given.vertices) << "triangle " << t;
    }
    EXPECT_EQ(kept, collider.triangle_count());
    EXPECT_THROW(collider.triangle(static_cast<std::uint32_t>(mesh.triangles.size())), Error);

    // A box around everything returns each kept triangle exactly once, never a dropped one.
    std::vector<std::uint32_t> all;
    collider.query_aabb(collider.bounds(), all);
    std::sort(all.begin(), all.end());
    EXPECT_EQ(std::adjacent_find(all.begin(), all.end()), all.end());
    EXPECT_EQ(all.size(), kept);
}

// The tree's own contract, checked on its nodes: every triangle slot in exactly one leaf
// lane, lanes in leaf order covering their node's range, each lane's box holding its
// child's lanes, empty lanes last with NaN boxes (which no query hits).
TEST(StaticCollider, TreeInvariants) {
    const TriangleMesh mesh = test::random_soup(3000, 9);
    const StaticCollider collider(mesh);
    const auto& nodes = collider.nodes();
    ASSERT_GE(nodes.size(), 2u);
    std::vector<int> seen(collider.triangle_count(), 0), reached(nodes.size(), 0);
    struct Item {
        std::uint32_t node, first, end;
        Aabb box;  // the parent lane's box (everything for the root)
    };
    const auto count = static_cast<std::uint32_t>(collider.triangle_count());
    std::vector<Item> stack{{0, 0, count, {glm::dvec3(-kInf), glm::dvec3(kInf)}}};
    std::size_t leaves = 0, lanes = 0;
    while (!stack.empty()) {
        const Item item = stack.back();
        stack.pop_back();
        ++reached[item.node];
        const BvhNode& n = nodes[item.node];
        ASSERT_EQ(n.first[0], item.first);
        ASSERT_FALSE(n.is_empty(0));
        for (int i = 0; i < BvhNode::kWidth; ++i) {
            const std::uint32_t end = n.end(i, item.end);
            ASSERT_LE(n.first[i], end);
            if (n.is_empty(i)) {
                ASSERT_EQ(n.first[i], item.end);
                ASSERT_TRUE(n.is_leaf(i));
                for (int a = 0; a < 3; ++a)
                    ASSERT_TRUE(std::isnan(n.min[a][i]) && std::isnan(n.max[a][i]));
                continue;
            }
            ++lanes;
            ASSERT_LT(n.first[i], end);
            const Aabb lane{{n.min[0][i], n.min[1][i], n.min[2][i]},
                            {n.max[0][i], n.max[1][i], n.max[2][i]}};
            for (int a = 0; a < 3; ++a) {
                ASSERT_LE(item.box.min[a], lane.min[a]);
                ASSERT_GE(item.box.max[a], lane.max[a]);
            }
            if (!n.is_leaf(i)) {
                ASSERT_LT(n.child[i], nodes.size());
                stack.push_back({n.child[i], n.first[i], end, lane});
                continue;
            }
            ++leaves;
            ASSERT_LE(end - n.first[i], collision_detail::kMaxLeafLaneSize);
            for (std::uint32_t s = n.first[i]; s < end; ++s) ++seen[s];
        }
        // Lanes fill from the first: an empty lane is followed by empty lanes only. The
        // collapse opens inner children until a node is full, so a node with an empty lane
        // has leaves only.
        for (int i = 1; i < BvhNode::kWidth; ++i)
            if (n.is_empty(i - 1)) {
                ASSERT_TRUE(n.is_empty(i));
            }
        if (n.is_empty(BvhNode::kWidth - 1)) {
            for (int i = 0; i < BvhNode::kWidth; ++i) ASSERT_TRUE(n.is_leaf(i));
        }
    }
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int k) { return k == 1; }));
    EXPECT_TRUE(std::all_of(reached.begin(), reached.end(), [](int k) { return k == 1; }));
    EXPECT_GE(lanes, 2 * nodes.size());  // not a binary tree in disguise
    EXPECT_LE(collider.bytes_used(), 200 * mesh.triangles.size());
}

}  // namespace
}  // namespace trackphys

namespace trackphys {
namespace {

// Same mesh, same tree, same answers in the same order (docs/design.md#determinism).
TEST(StaticCollider, BuildsAreDeterministic) {
    const TriangleMesh mesh = test::random_soup(5000, 77);
    const StaticCollider a(mesh), b(mesh);
    ASSERT_EQ(a.nodes().size(), b.nodes().size());
    EXPECT_EQ(std::memcmp(a.nodes().data(), b.nodes().data(), a.nodes().size() * sizeof(BvhNode)),
              0);
    std::vector<std::uint32_t> out_a, out_b;
    a.query_aabb({glm::dvec3(-50.0), glm::dvec3(20.0)}, out_a);
    b.query_aabb({glm::dvec3(-50.0), glm::dvec3(20.0)}, out_b);
    EXPECT_EQ(out_a, out_b);
    EXPECT_FALSE(out_a.empty());
}

// Queries append into the caller's vector and nothing else grows: once it has the
// capacity, repeated queries keep the same storage.
TEST(StaticCollider, ReusedBuffersDoNotReallocate) {
    const test::BankedLoop loop;
    const StaticCollider collider(loop.mesh(400));
    std::vector<std::uint32_t> out;
    out.reserve(4096);
    const std::uint32_t* storage = out.data();
    for (int i = 0; i < 200; ++i) {
        out.clear();
        collider.query_aabb(loop.car_box(i / 200.0, 2.8, 0.5), out);
        ASSERT_FALSE(out.empty());
        collider.query_capsule(loop.frame(i / 200.0).center, loop.frame(i / 200.0).center + 0.3,
                               0.5, out);
        ASSERT_EQ(out.data(), storage);
    }
}

}  // namespace
}  // namespace trackphys
