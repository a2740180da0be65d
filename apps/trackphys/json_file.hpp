#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

namespace trackphys::cli {

/// Writes `json` (indented) to `path` atomically: into path + ".partial", then renamed over
/// path, so a reader never sees half a report. Throws trackphys::Error naming the file.
void write_json_file(const nlohmann::json& json, const std::filesystem::path& path);

}  // namespace trackphys::cli
