// `trackphys info FILE`: what a static collider would get from a mesh file, or what a baked
// map holds (map_info.cpp).

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "json_file.hpp"
#include "map_info.hpp"
#include "mesh_reading.hpp"
#include "trackphys/collision/static_collider.hpp"
#include "trackphys/error.hpp"
#include "trackphys/io/map_file.hpp"
#include "trackphys/io/mesh_io.hpp"

namespace trackphys::cli {
namespace {

// What --surface-grips and WorldSettings::surfaces index: each surface id's material (its
// name in the file, report.materials) and how many triangles have it.
struct SurfaceInfo {
    std::string material;
    std::size_t triangles = 0;
};

std::vector<SurfaceInfo> surfaces_in(const TriangleMesh& mesh, const MeshLoadReport& r) {
    std::vector<SurfaceInfo> surfaces(std::max<std::size_t>(r.materials.size(), 1));
    for (std::size_t id = 0; id < r.materials.size(); ++id) surfaces[id].material = r.materials[id];
    if (mesh.surfaces.empty()) surfaces[0].triangles = mesh.triangles.size();
    for (const SurfaceId id : mesh.surfaces) {
        if (id >= surfaces.size()) surfaces.resize(std::size_t{id} + 1);
        ++surfaces[id].triangles;
    }
    return surfaces;
}

void print_json(const InfoOptions& options, const MeshLoadReport& r,
                const std::vector<SurfaceInfo>& surfaces) {
    nlohmann::json surface_list = nlohmann::json::array();
    for (std::size_t id = 0; id < surfaces.size(); ++id)
        surface_list.push_back({{"id", id},
                                {"material", surfaces[id].material},
                                {"triangles", surfaces[id].triangles}});
    const nlohmann::json out = {
        {"file", options.file},
        {"triangles", r.triangles},
        {"vertices", r.vertices},
        {"mesh_instances", r.mesh_instances},
        {"bounds",
         {{"min", json_of(r.bounds.min)},
          {"max", json_of(r.bounds.max)},
          {"size", json_of(r.bounds.extent())}}},
        {"area_m2", r.area},
        {"degenerate_dropped", r.degenerate_dropped},
        {"duplicates_dropped", r.duplicates_dropped},
        {"points_skipped", r.points_skipped},
        {"lines_skipped", r.lines_skipped},
        {"triangulation_lost", r.triangulation_lost},
        {"mirrored_instances", r.mirrored_instances},
        {"surfaces", surface_list},
    };
    std::printf("%s\n", report_text(out).c_str());
}

void print_vector(const char* label, const glm::dvec3& v) {
    std::printf("%-20s %.6f %.6f %.6f m\n", label, v.x, v.y, v.z);
}

void print_text(const InfoOptions& options, const MeshLoadReport& r,
                const std::vector<SurfaceInfo>& surfaces) {
    std::printf("%-20s %s\n", "file", options.file.c_str());
    std::printf("%-20s %zu\n", "triangles", r.triangles);
    std::printf("%-20s %zu\n", "vertices", r.vertices);
    std::printf("%-20s %zu\n", "mesh instances", r.mesh_instances);
    print_vector("bounds min", r.bounds.min);
    print_vector("bounds max", r.bounds.max);
    print_vector("size", r.bounds.extent());
    std::printf("%-20s %.3f m^2\n", "area", r.area);
    std::printf("%-20s %zu\n", "degenerate dropped", r.degenerate_dropped);
    std::printf("%-20s %zu\n", "duplicates dropped", r.duplicates_dropped);
    std::printf("%-20s %zu\n", "points skipped", r.points_skipped);
    std::printf("%-20s %zu\n", "lines skipped", r.lines_skipped);
    std::printf("%-20s %zu\n", "triangulation lost", r.triangulation_lost);
    std::printf("%-20s %zu\n", "mirrored instances", r.mirrored_instances);
    for (std::size_t id = 0; id < surfaces.size(); ++id)
        // Quoted as messages quote a file's text: a material name is the file's to choose,
        // escape sequences that would drive the terminal included.
        std::printf("%-20s %zu: %zu triangles, material %s\n", id == 0 ? "surfaces" : "", id,
                    surfaces[id].triangles, quoted_text(surfaces[id].material).c_str());
}

}  // namespace

void run_info(const InfoOptions& options) {
    // A file named .tpmap is read as a map, so one without the magic is called a bad map,
    // not a mesh format trackphys does not read.
    if (is_map_file(options.file) || std::filesystem::path(options.file).extension() == ".tpmap")
        return print_map_info(options.file, options.json);
    MeshLoadReport report;
    // Throws trackphys::Error on bad input: main reports it.
    const TriangleMesh mesh = read_mesh(options.file, report, options.mesh_limits);
    // A mesh every loader reads can still be one no collider takes (a coordinate beyond its
    // limit): bake and drive --mesh would refuse it, so info does too.
    try {
        StaticCollider::check(mesh);
    } catch (const Error& e) {
        throw Error("mesh file '" + options.file + "': a static collider refuses it: " + e.what());
    }
    const std::vector<SurfaceInfo> surfaces = surfaces_in(mesh, report);
    if (options.json)
        print_json(options, report, surfaces);
    else
        print_text(options, report, surfaces);
}

}  // namespace trackphys::cli
