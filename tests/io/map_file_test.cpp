// Map files: a loaded map answers every query as the freshly built one and encodes to the
// same bytes; every truncation, every altered header field, another version or other build
// options, and flips in every array are an error naming the file, or (flips the checks
// cannot tell from valid data) a map whose queries stay in bounds (run under ASan too).
#include "trackphys/io/map_file.hpp"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

#include "io/map_body.hpp"
#include "io/map_codec.hpp"
#include "support/error_message.hpp"
#include "trackphys/error.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/geometry/mesh_chunks.hpp"

namespace trackphys {
namespace {

using test::error_of;

constexpr std::size_t kHeaderBytes = 64;
constexpr std::size_t kChecksumAt = 24;

// A 1 km generated track: ten chunks, ~60k triangles, baked once for all tests.
const StaticMap& baked() {
    static const StaticMap map = [] {
        TrackParams params;
        params.seed = 3;
        params.length_m = 1000.0;
        return bake_track_map(generate_track(params), PlaneTreeSettings::precomputed(), 2);
    }();
    return map;
}
const std::string& baked_bytes() {
    static const std::string bytes = encode_map(baked());
    return bytes;
}

// The bytes with the header's checksum made to match again, as a crafted file would.
std::string resealed(std::string bytes) {
    std::memset(bytes.data() + kChecksumAt, 0, 8);
    map_detail::MapChecksum checksum;
    checksum.add(bytes.data(), bytes.size() / 8 * 8);
    const std::uint64_t value = checksum.value();
    std::memcpy(bytes.data() + kChecksumAt, &value, 8);
    return bytes;
}

// Where each array of the file lies: [begin, end) in bytes, and its name.
struct Section {
    std::size_t begin, end;
    std::string name;
};
std::vector<Section> sections_of(const std::string& bytes) {
    std::vector<Section> out;
    std::size_t at = kHeaderBytes + 64;  // the map record
    const auto add = [&](std::uint64_t bytes_used, const std::string& name) {
        out.push_back({at, at + bytes_used, name});
        at += map_detail::padded(bytes_used);
    };
    const StaticMap& map = baked();
    add(112, "track parameters");
    add(map.track->centerline.size() * sizeof(CenterlineSample), "centreline");
    for (std::uint32_t id = 0; id < map.statics->size(); ++id) {
        detail::MapCodec::ColliderRecord r;
        std::memcpy(&r, bytes.data() + at, sizeof r);
        const std::string c = "collider " + std::to_string(id) + " ";
        add(sizeof r, c + "record");
        add(r.vertices * 24, c + "vertices");
        add(r.slots * 12, c + "slot vertices");
        add(r.mesh_triangles * 4, c + "triangle slots");
        add((r.slots + 7) / 8 * 128, c + "slot blocks");
        add(r.nodes * 256, c + "BVH nodes");
        add(r.grids * 48, c + "grids");
        add(r.nodes * 4, c + "node grids");
        add(r.plane_nodes * 24, c + "plane nodes");
        add(r.plane_slabs * 20, c + "plane slabs");
        add(r.slots * 4, c + "plane ids");
        add(r.surfaces * 2, c + "surface ids");
    }
    EXPECT_EQ(at, bytes.size()) << "the sections do not cover the file";
    return out;
}

// Random queries around the map: boxes of car size to a few hundred metres, rays in any
// direction, spheres and swept ellipsoids for the plane trees.
struct QueryRun {
    std::vector<TriangleRef> boxes;
    std::vector<std::uint32_t> rays;
    std::vector<double> ray_distances;
    std::vector<std::uint32_t> tree_slots;
    std::vector<std::uint32_t> tree_ids;
};

QueryRun run_queries(const StaticMap& map, int count) {
    std::mt19937 rng(11);
    Aabb bounds;
    for (std::uint32_t id = 0; id < map.statics->size(); ++id)
        bounds.expand(map.statics->collider(id).bounds());
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const auto point = [&] {
        return bounds.min + (bounds.max - bounds.min) * glm::dvec3(u(rng), u(rng), u(rng));
    };
    QueryRun run;
    std::vector<std::uint32_t> slots;
    for (int q = 0; q < count; ++q) {
        const glm::dvec3 center = point();
        const double half = q % 10 == 0 ? 200.0 * u(rng) : 3.0 * u(rng);
        map.statics->query_aabb(Aabb{center - half, center + half}, run.boxes);

        glm::dvec3 dir(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
        dir = glm::normalize(dir + glm::dvec3(0.0, 1e-3, 0.0));
        const auto hit = map.statics->raycast(center + glm::dvec3(0.0, 5.0, 0.0), dir, 500.0);
        run.rays.push_back(hit ? hit->collider : ~0u);
        run.rays.push_back(hit ? hit->hit.triangle : ~0u);
        run.ray_distances.push_back(hit ? hit->hit.distance : -1.0);

        const std::uint32_t id = q % static_cast<std::uint32_t>(map.statics->size());
        const PlaneTree& tree = *map.plane_trees[id];
        const glm::dvec3 near = map.statics->collider(id).bounds().center() +
                                glm::dvec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5) * 60.0;
        const Aabb box{near - 4.0, near + 4.0};
        slots.clear();
        tree.query_sphere(near, 3.0 * u(rng), slots, tree.entry_node(box));
        const Ellipsoid body(near, glm::angleAxis(u(rng), glm::dvec3(0.0, 1.0, 0.0)),
                             glm::dvec3(0.9, 0.4, 2.1));
        tree.query_swept_ellipsoid(body, near + glm::dvec3(0.0, 0.0, 1.0), 0.05, slots);
        for (const std::uint32_t s : slots) {
            run.tree_slots.push_back(s);
            run.tree_ids.push_back(tree.id(s));
        }
    }
    return run;
}

// Whether the loaded trees keep their frames (the default budget holds this map's, as the
// baked trees keep theirs) or build them (no budget).
class MapFileFrames : public testing::TestWithParam<std::size_t> {};

TEST_P(MapFileFrames, LoadedMapAnswersTenThousandQueriesAsTheBuiltOne) {
    const std::size_t budget = GetParam();
    const StaticMap loaded =
        decode_map(baked_bytes(), "map", PlaneTreeSettings::precomputed(), 0, budget);
    ASSERT_EQ(loaded.statics->size(), baked().statics->size());
    for (std::uint32_t id = 0; id < loaded.statics->size(); ++id) {
        EXPECT_TRUE(baked().plane_trees[id]->keeps_frames());
        EXPECT_EQ(loaded.plane_trees[id]->keeps_frames(), budget != 0);
        const PlaneTree& a = *baked().plane_trees[id];
        const PlaneTree& b = *loaded.plane_trees[id];
        for (std::uint32_t slot = 0; slot < a.triangle_count(); slot += 97) {
            const NormalizedTriangle fa = a.triangle(slot), fb = b.triangle(slot);
            ASSERT_EQ(std::memcmp(&fa, &fb, sizeof fa), 0) << "collider " << id << " slot " << slot;
        }
    }
    for (std::uint32_t id = 0; id < loaded.statics->size(); ++id) {
        const StaticCollider& a = baked().statics->collider(id);
        const StaticCollider& b = loaded.statics->collider(id);
        EXPECT_EQ(a.content_hash(), b.content_hash());
        EXPECT_EQ(a.bounds().min, b.bounds().min);
        EXPECT_EQ(a.bounds().max, b.bounds().max);
        EXPECT_EQ(baked().plane_trees[id]->depth(), loaded.plane_trees[id]->depth());
    }
    const QueryRun fresh = run_queries(baked(), 10'000), back = run_queries(loaded, 10'000);
    EXPECT_GT(fresh.boxes.size(), 100'000u) << "the queries should find triangles";
    EXPECT_GT(fresh.tree_slots.size(), 1'000u);
    EXPECT_EQ(fresh.boxes, back.boxes);
    EXPECT_EQ(fresh.rays, back.rays);
    EXPECT_EQ(fresh.ray_distances, back.ray_distances);
    EXPECT_EQ(fresh.tree_slots, back.tree_slots);
    EXPECT_EQ(fresh.tree_ids, back.tree_ids);
}

INSTANTIATE_TEST_SUITE_P(MapFile, MapFileFrames, testing::Values(kPlaneTreeFrameBudget, 0));

TEST(MapFile, LoadedMapEncodesToTheSameBytesAndKeepsItsTrack) {
    const StaticMap loaded = decode_map(baked_bytes());
    EXPECT_EQ(encode_map(loaded), baked_bytes());
    ASSERT_TRUE(loaded.track.has_value());
    EXPECT_TRUE(loaded.track->chunks.empty());
    EXPECT_EQ(loaded.track->params.seed, 3u);
    EXPECT_EQ(loaded.track->length_m, baked().track->length_m);
    EXPECT_EQ(loaded.track->centerline.size(), baked().track->centerline.size());
}

TEST(MapFile, BakeGivesTheSameMapOnAnyThreadCount) {
    TrackParams params;
    params.seed = 3;
    params.length_m = 1000.0;
    const Track track = generate_track(params);
    EXPECT_EQ(encode_map(bake_track_map(track, PlaneTreeSettings::precomputed(), 1)),
              baked_bytes());
}

// One mesh is one collider, whose tree takes every thread: the same map as on one.
TEST(MapFile, BakeGivesTheSameMapOnAnyThreadCountForOneMesh) {
    TrackParams params;
    params.seed = 3;
    params.length_m = 1000.0;
    TriangleMesh whole;
    for (const TrackChunk& chunk : generate_track(params).chunks) {
        const auto offset = static_cast<std::uint32_t>(whole.vertices.size());
        whole.vertices.insert(whole.vertices.end(), chunk.mesh.vertices.begin(),
                              chunk.mesh.vertices.end());
        for (const auto& t : chunk.mesh.triangles)
            whole.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
    }
    ASSERT_GT(whole.triangles.size(), 20'000u) << "enough for the tree to split apart";
    const std::string one = encode_map(bake_map({&whole, 1}, PlaneTreeSettings::precomputed(), 1));
    for (const unsigned threads : {2u, 3u})
        EXPECT_EQ(encode_map(bake_map({&whole, 1}, PlaneTreeSettings::precomputed(), threads)), one)
            << threads << " threads";
}

// The progress hears each collider once, counting up to all of them, one call at a time
// from whichever thread built it, and the bake is the same map for listening.
TEST(MapFile, BakeProgressHearsEachColliderOnceOnAnyThreadCount) {
    TrackParams params;
    params.seed = 3;
    params.length_m = 1000.0;
    const Track track = generate_track(params);
    for (const unsigned threads : {1u, 2u, 4u}) {
        std::vector<std::size_t> dones;
        std::vector<std::size_t> totals;
        const StaticMap map = bake_track_map(track, PlaneTreeSettings::precomputed(), threads,
                                             [&](std::size_t done, std::size_t total) {
                                                 dones.push_back(done);
                                                 totals.push_back(total);
                                             });
        std::vector<std::size_t> counting(track.chunks.size());
        std::iota(counting.begin(), counting.end(), std::size_t{1});
        EXPECT_EQ(dones, counting) << threads << " threads";
        EXPECT_EQ(totals, std::vector<std::size_t>(track.chunks.size(), track.chunks.size()))
            << threads << " threads";
        EXPECT_EQ(encode_map(map), baked_bytes()) << threads << " threads";
    }
}

TEST(MapFile, BakeProgressThatThrowsCancelsTheBake) {
    TrackParams params;
    params.seed = 3;
    params.length_m = 1000.0;
    const Track track = generate_track(params);
    ASSERT_GE(track.chunks.size(), 8u);
    struct Cancelled {};
    for (const unsigned threads : {1u, 2u}) {
        std::size_t heard = 0;
        EXPECT_THROW(bake_track_map(track, PlaneTreeSettings::precomputed(), threads,
                                    [&](std::size_t done, std::size_t) {
                                        heard = done;
                                        if (done == 3) throw Cancelled{};
                                    }),
                     Cancelled);
        // On one thread nothing is built after the third collider; on two, the other
        // thread finishes the collider it had begun (and, descheduled, perhaps one more).
        if (threads == 1) {
            EXPECT_EQ(heard, 3u);
        }
        EXPECT_LT(heard, track.chunks.size()) << threads << " threads";
    }
}

TEST(MapFile, EveryTruncationIsAnErrorNamingTheSource) {
    const std::string& bytes = baked_bytes();
    for (int k = 0; k < 64; ++k) {
        const std::size_t size = bytes.size() * k / 64;
        const std::string message =
            error_of([&] { decode_map(std::string_view(bytes).substr(0, size), "map 'cut'"); });
        EXPECT_EQ(message.rfind("map 'cut': ", 0), 0u) << size << ": " << message;
        EXPECT_TRUE(message.find("truncated") != std::string::npos ||
                    message.find("shorter than") != std::string::npos)
            << size << ": " << message;
    }
}

TEST(MapFile, EveryAlteredHeaderFieldIsAnError) {
    // Field offsets and what the message must say.
    const struct {
        std::size_t at, size;
        const char* says;
    } fields[] = {
        {0, 8, "wrong magic"}, {8, 4, "format version"}, {12, 4, "header claims"},
        {16, 8, "body bytes"}, {24, 8, "checksum"},      {32, 4, "checksum"},
        {36, 4, "checksum"},   {40, 8, "checksum"},      {48, 8, "checksum"},
        {56, 8, "checksum"},
    };
    for (const auto& f : fields) {
        std::string bytes = baked_bytes();
        bytes[f.at + f.size - 1] ^= 0x01;
        bytes[f.at] ^= 0x10;
        const std::string message = error_of([&] { decode_map(bytes); });
        EXPECT_NE(message.find(f.says), std::string::npos) << f.at << ": " << message;
    }
}

// Plane-tree settings no tree could be built with, in a sealed file read without expected
// settings (which would hand them to the caller), are refused naming the field: the header's
// max leaf size at byte 36, query radius at 40, node cost at 48, slab thickness at 56.
TEST(MapFile, HeaderPlaneTreeSettingsNoTreeCouldUseAreRefused) {
    const auto with = [](std::size_t at, auto value) {
        std::string bytes = baked_bytes();
        std::memcpy(bytes.data() + at, &value, sizeof value);
        return error_of([&] { decode_map(resealed(bytes), "map", std::nullopt); });
    };
    EXPECT_NE(
        with(36, std::uint32_t{0})
            .find("the header's plane-tree settings: PlaneTreeSettings.max_leaf_size must be in "
                  "[1, 64], got 0"),
        std::string::npos);
    EXPECT_NE(with(40, -1.0).find("PlaneTreeSettings.query_radius must be finite and > 0, got -1"),
              std::string::npos);
    EXPECT_NE(with(48, std::numeric_limits<double>::quiet_NaN())
                  .find("PlaneTreeSettings.node_cost must be finite and > 0, got nan"),
              std::string::npos);
    EXPECT_NE(with(56, std::numeric_limits<double>::infinity())
                  .find("PlaneTreeSettings.slab_thickness must be finite and >= 0, got inf"),
              std::string::npos);
}

// The checksum is computed beside the colliders' reading, yet it is the error reported, on
// any thread count, also when the flip breaks a record or an array.
TEST(MapFile, AnyByteFlipFailsTheChecksum) {
    std::mt19937 rng(5);
    const std::string& good = baked_bytes();
    std::uniform_int_distribution<std::size_t> at(kHeaderBytes, good.size() - 1);
    for (int i = 0; i < 200; ++i) {
        std::string bytes = good;
        bytes[at(rng)] ^= static_cast<char>(1 + rng() % 255);
        for (const unsigned threads : {1u, 3u})
            EXPECT_EQ(error_of([&] {
                          decode_map(bytes, "map", PlaneTreeSettings::precomputed(), threads);
                      }),
                      "map: checksum mismatch (the file is corrupted)")
                << threads;
    }
}

TEST(MapFile, FlipsInEveryArrayAreRejectedOrStayInBounds) {
    const std::string& good = baked_bytes();
    std::mt19937 rng(7);
    int rejected = 0, loaded = 0;
    for (const Section& s : sections_of(good)) {
        if (s.begin == s.end) continue;
        std::uniform_int_distribution<std::size_t> at(s.begin, s.end - 1);
        for (int i = 0; i < 3; ++i) {
            std::string bytes = good;
            for (int k = 0; k < 1 + i; ++k) bytes[at(rng)] ^= static_cast<char>(1 + rng() % 255);
            StaticMap map;
            try {
                map = decode_map(resealed(bytes), "map 'flipped'");
            } catch (const Error& e) {
                EXPECT_EQ(std::string(e.what()).rfind("map 'flipped': ", 0), 0u) << e.what();
                ++rejected;
                continue;
            }
            ++loaded;
            run_queries(map, 5);  // in bounds, and it ends (ASan and the timeout watch)
        }
    }
    EXPECT_GT(rejected, 30) << "the structure checks should catch many flips";
    EXPECT_GT(loaded, 30) << "flips in coordinates should still load";
}

TEST(MapFile, CraftedStructuresAreRejected) {
    const std::string& good = baked_bytes();
    const std::vector<Section> sections = sections_of(good);
    const auto section = [&](const std::string& name) {
        return *std::find_if(sections.begin(), sections.end(),
                             [&](const Section& s) { return s.name == name; });
    };
    const auto with = [&](std::size_t at, std::uint32_t value) {
        std::string bytes = good;
        std::memcpy(bytes.data() + at, &value, 4);
        return error_of([&] { decode_map(resealed(bytes)); });
    };
    const Section nodes = section("collider 0 BVH nodes");
    const std::size_t child0 = nodes.begin + offsetof(BvhNode, child);
    EXPECT_NE(with(child0, 0).find("BVH node 0"), std::string::npos) << with(child0, 0);
    EXPECT_NE(with(child0, 1u << 30).find("out of range"), std::string::npos);
    const Section plane = section("collider 0 plane nodes");
    // The root's children made the root itself: a cycle.
    const std::size_t root_first = plane.begin + offsetof(PlaneTreeNode, first);
    EXPECT_NE(with(root_first, 0).find("plane-tree node 0"), std::string::npos)
        << with(root_first, 0);
    // A slab flag on the root (which has none): one slab fewer than flagged nodes.
    const std::size_t root_packed = plane.begin + offsetof(PlaneTreeNode, packed);
    std::uint32_t packed = 0;
    std::memcpy(&packed, good.data() + root_packed, 4);
    ASSERT_EQ(packed & PlaneTreeNode::kSlabBit, 0u);
    const std::string extra_slab = with(root_packed, packed | PlaneTreeNode::kSlabBit);
    EXPECT_NE(extra_slab.find("nodes with a slab"), std::string::npos) << extra_slab;
    const Section ids = section("collider 0 plane ids");
    EXPECT_NE(with(ids.begin, 1u << 30).find("not a triangle the collider keeps"),
              std::string::npos);
    const Section verts = section("collider 0 slot vertices");
    EXPECT_NE(with(verts.begin, 1u << 30).find("vertex index"), std::string::npos);
}

// Colliders are loaded on several threads: the map, and the error a bad one gives, must be
// those of a serial load.
TEST(MapFile, AnyThreadCountLoadsTheSameAndNamesTheFirstBadCollider) {
    for (const unsigned threads : {1u, 2u, 3u})
        EXPECT_EQ(
            encode_map(decode_map(baked_bytes(), "map", PlaneTreeSettings::precomputed(), threads)),
            baked_bytes())
            << threads << " threads";

    const std::vector<Section> sections = sections_of(baked_bytes());
    std::string bytes = baked_bytes();
    for (const char* name : {"collider 3 slot vertices", "collider 8 slot vertices"}) {
        const Section s = *std::find_if(sections.begin(), sections.end(),
                                        [&](const Section& x) { return x.name == name; });
        const std::uint32_t out_of_range = 1u << 30;
        std::memcpy(bytes.data() + s.begin, &out_of_range, 4);
    }
    bytes = resealed(bytes);
    for (const unsigned threads : {1u, 2u, 3u}) {
        const std::string message =
            error_of([&] { decode_map(bytes, "map", PlaneTreeSettings::precomputed(), threads); });
        EXPECT_NE(message.find("collider 3: slot 0: vertex index"), std::string::npos)
            << threads << " threads: " << message;
    }
}

// Surface ids go from the mesh through the collider and the file back, by mesh index, a
// dropped triangle's too; a mesh without ids loads without any.
TEST(MapFile, SurfaceIdsSurviveTheFile) {
    TriangleMesh labelled;
    labelled.vertices = {{0, 0, 0}, {10, 0, 0}, {10, 0, 10}, {0, 0, 10}, {20, 0, 0}};
    labelled.triangles = {{0, 2, 1}, {0, 1, 4}, {0, 3, 2}};  // the second is degenerate
    labelled.surfaces = {3, 7, 1};
    TriangleMesh plain = labelled;
    plain.surfaces.clear();
    const std::vector<TriangleMesh> meshes = {labelled, plain};
    const StaticMap loaded = decode_map(encode_map(bake_map(meshes)));
    const StaticCollider& first = loaded.statics->collider(0);
    for (std::uint32_t t = 0; t < 3; ++t) EXPECT_EQ(first.surface(t), labelled.surfaces[t]) << t;
    EXPECT_EQ(first.highest_surface(), 3);
    EXPECT_TRUE(loaded.statics->collider(1).surfaces().empty());
    // Split into 5 m cells (bake --chunk), each triangle keeps its id: cells (0, 1), (1, 0),
    // (2, 0) hold triangles 2, 0 and 1.
    const std::vector<TriangleMesh> cells = split_into_chunks(labelled, 5.0);
    ASSERT_EQ(cells.size(), 3u);
    EXPECT_EQ(cells[0].surfaces, std::vector<SurfaceId>{1});
    EXPECT_EQ(cells[1].surfaces, std::vector<SurfaceId>{3});
    EXPECT_EQ(cells[2].surfaces, std::vector<SurfaceId>{7});
    // The generated track's walls are surface 1.
    const StaticMap track = decode_map(baked_bytes());
    EXPECT_EQ(track.statics->collider(0).highest_surface(), kWallSurface);

    // A count that is neither 0 nor the mesh triangles' is refused before it is read.
    std::string bytes = encode_map(bake_map(meshes));
    const std::size_t record = kHeaderBytes + 64;
    const std::uint64_t wrong = 2;
    std::memcpy(bytes.data() + record + offsetof(detail::MapCodec::ColliderRecord, surfaces),
                &wrong, 8);
    const std::string message = error_of([&] { decode_map(resealed(bytes)); });
    EXPECT_NE(message.find("2 surface ids for 3 mesh triangles"), std::string::npos) << message;
}

TEST(MapFile, AnotherVersionOrOtherBuildOptionsAreNamed) {
    std::string bytes = baked_bytes();
    // Version 3 hashed the colliders without their surface ids.
    static_assert(kMapFormatVersion == 4);
    for (const std::uint32_t version : {3u, 5u}) {
        std::memcpy(bytes.data() + 8, &version, 4);
        const std::string message = error_of([&] { decode_map(resealed(bytes)); });
        EXPECT_NE(message.find("format version " + std::to_string(version) +
                               ", this build reads only version 4: bake the map again"),
                  std::string::npos)
            << message;
    }

    TriangleMesh quad;
    quad.vertices = {{0, 0, 0}, {10, 0, 0}, {10, 0, 10}, {0, 0, 10}};
    quad.triangles = {{0, 2, 1}, {0, 3, 2}};
    PlaneTreeSettings other = PlaneTreeSettings::precomputed();
    other.slab_thickness = 0.3;
    const std::string other_bytes = encode_map(bake_map({&quad, 1}, other, 1));
    const std::string message = error_of([&] { decode_map(other_bytes, "map 'q'"); });
    EXPECT_NE(message.find("map 'q': its plane trees were built with other options"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("slab thickness 0.3 m"), std::string::npos) << message;
    EXPECT_EQ(decode_map(other_bytes, "q", other).plane_tree_settings.slab_thickness, 0.3);
    EXPECT_EQ(decode_map(other_bytes, "q", std::nullopt).statics->size(), 1u);
}

// baked() saved as track.tpmap in a new folder of this process's (the caller removes it).
std::filesystem::path saved_in_new_folder(const std::string& name) {
    const std::filesystem::path folder =
        std::filesystem::temp_directory_path() / (name + "-" + std::to_string(::getpid()));
    std::filesystem::create_directories(folder);
    save_map(folder / "track.tpmap", baked());
    return folder / "track.tpmap";
}

TEST(MapFile, SaveAndLoadNameTheFileAndLeaveNoPartialFile) {
    const std::filesystem::path file = saved_in_new_folder("trackphys-map-test");
    const std::filesystem::path folder = file.parent_path();
    EXPECT_EQ(load_static_world(file).statics->size(), baked().statics->size());
    EXPECT_TRUE(is_map_file(file));
    EXPECT_EQ(std::filesystem::directory_iterator(folder)->path(), file) << "a leftover file";

    const std::string missing = error_of([&] { load_static_world(folder / "none.tpmap"); });
    EXPECT_NE(missing.find("none.tpmap': no such file"), std::string::npos) << missing;
    EXPECT_NE(error_of([&] { load_static_world(folder); }).find("is a folder"), std::string::npos);
    EXPECT_NE(error_of([&] {
                  save_map(folder / "no" / "such.tpmap", baked());
              }).find("cannot write the map"),
              std::string::npos);
    EXPECT_FALSE(is_map_file(folder / "none.tpmap"));
    std::filesystem::remove_all(folder);
}

// A map rewritten in place while a game loads it (an updater cutting it short and writing
// it again): every load gives the map or an error naming the file, never a crash (a mapped
// file's pages, gone with the truncation, killed the process with SIGBUS).
TEST(MapFile, AFileRewrittenDuringTheLoadIsTheMapOrAnError) {
    const std::filesystem::path file = saved_in_new_folder("trackphys-map-race");
    std::atomic<bool> stop{false};
    std::thread writer([&] {
        const std::string& bytes = baked_bytes();
        while (!stop) {
            std::filesystem::resize_file(file, bytes.size() / 3);
            std::fstream(file, std::ios::binary | std::ios::in | std::ios::out)
                .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        }
    });
    int loaded = 0, refused = 0;
    for (int i = 0; i < 30; ++i) {
        try {
            EXPECT_EQ(load_static_world(file).statics->size(), baked().statics->size());
            ++loaded;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("track.tpmap'"), std::string::npos) << e.what();
            ++refused;
        }
    }
    stop = true;
    writer.join();
    EXPECT_EQ(loaded + refused, 30);
    std::filesystem::remove_all(file.parent_path());
}

TEST(MapFile, MeshChunksCoverTheMeshOnce) {
    TriangleMesh grid;
    for (int i = 0; i <= 20; ++i)
        for (int j = 0; j <= 20; ++j) grid.vertices.push_back({i * 10.0, 0.0, j * 10.0});
    for (std::uint32_t i = 0; i < 20; ++i)
        for (std::uint32_t j = 0; j < 20; ++j) {
            const std::uint32_t v = i * 21 + j;
            grid.triangles.push_back({v, v + 1, v + 22});
            grid.triangles.push_back({v, v + 22, v + 21});
        }
    const std::vector<TriangleMesh> chunks = split_into_chunks(grid, 50.0);
    EXPECT_EQ(chunks.size(), 16u);
    std::size_t triangles = 0;
    for (const TriangleMesh& c : chunks) {
        triangles += c.triangles.size();
        for (const auto& t : c.triangles)
            for (const std::uint32_t v : t) EXPECT_LT(v, c.vertices.size());
    }
    EXPECT_EQ(triangles, grid.triangles.size());
    EXPECT_NE(error_of([&] { split_into_chunks(grid, 0.0); }).find("chunk size"),
              std::string::npos);
}

}  // namespace
}  // namespace trackphys
