#include "json_file.hpp"

#include <fstream>

#include "trackphys/error.hpp"
#include "trackphys/profile/trace_recorder.hpp"

namespace trackphys::cli {

std::string report_text(const nlohmann::json& json) {
    return json.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
}

void write_json_file(const nlohmann::json& json, const std::filesystem::path& path) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) throw Error("cannot open '" + path.string() + "' to write the JSON report");
    out << report_text(json) << '\n';
    if (!out.flush()) throw Error("cannot write the JSON report '" + path.string() + "'");
}

void write_trace_file(const TraceRecorder& trace, const std::filesystem::path& staged,
                      const std::filesystem::path& named) {
    std::ofstream out(staged, std::ios::binary);
    trace.write_chrome_trace(out);
    if (!out.flush()) throw Error("--trace '" + named.string() + "': cannot write the trace");
}

}  // namespace trackphys::cli
