#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

namespace trackphys::cli {

/// Writes `json` (indented) to `path`, a file StagedOutputs staged (so a reader never sees
/// half a report). Throws trackphys::Error naming the file.
void write_json_file(const nlohmann::json& json, const std::filesystem::path& path);

}  // namespace trackphys::cli
