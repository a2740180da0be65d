#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

namespace trackphys {
class TraceRecorder;
}

namespace trackphys::cli {

/// Writes `json` (indented) to `path`, a file StagedOutputs staged (so a reader never sees
/// half a report). Throws trackphys::Error naming the file.
void write_json_file(const nlohmann::json& json, const std::filesystem::path& path);

/// Writes `trace` as a Chrome trace to `staged`, the file StagedOutputs staged for the
/// `--trace` option the user named `named`. Throws trackphys::Error naming `named`.
void write_trace_file(const TraceRecorder& trace, const std::filesystem::path& staged,
                      const std::filesystem::path& named);

}  // namespace trackphys::cli
