// libFuzzer target: map loading, bytes -> decode_map -> queries on what loaded.
//
// Each input is tried twice: as it is, which exercises the header checks (magic, version,
// length, checksum), and re-sealed (its checksum rewritten to match), which lets mutations
// reach the body: the records, the arrays and the structure checks of map_check.cpp.
//
// Every input must be rejected with trackphys::Error or load; a loaded map must answer box,
// ray, sphere and swept-ellipsoid queries in bounds and in finite time. Any other exception,
// crash, sanitizer report or hang is a finding. The seeds are the maps of tests/data's flat
// ground (`trackphys bake tests/data/flat_ground.obj --out flat_ground.tpmap`) and of its
// two_surfaces.obj, whose two materials give the colliders surface ids (baked from inside
// tests/data, which holds its .mtl); after a format change, bake them again.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "io/map_body.hpp"
#include "trackphys/error.hpp"
#include "trackphys/geometry/ellipsoid.hpp"
#include "trackphys/io/map_file.hpp"

namespace {

constexpr std::size_t kChecksumAt = 24;

// The same bytes with the header's checksum made to match them.
std::string resealed(std::string bytes) {
    std::memset(bytes.data() + kChecksumAt, 0, 8);
    trackphys::map_detail::MapChecksum checksum;
    checksum.add(bytes.data(), bytes.size() / 8 * 8);
    const std::uint64_t value = checksum.value();
    std::memcpy(bytes.data() + kChecksumAt, &value, 8);
    return bytes;
}

void query(const trackphys::StaticMap& map) {
    std::vector<trackphys::TriangleRef> refs;
    std::vector<std::uint32_t> slots;
    const glm::dvec3 points[] = {{0.0, 0.0, 0.0}, {10.0, 1.0, -10.0}, {-40.0, 0.5, 30.0}};
    for (const glm::dvec3& p : points) {
        map.statics->query_aabb(trackphys::Aabb{p - 5.0, p + 5.0}, refs);
        map.statics->query_aabb(trackphys::Aabb{p - 1e6, p + 1e6}, refs);
        (void)map.statics->raycast(p + glm::dvec3(0.0, 3.0, 0.0), {0.0, -1.0, 0.0}, 100.0);
        (void)map.statics->raycast(p, glm::normalize(glm::dvec3(1.0, -0.2, 0.3)), 1e9);
        for (const auto& tree : map.plane_trees) {
            const trackphys::Aabb box{p - 3.0, p + 3.0};
            tree->query_sphere(p, 2.0, slots, tree->entry_node(box));
            const trackphys::Ellipsoid body(p, glm::dquat(1.0, 0.0, 0.0, 0.0), {0.9, 0.4, 2.1});
            tree->query_swept_ellipsoid(body, p + glm::dvec3(0.0, 0.0, 1.0), 0.05, slots);
            for (const std::uint32_t s : slots) (void)tree->id(s);
            slots.clear();
        }
    }
}

void try_map(std::string_view bytes) {
    trackphys::StaticMap map;
    try {
        map = trackphys::decode_map(bytes, "fuzz", std::nullopt, 1);
    } catch (const trackphys::Error&) {
        return;
    }
    query(map);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    try_map(bytes);
    if (size >= 64) try_map(resealed(std::string(bytes)));
    return 0;
}
