// PlaneTree: queries equal a brute-force scan with the tree's own filter, and that filter is
// the exact contact test (long-double references); node planes hold their triangles; builds
// are deterministic, bounded in depth and reuse storage; bad input is rejected.
#include "trackphys/collision/plane_tree.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <optional>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "collision/collision_meshes.hpp"
#include "collision/plane_tree_reference.hpp"
#include "trackphys/collision/static_collider.hpp"
#include "trackphys/detail/plane_tree_builder.hpp"
#include "trackphys/error.hpp"
#include "trackphys/track/track.hpp"
#include "trackphys/track/track_stats.hpp"

namespace trackphys {
namespace {

using collision_detail::EllipsoidShape;
using collision_detail::SphereShape;

// Reference distances within this of the limit are not judged (rounding of the double
// filter and of the stored frames is ~1e-13 m at these scales).
constexpr long double kTolerance = 1e-9L;

struct Soup {
    std::vector<NormalizedTriangle> triangles;
    std::vector<std::uint32_t> ids;
};

Soup normalized(const TriangleMesh& mesh) {
    Soup soup;
    for (std::uint32_t i = 0; i < mesh.triangles.size(); ++i) {
        const auto& t = mesh.triangles[i];
        const Triangle tri(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
        if (tri.is_degenerate()) continue;
        soup.triangles.emplace_back(tri);
        soup.ids.push_back(i);
    }
    return soup;
}

PlaneTree build(const Soup& soup, const PlaneTreeSettings& settings) {
    PlaneTree tree;
    PlaneTreeBuilder().build(soup.triangles, soup.ids, settings, tree);
    return tree;
}

/// One query: a swept sphere (plain when start == end) or a swept ellipsoid.
struct Query {
    glm::dvec3 start, end;
    double radius = 0.0;
    std::optional<Ellipsoid> ellipsoid;
    double margin = 0.0;
};

struct Tally {
    std::size_t queries = 0, reported = 0, judged = 0;
};

/// The query's result equals the brute-force scan with the same filter, contains every
/// triangle the reference says the shape touches, and nothing the reference says it misses.
void check(const PlaneTree& tree, const Query& q, Tally& tally) {
    std::vector<std::uint32_t> out{12345u};  // queries append: the old entry must survive
    std::vector<std::uint32_t> expected{12345u};
    Aabb near;  // a box holding the shape: triangles outside it cannot touch
    near.expand(q.start);
    near.expand(q.end);
    double scale = 1.0;
    if (q.ellipsoid) {
        tree.query_swept_ellipsoid(*q.ellipsoid, q.end, q.margin, out);
        const EllipsoidShape shape(*q.ellipsoid, q.end, q.margin);
        const auto slots = test::brute_force_slots(tree, shape);
        expected.insert(expected.end(), slots.begin(), slots.end());
        scale = 1.0 + q.margin / q.ellipsoid->sorted_radii().z;
        near = near.padded(q.ellipsoid->bounding_radius() * scale + 1e-6);
    } else if (q.start == q.end) {
        tree.query_sphere(q.start, q.radius, out);
        const auto slots =
            test::brute_force_slots(tree, SphereShape<false>(q.start, q.end, q.radius));
        expected.insert(expected.end(), slots.begin(), slots.end());
        near = near.padded(q.radius + 1e-6);
    } else {
        tree.query_swept_sphere(q.start, q.end, q.radius, out);
        const auto slots =
            test::brute_force_slots(tree, SphereShape<true>(q.start, q.end, q.radius));
        expected.insert(expected.end(), slots.begin(), slots.end());
        near = near.padded(q.radius + 1e-6);
    }
    ASSERT_EQ(out, expected) << "tree query differs from the brute-force scan";
    ++tally.queries;
    tally.reported += out.size() - 1;

    const long double limit = q.ellipsoid ? 1.0L : (long double)q.radius;
    for (std::uint32_t slot = 0; slot < tree.triangle_count(); ++slot) {
        const Triangle t = tree.triangle(slot).triangle();
        if (!t.bounds().overlaps(near)) continue;
        const long double d = q.ellipsoid
                                  ? test::swept_ellipsoid_distance(*q.ellipsoid, scale, q.end, t)
                                  : test::swept_sphere_distance(q.start, q.end, t);
        const bool reported = std::binary_search(out.begin() + 1, out.end(), slot);
        if (d <= limit - kTolerance) {
            ++tally.judged;
            EXPECT_TRUE(reported) << "missed slot " << slot << " at distance " << double(d)
                                  << " <= " << double(limit);
        } else if (d >= limit + kTolerance) {
            ++tally.judged;
            EXPECT_FALSE(reported)
                << "slot " << slot << " at distance " << double(d) << " > " << double(limit);
        }
    }
}

glm::dquat random_rotation(std::mt19937_64& rng) {
    std::normal_distribution<double> g;
    return glm::normalize(glm::dquat(g(rng), g(rng), g(rng), g(rng)));
}

/// Queries placed near random triangles of the soup: spheres, swept spheres and swept
/// ellipsoids (random orientation and semi-axes, some with a margin).
std::vector<Query> queries_near(const Soup& soup, std::size_t count, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<std::size_t> pick(0, soup.triangles.size() - 1);
    std::uniform_real_distribution<double> unit(0.0, 1.0), sym(-1.0, 1.0),
        log_radius(std::log(0.05), std::log(5.0));
    std::vector<Query> out;
    for (std::size_t i = 0; i < count; ++i) {
        const Triangle t = soup.triangles[pick(rng)].triangle();
        double u = unit(rng), v = unit(rng);
        if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
        const glm::dvec3 on = t[0] + (t[1] - t[0]) * u + (t[2] - t[0]) * v;
        const double r = std::exp(log_radius(rng));
        Query q;
        q.start = on + glm::dvec3(sym(rng), sym(rng), sym(rng)) * r;
        const int kind = int(i % 3);
        q.end = kind == 0 ? q.start : q.start + glm::dvec3(sym(rng), sym(rng), sym(rng)) * 2.0;
        q.radius = r;
        if (kind == 2) {
            const glm::dvec3 axes(r * (0.2 + unit(rng)), r * (0.2 + unit(rng)),
                                  r * (0.2 + unit(rng)));
            q.ellipsoid.emplace(q.start, random_rotation(rng), axes);
            q.margin = (i % 2 == 0) ? 0.0 : 0.1 * r * unit(rng);
        }
        out.push_back(q);
    }
    return out;
}

TEST(PlaneTree, RandomSoupQueriesAreExactAndMatchBruteForce) {
    const Soup soup = normalized(test::random_soup(3000, 21));
    for (const PlaneTreeSettings& settings :
         {PlaneTreeSettings::per_update(), PlaneTreeSettings::precomputed()}) {
        const PlaneTree tree = build(soup, settings);
        Tally tally;
        for (const Query& q : queries_near(soup, 450, 22)) check(tree, q, tally);
        // The queries must exercise the filter both ways.
        EXPECT_GT(tally.reported, tally.queries / 2);
        EXPECT_GT(tally.judged - tally.reported, tally.queries / 4);  // judged near misses
    }
}

TEST(PlaneTree, NastyMeshQueriesMatchBruteForce) {
    // Shared edges on a grid, duplicates, kilometre triangles and slivers.
    const Soup soup = normalized(test::nasty_mesh(5));
    const PlaneTree tree = build(soup, PlaneTreeSettings::precomputed());
    Tally tally;
    for (const Query& q : queries_near(soup, 300, 6)) check(tree, q, tally);
    EXPECT_GT(tally.reported, tally.queries);
}

/// The tightest turn's chunk of the default track, and queries shaped like the car's
/// ellipsoids on its road: what the mid phase meets in practice.
struct TrackChunkCase {
    Soup soup;
    std::vector<Query> queries;
};

const TrackChunkCase& track_chunk_case() {
    static const TrackChunkCase instance = [] {
        TrackParams params;
        params.seed = 7;
        const Track track = generate_track(params);
        const std::size_t tightest = compute_track_stats(track).tightest_sample;
        std::size_t chunk = 0;
        while (chunk + 1 < track.chunks.size() && track.chunks[chunk + 1].first_sample <= tightest)
            ++chunk;
        TrackChunkCase c;
        c.soup = normalized(track.chunks[chunk].mesh);
        const std::size_t end = chunk + 1 < track.chunks.size()
                                    ? track.chunks[chunk + 1].first_sample
                                    : track.centerline.size();
        std::mt19937_64 rng(8);
        std::uniform_int_distribution<std::size_t> sample(track.chunks[chunk].first_sample,
                                                          end - 1);
        std::uniform_real_distribution<double> lateral(-7.5, 7.5), height(-0.2, 1.5),
            radius(0.2, 2.0), sweep(0.0, 0.3), unit(0.0, 1.0);
        for (int i = 0; i < 240; ++i) {
            const CenterlineSample& s = track.centerline[sample(rng)];
            Query q;
            q.start = s.position + s.left * lateral(rng) + s.up * height(rng);
            q.end = (i % 3 == 0) ? q.start : q.start + s.tangent * sweep(rng);
            q.radius = radius(rng);
            if (i % 3 == 2) {
                const glm::dquat frame = glm::quat_cast(glm::dmat3(s.left, s.up, s.tangent));
                q.ellipsoid.emplace(
                    q.start, frame,
                    glm::dvec3(0.2 + unit(rng), 0.15 + 0.3 * unit(rng), 0.3 + 1.5 * unit(rng)));
                q.margin = 0.02;
            }
            c.queries.push_back(q);
        }
        return c;
    }();
    return instance;
}

std::pair<std::uint32_t, std::uint32_t> check_subtree(const PlaneTree& tree, std::uint32_t node,
                                                      int depth, int& max_depth);

TEST(PlaneTree, TrackChunkQueriesAreExactAndMatchBruteForce) {
    const TrackChunkCase& c = track_chunk_case();
    for (const PlaneTreeSettings& settings :
         {PlaneTreeSettings::per_update(), PlaneTreeSettings::precomputed()}) {
        const PlaneTree tree = build(c.soup, settings);
        int max_depth = 0;
        check_subtree(tree, 0, 0, max_depth);
        const auto slabs = std::count_if(tree.nodes().begin(), tree.nodes().end(),
                                         [](const PlaneTreeNode& n) { return n.has_slab(); });
        // The precomputed tree puts slabs over the road; the per-update one has none.
        if (settings.slab_thickness > 0.0)
            EXPECT_GT(slabs, 20);
        else
            EXPECT_EQ(slabs, 0);
        Tally tally;
        for (const Query& q : c.queries) check(tree, q, tally);
        EXPECT_GT(tally.reported, 2 * tally.queries);
    }
}

TEST(PlaneTree, QueriesFromTheEntryNodeOfABoxMatchQueriesFromTheRoot) {
    const TrackChunkCase& c = track_chunk_case();
    const PlaneTree tree = build(c.soup, PlaneTreeSettings::precomputed());
    std::size_t below_root = 0, reported = 0;
    std::vector<std::uint32_t> from_root, from_entry;
    for (const Query& q : c.queries) {
        // A car-update-sized box around the query (which it holds).
        Aabb box;
        box.expand(q.start);
        box.expand(q.end);
        box = box.padded(q.ellipsoid ? q.ellipsoid->bounding_radius() * 1.2 + 3.0 : q.radius + 3.0);
        const std::uint32_t entry = tree.entry_node(box);
        below_root += entry != 0 ? 1 : 0;
        from_root.clear();
        from_entry.clear();
        if (q.ellipsoid) {
            tree.query_swept_ellipsoid(*q.ellipsoid, q.end, q.margin, from_root);
            tree.query_swept_ellipsoid(*q.ellipsoid, q.end, q.margin, from_entry, entry);
        } else {
            tree.query_swept_sphere(q.start, q.end, q.radius, from_root);
            tree.query_swept_sphere(q.start, q.end, q.radius, from_entry, entry);
        }
        EXPECT_EQ(from_entry, from_root);
        reported += from_root.size();
    }
    EXPECT_GT(below_root, c.queries.size() / 2);
    EXPECT_GT(reported, c.queries.size());
    EXPECT_EQ(tree.entry_node(Aabb{}), 0u);
}

/// Slot range [begin, end) of the subtree at `node`, checking on the way that every node's
/// plane holds every vertex of its subtree and that depth stays within the cap.
std::pair<std::uint32_t, std::uint32_t> check_subtree(const PlaneTree& tree, std::uint32_t node,
                                                      int depth, int& max_depth) {
    const PlaneTreeNode& n = tree.nodes()[node];
    max_depth = std::max(max_depth, depth);
    std::pair<std::uint32_t, std::uint32_t> range;
    if (n.is_leaf()) {
        range = {n.first, n.first + n.count()};
    } else {
        const auto left = check_subtree(tree, n.first, depth + 1, max_depth);
        const auto right = check_subtree(tree, n.first + 1, depth + 1, max_depth);
        EXPECT_EQ(left.second, right.first) << "children must cover adjacent slot ranges";
        range = {left.first, right.second};
        EXPECT_EQ(n.count(), range.second - range.first);
    }
    if (n.has_slab()) {
        const PlaneTreeSlab& slab = tree.slab(node);
        const glm::dvec3 normal(slab.normal[0], slab.normal[1], slab.normal[2]);
        EXPECT_LE(glm::length(normal), 1.0);
        for (std::uint32_t slot = range.first; slot < range.second; ++slot)
            for (int k = 0; k < 3; ++k) {
                const double d = glm::dot(normal, tree.triangle(slot).vertex(k));
                EXPECT_TRUE(double(slab.low) <= d && d <= double(slab.high))
                    << "node " << node << " slab misses slot " << slot;
            }
    }
    if (node != 0) {
        const glm::dvec3 normal(n.normal[0], n.normal[1], n.normal[2]);
        EXPECT_LE(glm::length(normal), 1.0);
        for (std::uint32_t slot = range.first; slot < range.second; ++slot)
            for (int k = 0; k < 3; ++k)
                EXPECT_LE(glm::dot(normal, tree.triangle(slot).vertex(k)), double(n.offset))
                    << "node " << node << " plane cuts slot " << slot;
    }
    return range;
}

TEST(PlaneTree, NodePlanesHoldTheirTrianglesAndSlotsArePermutation) {
    const Soup soup = normalized(test::random_soup(2000, 31));
    for (const PlaneTreeSettings& settings :
         {PlaneTreeSettings::per_update(), PlaneTreeSettings::precomputed()}) {
        const PlaneTree tree = build(soup, settings);
        int max_depth = 0;
        const auto range = check_subtree(tree, 0, 0, max_depth);
        EXPECT_EQ(range.first, 0u);
        EXPECT_EQ(range.second, tree.triangle_count());
        EXPECT_EQ(max_depth, tree.depth());
        std::vector<std::uint32_t> ids;
        for (std::uint32_t slot = 0; slot < tree.triangle_count(); ++slot)
            ids.push_back(tree.id(slot));
        std::sort(ids.begin(), ids.end());
        EXPECT_EQ(ids, soup.ids);
        if (settings.rule == PlaneSplitRule::pca_median) {
            // Median cuts: a balanced tree with leaves of at most max_leaf_size.
            EXPECT_LE(tree.depth(), 10);
            for (const PlaneTreeNode& n : tree.nodes())
                if (n.is_leaf()) {
                    EXPECT_LE(n.count(), std::uint32_t(settings.max_leaf_size));
                }
        }
    }
}

/// Same nodes, slabs, slots and depth, bit for bit.
void expect_same_tree(const PlaneTree& a, const PlaneTree& b) {
    ASSERT_EQ(a.nodes().size(), b.nodes().size());
    for (std::uint32_t i = 0; i < b.nodes().size(); ++i) {
        const PlaneTreeNode& x = a.nodes()[i];
        const PlaneTreeNode& y = b.nodes()[i];
        EXPECT_TRUE(x.normal[0] == y.normal[0] && x.normal[1] == y.normal[1] &&
                    x.normal[2] == y.normal[2] && x.offset == y.offset && x.first == y.first &&
                    x.packed == y.packed)
            << "node " << i;
        if (x.has_slab() && y.has_slab()) {
            const PlaneTreeSlab &p = a.slab(i), &q = b.slab(i);
            EXPECT_TRUE(p.normal[0] == q.normal[0] && p.normal[1] == q.normal[1] &&
                        p.normal[2] == q.normal[2] && p.low == q.low && p.high == q.high)
                << "slab of node " << i;
        }
    }
    ASSERT_EQ(a.triangle_count(), b.triangle_count());
    for (std::uint32_t slot = 0; slot < b.triangle_count(); ++slot)
        EXPECT_EQ(a.id(slot), b.id(slot));
    EXPECT_EQ(a.depth(), b.depth());
}

TEST(PlaneTree, BuildIsDeterministicAndRebuildReusesStorage) {
    const Soup soup = normalized(test::random_soup(1500, 41));
    const Soup other = normalized(test::random_soup(1200, 42));
    for (const PlaneTreeSettings& settings :
         {PlaneTreeSettings::per_update(), PlaneTreeSettings::precomputed()}) {
        PlaneTreeBuilder builder;
        PlaneTree reused;
        builder.build(other.triangles, other.ids, settings, reused);
        builder.build(soup.triangles, soup.ids, settings, reused);
        expect_same_tree(reused, build(soup, settings));
        // A rebuild over as many triangles keeps the tree's storage.
        const auto* nodes = reused.nodes().data();
        builder.build(soup.triangles, soup.ids, settings, reused);
        EXPECT_EQ(reused.nodes().data(), nodes);
    }
}

TEST(PlaneTree, BuildOnSeveralThreadsIsTheSingleThreadBuild) {
    // Enough triangles for the first levels to be split in waves and the subtrees below
    // built apart, then laid out as one thread lays them: the same tree, whatever the count.
    TriangleMesh mesh = test::random_soup(20000, 61);
    // A flat square's 6000 copies too: equal cuts and slabs.
    for (int i = 0; i < 3000; ++i) {
        const auto v = static_cast<std::uint32_t>(mesh.vertices.size());
        mesh.vertices.insert(mesh.vertices.end(), {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}});
        mesh.triangles.push_back({v, v + 1, v + 2});
        mesh.triangles.push_back({v, v + 2, v + 3});
    }
    const Soup soup = normalized(mesh);
    for (const PlaneTreeSettings& settings :
         {PlaneTreeSettings::per_update(), PlaneTreeSettings::precomputed()}) {
        const PlaneTree one = build(soup, settings);
        if (settings.slab_thickness > 0.0) {
            ASSERT_GT(one.slab_count(), 0u);
        }
        for (const unsigned threads : {2u, 3u, 0u}) {
            SCOPED_TRACE(threads);
            PlaneTree several;
            PlaneTreeBuilder().build(soup.triangles, soup.ids, settings, several, threads);
            expect_same_tree(several, one);
        }
    }
}

TEST(PlaneTree, IdenticalTrianglesStayWithinTheDepthCap) {
    // 3000 copies of one triangle: no plane separates anything, every cut is as good as
    // another. The depth cap and the balanced tie-break keep the tree bounded.
    TriangleMesh mesh;
    mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}};
    mesh.triangles.assign(3000, {0u, 1u, 2u});
    const Soup soup = normalized(mesh);
    for (const PlaneTreeSettings& settings :
         {PlaneTreeSettings::per_update(), PlaneTreeSettings::precomputed()}) {
        const PlaneTree tree = build(soup, settings);
        EXPECT_LE(tree.depth(), PlaneTreeSettings::kMaxDepth);
        EXPECT_LE(tree.depth(), 16);
        std::vector<std::uint32_t> out;
        tree.query_swept_sphere({0.2, 0.5, 0.2}, {0.3, 0.5, 0.3}, 0.6, out);
        EXPECT_EQ(out.size(), 3000u);
        out.clear();
        tree.query_sphere({0.2, 0.7, 0.2}, 0.6, out);
        EXPECT_TRUE(out.empty());
    }
}

TEST(PlaneTree, BinnedCutSeparatesTwoDistantClustersAtTheRoot) {
    // 300 + 100 small triangles 100 m apart along x: far above the full sweep's size, so
    // the root's cut comes from the bins, and the one boundary in the gap costs least. A
    // bin count that disagrees with the items actually moved left would put triangles of
    // one cluster on the other's side.
    TriangleMesh mesh;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int i = 0; i < 400; ++i) {
        const double x = (i < 300 ? 0.0 : 100.0) + 10.0 * unit(rng), z = 10.0 * unit(rng);
        const auto v = static_cast<std::uint32_t>(mesh.vertices.size());
        mesh.vertices.insert(mesh.vertices.end(),
                             {{x, 0.0, z}, {x + 0.5, 0.1 * unit(rng), z}, {x, 0.0, z + 0.5}});
        mesh.triangles.push_back({v, v + 1, v + 2});
    }
    const PlaneTree tree = build(normalized(mesh), PlaneTreeSettings::precomputed());
    const PlaneTreeNode& root = tree.nodes()[0];
    ASSERT_FALSE(root.is_leaf());
    const std::uint32_t left = tree.nodes()[root.first].count();
    EXPECT_TRUE(left == 300 || left == 100) << left;
    // Every slot on the left is from one cluster (ids 0..299 are the first).
    for (std::uint32_t slot = 0; slot < left; ++slot)
        EXPECT_EQ(tree.id(slot) < 300, left == 300) << slot;
}

TEST(PlaneTree, EmptyTreeReportsNothing) {
    PlaneTree tree;
    std::vector<std::uint32_t> out;
    EXPECT_EQ(tree.query_sphere({0, 0, 0}, 1e9, out).triangles_reported, 0u);
    PlaneTreeBuilder().build({}, {}, PlaneTreeSettings::precomputed(), tree);
    tree.query_swept_sphere({0, 0, 0}, {1, 1, 1}, 1e9, out);
    EXPECT_TRUE(out.empty());
    EXPECT_EQ(tree.triangle_count(), 0u);
}

TEST(PlaneTree, RejectsBadSettingsAndInput) {
    const Soup soup = normalized(test::random_soup(10, 51));
    PlaneTree tree;
    PlaneTreeBuilder builder;
    PlaneTreeSettings bad = PlaneTreeSettings::precomputed();
    bad.max_leaf_size = 0;
    EXPECT_THROW(builder.build(soup.triangles, soup.ids, bad, tree), Error);
    bad = PlaneTreeSettings::precomputed();
    bad.query_radius = -1.0;
    EXPECT_THROW(builder.build(soup.triangles, soup.ids, bad, tree), Error);
    bad = PlaneTreeSettings::precomputed();
    bad.slab_thickness = -0.1;
    EXPECT_THROW(builder.build(soup.triangles, soup.ids, bad, tree), Error);
    bad = PlaneTreeSettings::precomputed();
    bad.node_cost = std::nan("");
    EXPECT_THROW(builder.build(soup.triangles, soup.ids, bad, tree), Error);
    EXPECT_THROW(builder.build(soup.triangles, std::span(soup.ids).first(3),
                               PlaneTreeSettings::per_update(), tree),
                 Error);

    builder.build(soup.triangles, soup.ids, PlaneTreeSettings::per_update(), tree);
    std::vector<std::uint32_t> out;
    EXPECT_THROW(tree.query_sphere({std::nan(""), 0, 0}, 1.0, out), Error);
    EXPECT_THROW(tree.query_swept_sphere({0, 0, 0}, {0, 0, 0}, -1.0, out), Error);
    const Ellipsoid e({0, 0, 0}, {1, 0, 0, 0}, {1, 2, 3});
    EXPECT_THROW(tree.query_swept_ellipsoid(e, {0, std::nan(""), 0}, 0.0, out), Error);
    EXPECT_THROW(tree.query_swept_ellipsoid(e, {0, 0, 0}, -0.1, out), Error);
}

TEST(PlaneTree, ColliderTreeIdsAreMeshIndicesOfKeptTriangles) {
    std::size_t degenerate = 0;
    const TriangleMesh mesh = test::nasty_mesh(3, &degenerate);
    const StaticCollider collider(mesh);
    const PlaneTree tree = make_collider_plane_tree(collider);
    ASSERT_EQ(tree.triangle_count(), collider.triangle_count());
    EXPECT_GT(degenerate, 0u);
    // Every id names a kept triangle, each once, and the slot holds that triangle's frame.
    std::vector<std::uint32_t> ids;
    for (std::uint32_t slot = 0; slot < tree.triangle_count(); ++slot) {
        const std::uint32_t id = tree.id(slot);
        ASSERT_TRUE(collider.has_triangle(id));
        ids.push_back(id);
        const NormalizedTriangle expected = collider.normalized_triangle(id);
        EXPECT_EQ(tree.triangle(slot).origin, expected.origin);
        EXPECT_EQ(tree.triangle(slot).x1, expected.x1);
    }
    std::sort(ids.begin(), ids.end());
    EXPECT_EQ(std::adjacent_find(ids.begin(), ids.end()), ids.end());
    // 24-byte nodes, 20-byte slabs on the slab nodes only, a 24-byte box and a 4-byte id,
    // no frames: ~50 bytes a triangle with leaves of a few triangles (160 when the tree kept
    // 120-byte frames and a slab for every node).
    EXPECT_LT(tree.bytes_used(), 64 * tree.triangle_count());
}

// Triangles 2 km out, vertices off the float grid (float steps there are 1.2e-4 m), and
// shapes that touch each one only at its extreme vertex along an axis: the shape's box
// ends exactly where the triangle's double box does, so a slot box rounded inward by one
// float step would drop the triangle although the filter accepts it.
TEST(PlaneTree, ShapesTouchingAtTheSlotBoxBoundsAreReported) {
    std::mt19937_64 rng(31);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    TriangleMesh mesh;
    for (std::uint32_t i = 0; i < 400; ++i) {
        const glm::dvec3 at(2000.0 + 30.0 * unit(rng), 20.0 * unit(rng),
                            -2000.0 + 30.0 * unit(rng));
        for (int k = 0; k < 3; ++k)
            mesh.vertices.push_back(at + glm::dvec3(unit(rng), unit(rng), unit(rng)));
        mesh.triangles.push_back({3 * i, 3 * i + 1, 3 * i + 2});
    }
    const StaticCollider collider(mesh);
    const Soup soup = normalized(mesh);
    const PlaneTree trees[] = {make_collider_plane_tree(collider),
                               build(soup, PlaneTreeSettings::per_update())};
    std::size_t accepted = 0;
    for (const PlaneTree& tree : trees) {
        for (std::uint32_t slot = 0; slot < tree.triangle_count(); ++slot) {
            const Triangle t = collider.triangle(tree.id(slot));
            for (int axis = 0; axis < 3; ++axis) {
                for (const double side : {-1.0, 1.0}) {
                    // The vertex farthest along side * e_axis, and shapes just beyond it.
                    glm::dvec3 v = t[0];
                    for (int k = 1; k < 3; ++k)
                        if (side * t[k][axis] > side * v[axis]) v = t[k];
                    glm::dvec3 out_dir(0.0);
                    out_dir[axis] = side;
                    const double r = 0.3;
                    glm::dvec3 semi(0.5);
                    semi[axis] = r;
                    const Ellipsoid e(v + out_dir * r, glm::dquat(1, 0, 0, 0), semi);
                    std::vector<std::uint32_t> got_sphere, got_ellipsoid;
                    tree.query_sphere(v + out_dir * r, r, got_sphere);
                    tree.query_swept_ellipsoid(e, e.center(), 0.0, got_ellipsoid);
                    EXPECT_EQ(got_sphere,
                              test::brute_force_slots(
                                  tree, SphereShape<false>(v + out_dir * r, v + out_dir * r, r)));
                    EXPECT_EQ(got_ellipsoid,
                              test::brute_force_slots(tree, EllipsoidShape(e, e.center(), 0.0)));
                    accepted += std::count(got_sphere.begin(), got_sphere.end(), slot) +
                                std::count(got_ellipsoid.begin(), got_ellipsoid.end(), slot);
                }
            }
        }
    }
    // The filter accepts most of these tangent contacts (rounding decides the rest).
    EXPECT_GT(accepted, 2 * 2 * 6 * 400 / 2);
}

}  // namespace
}  // namespace trackphys
