#include "json_file.hpp"

#include <fstream>
#include <string>
#include <system_error>

#include "trackphys/error.hpp"

namespace trackphys::cli {

void write_json_file(const nlohmann::json& json, const std::filesystem::path& path) {
    const std::filesystem::path temporary = path.string() + ".partial";
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out) throw Error("cannot open '" + temporary.string() + "' to write the JSON report");
        out << json.dump(2) << '\n';
        if (!out.flush()) throw Error("cannot write the JSON report '" + temporary.string() + "'");
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error) {
        std::filesystem::remove(temporary, error);
        throw Error("cannot move the JSON report into place at '" + path.string() + "'");
    }
}

}  // namespace trackphys::cli
