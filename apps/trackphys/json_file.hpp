#pragma once

#include <filesystem>
#include <string>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

namespace trackphys {
class TraceRecorder;
}

namespace trackphys::cli {

/// A point or vector as the reports write it: [x, y, z].
inline nlohmann::json json_of(const glm::dvec3& v) {
    return nlohmann::json::array({v.x, v.y, v.z});
}

/// `json` as the reports print it: indented, and with bytes that are not UTF-8 (a file or
/// material name in another encoding) replaced by U+FFFD, where nlohmann::json's dump would
/// throw after the whole drive or race had run.
std::string report_text(const nlohmann::json& json);

/// Writes report_text(json) to `path`, a file StagedOutputs staged (so a reader never sees
/// half a report). Throws trackphys::Error naming the file.
void write_json_file(const nlohmann::json& json, const std::filesystem::path& path);

/// Writes `trace` as a Chrome trace to `staged`, the file StagedOutputs staged for the
/// `--trace` option the user named `named`. Throws trackphys::Error naming `named`.
void write_trace_file(const TraceRecorder& trace, const std::filesystem::path& staged,
                      const std::filesystem::path& named);

}  // namespace trackphys::cli
