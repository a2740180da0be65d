#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "commands.hpp"
#include "file_clashes.hpp"
#include "replay_page.hpp"
#include "staged_outputs.hpp"
#include "trackphys/error.hpp"
#include "viewer_bundle.hpp"

namespace trackphys::cli {

void run_view(const ViewOptions& o) {
    const std::string_view bundle = viewer_bundle();
    if (bundle.empty())
        throw Error(
            "this trackphys was built without the replay viewer: install Node.js and "
            "npm, run scripts/setup.sh (it runs npm ci in viewer/) and build again "
            "with -DTRACKPHYS_BUILD_VIEWER=ON");
    const auto start = std::chrono::steady_clock::now();
    const ReplayRecording recording = read_replay_recording(o.recording);
    refuse_file_clashes(
        {{"RECORDING", o.recording}, {"the recording's track", recording.track_file}},
        {{"--out", o.out}});
    StagedOutputs outputs;
    const std::filesystem::path staged = outputs.stage(o.out, "--out");
    ReplayPageStats stats;
    const std::string page = make_replay_page(recording, bundle, o.mesh_limits, stats);
    std::ofstream out(staged, std::ios::binary);
    out.write(page.data(), static_cast<std::streamsize>(page.size()));
    if (!out.flush()) throw Error("--out '" + o.out.string() + "': cannot write the page");
    out.close();
    outputs.commit();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("recording    %s, %.1f MB\n", o.recording.string().c_str(),
                static_cast<double>(stats.recording_bytes) / 1e6);
    std::printf("track        %zu triangles\n", stats.track_triangles);
    std::printf("wrote        %s, %.1f MB (viewer %.0f kB) in %.2f s\n", o.out.string().c_str(),
                static_cast<double>(stats.page_bytes) / 1e6,
                static_cast<double>(bundle.size()) / 1e3, seconds);
}

}  // namespace trackphys::cli
