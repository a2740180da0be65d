#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "file_clashes.hpp"
#include "mesh_limit_options.hpp"
#include "replay_page.hpp"
#include "staged_outputs.hpp"
#include "trackphys/error.hpp"
#include "viewer_bundle.hpp"

namespace trackphys::cli {
namespace {

struct ViewOptions {
    std::filesystem::path recording;
    std::filesystem::path out;
    MeshLoadLimits mesh_limits;
};

void run(const ViewOptions& o) {
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

}  // namespace

void add_view_command(CLI::App& app) {
    auto o = std::make_shared<ViewOptions>();
    CLI::App* command = app.add_subcommand(
        "view",
        "Write a self-contained HTML page that replays a recording (drive --record) in a 3D "
        "viewer: open it in a browser, no server or network needed");
    command->add_option("RECORDING", o->recording, "The recording (JSON Lines)")->required();
    command->add_option("--out", o->out, "The page to write (.html)")->required();
    add_mesh_limit_options(*command, o->mesh_limits);
    command->callback([o] { run(*o); });
}

}  // namespace trackphys::cli
