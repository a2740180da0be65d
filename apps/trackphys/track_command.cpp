#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <regex>
#include <string>
#include <system_error>

#include "commands.hpp"
#include "file_clashes.hpp"
#include "staged_outputs.hpp"
#include "track_mesh.hpp"
#include "track_svg.hpp"
#include "trackphys/error.hpp"
#include "trackphys/io/mesh_io.hpp"
#include "trackphys/track/track.hpp"
#include "trackphys/track/track_stats.hpp"

namespace trackphys::cli {
namespace {

// Writes the merged track mesh to path (format by extension).
void write_track_mesh(const Track& track, const std::filesystem::path& path) {
    save_mesh(merge_chunks(track), path);
}

void print_summary(const Track& track, double seconds) {
    const TrackStats stats = compute_track_stats(track);
    const UpdateBoxSpec box_spec;
    const CenterlineSample& tightest = track.centerline[stats.tightest_sample];
    const BoxTriangleCount in_box =
        count_triangles_in_box(track, car_update_box(tightest, box_spec));
    const TrackParams& p = track.params;
    std::printf("track        seed %llu, %d Bezier segments (%d shapes rejected first)\n",
                static_cast<unsigned long long>(p.seed),
                static_cast<int>(track.bezier_segment_count), track.rejected_shapes);
    std::printf("length       %.3f m, %.1f m wide, %zu rows\n", stats.length_m, p.width_m,
                track.centerline.size());
    std::printf("triangles    %zu (road %zu, walls %zu), %zu vertices\n", stats.triangle_count,
                stats.road_triangle_count, stats.triangle_count - stats.road_triangle_count,
                stats.vertex_count);
    std::printf("colliders    %zu chunks of ~%.0f m\n", stats.chunk_count, p.chunk_length_m);
    std::printf("bank         %.1f .. %.1f deg\n", stats.min_bank_deg, stats.max_bank_deg);
    std::printf("elevation    %.2f .. %.2f m\n", stats.min_elevation_m, stats.max_elevation_m);
    std::printf("road edges   %.3f .. %.3f m along the track\n", stats.min_road_edge_m,
                stats.max_road_edge_m);
    std::printf("tightest     radius %.1f m at %.1f m along\n", stats.min_turn_radius_m,
                tightest.distance);
    std::printf(
        "update box   %zu road + %zu wall triangles overlap a %.1f x %.1f x %.1f m car's box swept "
        "for %.0f km/h over %.0f ms, in the tightest turn\n",
        in_box.road, in_box.wall, box_spec.car_size.z, box_spec.car_size.x, box_spec.car_size.y,
        box_spec.speed_mps * 3.6, box_spec.update_dt_s * 1000.0);
    std::printf("mesh hash    %016llx\n", static_cast<unsigned long long>(stats.mesh_hash));
    std::printf("generated in %.1f ms\n", seconds * 1000.0);
}

// validate_track_params, its message naming the command's flags rather than the fields they
// set ("TrackParams.length_m must be ..." -> "--length must be ..."); a field without a flag
// keeps its name.
void check_track_flags(const TrackOptions& options) {
    try {
        validate_track_params(options.params);
    } catch (const Error& e) {
        std::string message = std::regex_replace(e.what(), std::regex("TrackParams\\."), "");
        for (const auto& [field, flag] : options.flag_of_field)
            message = std::regex_replace(message, std::regex("\\b" + field + "\\b"), flag);
        throw Error(message);
    }
}

}  // namespace

void run_track(const TrackOptions& options) {
    check_track_flags(options);
    // Check the output names before spending time on the track.
    refuse_file_clashes({}, {{"--out", options.out}, {"--svg", options.svg}});
    if (!options.out.empty() && !can_save_mesh_as(options.out))
        throw Error("--out '" + options.out.string() + "': the extension must be " +
                    saved_mesh_extensions);
    if (!options.out.empty()) check_destination(options.out, "--out");
    // The picture is staged and put in place with the mesh (save_mesh is atomic itself), so
    // a failure leaves neither (staged_outputs.hpp).
    StagedOutputs outputs;
    const std::filesystem::path svg =
        options.svg.empty() ? options.svg : outputs.stage(options.svg, "--svg");
    const auto start = std::chrono::steady_clock::now();
    const Track track = generate_track(options.params);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    print_summary(track, seconds);
    if (!svg.empty()) write_track_svg(track, svg);
    if (!options.out.empty()) write_track_mesh(track, options.out);
    try {
        outputs.commit();
    } catch (const Error&) {
        std::error_code ignored;
        if (!options.out.empty()) std::filesystem::remove(options.out, ignored);
        throw;
    }
    for (const std::filesystem::path* written : {&options.svg, &options.out})
        if (!written->empty()) std::printf("wrote        %s\n", written->string().c_str());
}

}  // namespace trackphys::cli
