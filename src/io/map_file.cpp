// Map files (layout in docs/tpmap.md): the header and the track here, the colliders in
// map_codec.cpp, their checks in map_check.cpp.

#include "trackphys/io/map_file.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <system_error>

#include "core/parallel_items.hpp"
#include "file_bytes.hpp"
#include "map_body.hpp"
#include "map_codec.hpp"
#include "trackphys/error.hpp"
#include "trackphys/io/regular_file.hpp"

namespace trackphys {
namespace {

using map_detail::BodyReader;
using map_detail::BodyWriter;
using map_detail::MapChecksum;

constexpr char kMagic[8] = {'T', 'P', 'M', 'A', 'P', '\0', '\x1a', '\n'};

// 64 bytes: the file's first line of defence, and the plane trees' build options.
struct Header {
    char magic[8];
    std::uint32_t version;
    std::uint32_t header_bytes;
    std::uint64_t body_bytes;
    std::uint64_t checksum;  ///< MapChecksum of the header (this field 0) and the body
    std::uint32_t split_rule;
    std::uint32_t max_leaf_size;
    double query_radius;
    double node_cost;
    double slab_thickness;
};
static_assert(sizeof(Header) == 64);
static_assert(offsetof(Header, checksum) == 24, "docs/tpmap.md places the checksum at byte 24");

// The body's first record. 64 bytes.
struct MapRecord {
    std::uint64_t colliders;
    std::uint64_t centerline_samples;  ///< 0: no track
    double track_length_m;
    std::uint64_t bezier_segments;
    std::int64_t rejected_shapes;
    std::uint64_t reserved[3];
};
static_assert(sizeof(MapRecord) == 64);

// TrackParams, every field 8 bytes. 112 bytes.
struct TrackParamsRecord {
    std::uint64_t seed;
    double length_m, width_m, max_bank_deg, full_bank_radius_m, elevation_amplitude_m,
        wall_height_m, wall_thickness_m, min_turn_radius_m, edge_tight_m, edge_straight_m,
        tight_radius_m;
    std::int64_t strips;
    double chunk_length_m;
};
static_assert(sizeof(TrackParamsRecord) == 112);
static_assert(sizeof(CenterlineSample) == 120, "a centreline sample is stored as its bytes");

TrackParamsRecord to_record(const TrackParams& p) {
    return {p.seed,          p.length_m,           p.width_m,
            p.max_bank_deg,  p.full_bank_radius_m, p.elevation_amplitude_m,
            p.wall_height_m, p.wall_thickness_m,   p.min_turn_radius_m,
            p.edge_tight_m,  p.edge_straight_m,    p.tight_radius_m,
            p.strips,        p.chunk_length_m};
}

TrackParams from_record(const TrackParamsRecord& r) {
    TrackParams p;
    p.seed = r.seed;
    p.length_m = r.length_m;
    p.width_m = r.width_m;
    p.max_bank_deg = r.max_bank_deg;
    p.full_bank_radius_m = r.full_bank_radius_m;
    p.elevation_amplitude_m = r.elevation_amplitude_m;
    p.wall_height_m = r.wall_height_m;
    p.wall_thickness_m = r.wall_thickness_m;
    p.min_turn_radius_m = r.min_turn_radius_m;
    p.edge_tight_m = r.edge_tight_m;
    p.edge_straight_m = r.edge_straight_m;
    p.tight_radius_m = r.tight_radius_m;
    if (r.strips < 1 || r.strips > 1'000'000)
        throw Error("track strips " + std::to_string(r.strips) + " out of range");
    p.strips = static_cast<int>(r.strips);
    p.chunk_length_m = r.chunk_length_m;
    return p;
}

std::string describe(const PlaneTreeSettings& s) {
    std::ostringstream out;
    out << "rule " << (s.rule == PlaneSplitRule::cost_based ? "cost_based" : "pca_median")
        << ", max leaf size " << s.max_leaf_size << ", query radius " << s.query_radius
        << " m, node cost " << s.node_cost << ", slab thickness " << s.slab_thickness << " m";
    return out.str();
}

bool same_settings(const PlaneTreeSettings& a, const PlaneTreeSettings& b) {
    return a.rule == b.rule && a.max_leaf_size == b.max_leaf_size &&
           std::bit_cast<std::uint64_t>(a.query_radius) ==
               std::bit_cast<std::uint64_t>(b.query_radius) &&
           std::bit_cast<std::uint64_t>(a.node_cost) == std::bit_cast<std::uint64_t>(b.node_cost) &&
           std::bit_cast<std::uint64_t>(a.slab_thickness) ==
               std::bit_cast<std::uint64_t>(b.slab_thickness);
}

PlaneTreeSettings read_settings(const Header& h) {
    if (h.split_rule > static_cast<std::uint32_t>(PlaneSplitRule::cost_based))
        throw Error("the header's plane-tree split rule " + std::to_string(h.split_rule) +
                    " is not a rule");
    PlaneTreeSettings s;
    s.rule = static_cast<PlaneSplitRule>(h.split_rule);
    s.max_leaf_size = static_cast<int>(std::min<std::uint32_t>(h.max_leaf_size, 1u << 30));
    s.query_radius = h.query_radius;
    s.node_cost = h.node_cost;
    s.slab_thickness = h.slab_thickness;
    // Checked here too: a map read without expected settings hands them to the caller.
    if (std::string why = s.validate(); !why.empty())
        throw Error("the header's plane-tree settings: " + why);
    return s;
}

bool is_unit(const glm::dvec3& v) {
    const double length2 = v.x * v.x + v.y * v.y + v.z * v.z;
    return std::abs(length2 - 1.0) <= 1e-6;
}

// What the autopilot and the start line rely on: finite samples with unit frames, in
// order of distance from 0 to below the track's length.
void check_centerline(const Track& t) {
    if (!(std::isfinite(t.length_m) && t.length_m > 0.0))
        throw Error("track length " + std::to_string(t.length_m) + " m is not positive");
    if (t.centerline.size() < 3) throw Error("a track centreline needs 3 samples at least");
    double previous = -1.0;
    for (std::size_t i = 0; i < t.centerline.size(); ++i) {
        const CenterlineSample& s = t.centerline[i];
        const bool finite = std::isfinite(s.curvature) && std::isfinite(s.bank) &&
                            std::isfinite(s.position.x) && std::isfinite(s.position.y) &&
                            std::isfinite(s.position.z);
        if (!finite || !is_unit(s.tangent) || !is_unit(s.up) || !is_unit(s.left))
            throw Error("centreline sample " + std::to_string(i) +
                        " is not finite or its frame is not unit");
        const bool ordered = i == 0 ? s.distance == 0.0 : s.distance > previous;
        if (!ordered || !(s.distance < t.length_m))
            throw Error("centreline sample " + std::to_string(i) + " at " +
                        std::to_string(s.distance) + " m is out of order");
        previous = s.distance;
    }
}

void write_track(BodyWriter& body, MapRecord& record, const Track& track) {
    record.centerline_samples = track.centerline.size();
    record.track_length_m = track.length_m;
    record.bezier_segments = track.bezier_segment_count;
    record.rejected_shapes = track.rejected_shapes;
    body.record(record);
    body.record(to_record(track.params));
    body.array(track.centerline);
}

Track read_track(BodyReader& body, const MapRecord& record) {
    Track track;
    track.params = from_record(body.record<TrackParamsRecord>("track parameters"));
    validate_track_params(track.params);
    track.length_m = record.track_length_m;
    track.bezier_segment_count = record.bezier_segments;
    track.rejected_shapes = static_cast<int>(
        std::clamp<std::int64_t>(record.rejected_shapes, 0, std::numeric_limits<int>::max()));
    body.array(track.centerline, record.centerline_samples, "centreline");
    check_centerline(track);
    return track;
}

Header make_header(const PlaneTreeSettings& s, std::uint64_t body_bytes) {
    Header h{};
    std::memcpy(h.magic, kMagic, sizeof kMagic);
    h.version = kMapFormatVersion;
    h.header_bytes = sizeof(Header);
    h.body_bytes = body_bytes;
    h.split_rule = static_cast<std::uint32_t>(s.rule);
    h.max_leaf_size = static_cast<std::uint32_t>(s.max_leaf_size);
    h.query_radius = s.query_radius;
    h.node_cost = s.node_cost;
    h.slab_thickness = s.slab_thickness;
    return h;
}

void check_host() {
    if constexpr (std::endian::native != std::endian::little)
        throw Error("map files are little-endian; this host is not");
}

// Writes the whole file to `out`: the header, its checksum computed first over the arrays
// in place.
void write_map(std::ostream& out, const StaticMap& map) {
    check_host();
    if (!map.statics) throw Error("map: no static world");
    const StaticWorld& world = *map.statics;
    if (map.plane_trees.size() != world.size())
        throw Error("map: " + std::to_string(map.plane_trees.size()) + " plane trees for " +
                    std::to_string(world.size()) + " colliders");
    BodyWriter body;
    MapRecord record{};
    record.colliders = world.size();
    if (map.track)
        write_track(body, record, *map.track);
    else
        body.record(record);
    for (std::uint32_t id = 0; id < world.size(); ++id) {
        if (!map.plane_trees[id])
            throw Error("map: collider " + std::to_string(id) + " has no plane tree");
        detail::MapCodec::write(body, world.collider(id), *map.plane_trees[id]);
    }
    Header header = make_header(map.plane_tree_settings, body.size());
    MapChecksum checksum;
    checksum.add(&header, sizeof header);
    body.add_to(checksum);
    header.checksum = checksum.value();
    out.write(reinterpret_cast<const char*>(&header), sizeof header);
    body.write_to(out);
}

StaticMap decode_checked(std::string_view bytes, const std::optional<PlaneTreeSettings>& expected,
                         unsigned threads, std::size_t frame_budget_bytes) {
    check_host();
    if (bytes.size() >= sizeof kMagic && std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
        throw Error("wrong magic (not a trackphys map file)");
    if (bytes.size() < sizeof(Header))
        throw Error(std::to_string(bytes.size()) +
                    " bytes, shorter than the 64-byte header "
                    "(truncated or not a map)");
    Header h;
    std::memcpy(&h, bytes.data(), sizeof h);
    if (h.version != kMapFormatVersion)
        throw Error("format version " + std::to_string(h.version) + ", this build reads only " +
                    "version " + std::to_string(kMapFormatVersion) +
                    ": bake the map again with this build");
    if (h.header_bytes != sizeof(Header))
        throw Error("the header claims " + std::to_string(h.header_bytes) + " bytes, not " +
                    std::to_string(sizeof(Header)));
    const std::uint64_t available = bytes.size() - sizeof(Header);
    if (h.body_bytes > available)
        throw Error("truncated: the header announces " + std::to_string(h.body_bytes) +
                    " body bytes, the file has " + std::to_string(available));
    if (h.body_bytes < available)
        throw Error(std::to_string(available - h.body_bytes) +
                    " bytes of trailing garbage after the body");
    if (h.body_bytes % map_detail::kMapAlignment != 0)
        throw Error("the body's " + std::to_string(h.body_bytes) +
                    " bytes are not a whole number of 64-byte blocks");
    const std::string_view body_bytes = bytes.substr(sizeof(Header));
    // The checksum runs beside the colliders' reading (a tenth of a large map's load), so the
    // body is read before it is known to be intact: every read is bounds-checked and every
    // structure verified (a file altered and sealed again is refused cleanly, see map_codec),
    // and a corrupted file still reports its checksum first, whatever else broke.
    const auto verify_checksum = [&] {
        Header unsealed = h;
        unsealed.checksum = 0;
        MapChecksum checksum;
        checksum.add(&unsealed, sizeof unsealed);
        checksum.add(body_bytes.data(), body_bytes.size());
        if (checksum.value() != h.checksum)
            throw Error("checksum mismatch (the file is corrupted)");
    };

    StaticMap map;
    const auto in_collider = [](std::size_t id, const Error& e) {
        return Error("collider " + std::to_string(id) + ": " + e.what());
    };
    std::vector<detail::MapCodec::ColliderBytes> colliders;
    PlaneTreeFrames frames{};
    try {
        map.plane_tree_settings = read_settings(h);
        if (expected && !same_settings(*expected, map.plane_tree_settings))
            throw Error("its plane trees were built with other options (" +
                        describe(map.plane_tree_settings) + ") than this world needs (" +
                        describe(*expected) + "): bake the map again with this build");

        BodyReader body(body_bytes);
        const auto record = body.record<MapRecord>("map record");
        for (const std::uint64_t r : record.reserved)
            if (r != 0) throw Error("a reserved field of the map record is not 0");
        if (record.colliders > std::numeric_limits<std::uint32_t>::max())
            throw Error(std::to_string(record.colliders) + " colliders, more than a world holds");
        if (record.centerline_samples != 0) map.track = read_track(body, record);
        for (std::uint64_t id = 0; id < record.colliders; ++id) {
            try {
                colliders.push_back(detail::MapCodec::locate(body));
            } catch (const Error& e) {
                throw in_collider(id, e);
            }
        }
        if (body.left() != 0)
            throw Error(std::to_string(body.left()) + " unread bytes at the end of the body");
        std::uint64_t triangles = 0;
        for (const detail::MapCodec::ColliderBytes& c : colliders) triangles += c.record.slots;
        frames = plane_tree_frames_within(triangles, frame_budget_bytes);
    } catch (const Error&) {
        verify_checksum();
        throw;
    }

    // Copying and verifying are most of a load, and each collider's are independent. Item 0
    // is the checksum, so that its error is the one reported (the first item's).
    std::vector<detail::MapCodec::Loaded> loaded(colliders.size());
    detail::run_items_in_parallel(colliders.size() + 1, threads, [&](std::size_t item) {
        if (item == 0) return verify_checksum();
        const std::size_t id = item - 1;
        try {
            loaded[id] = detail::MapCodec::read(colliders[id], frames);
        } catch (const Error& e) {
            throw in_collider(id, e);
        }
    });
    auto world = std::make_shared<StaticWorld>();
    for (detail::MapCodec::Loaded& l : loaded) {
        world->add(std::move(l.collider));
        map.plane_trees.push_back(std::move(l.tree));
    }
    map.statics = std::move(world);
    return map;
}

}  // namespace

std::string encode_map(const StaticMap& map) {
    std::ostringstream out(std::ios::binary);
    write_map(out, map);
    return std::move(out).str();
}

StaticMap decode_map(std::string_view bytes, const std::string& source,
                     const std::optional<PlaneTreeSettings>& expected, unsigned threads,
                     std::size_t frame_budget_bytes) {
    try {
        return decode_checked(bytes, expected, threads, frame_budget_bytes);
    } catch (const Error& e) {
        throw Error(source + ": " + e.what());
    }
}

void save_map(const std::filesystem::path& path, const StaticMap& map) {
    const std::filesystem::path temporary = path.string() + ".partial";
    std::error_code ignored;
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out)
            throw Error("cannot write the map '" + path.string() + "': cannot create '" +
                        temporary.string() + "'");
        try {
            write_map(out, map);
        } catch (...) {
            out.close();
            std::filesystem::remove(temporary, ignored);
            throw;
        }
        if (!out.flush()) {
            out.close();
            std::filesystem::remove(temporary, ignored);
            throw Error("cannot write the map '" + temporary.string() + "'");
        }
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error) {
        std::filesystem::remove(temporary, ignored);
        throw Error("cannot move the map into place at '" + path.string() +
                    "': " + error.message());
    }
}

StaticMap load_static_world(const std::filesystem::path& path,
                            const std::optional<PlaneTreeSettings>& expected, unsigned threads,
                            std::size_t frame_budget_bytes) {
    const std::string source = "map '" + path.string() + "'";
    require_regular_file(path, source);
    const detail::FileBytes file(path, "map");
    return decode_map(file.bytes(), source, expected, threads, frame_budget_bytes);
}

bool is_map_file(const std::filesystem::path& path) {
    // Opening a FIFO would block until someone writes to it.
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) return false;
    std::ifstream in(path, std::ios::binary);
    char magic[sizeof kMagic] = {};
    return in.read(magic, sizeof magic) && std::memcmp(magic, kMagic, sizeof kMagic) == 0;
}

}  // namespace trackphys
