#include "replay_page.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <system_error>
#include <vector>

#include <zlib.h>

#include "mesh_reading.hpp"
#include "recording_lines.hpp"
#include "trackphys/error.hpp"
#include "trackphys/geometry/triangle_mesh.hpp"
#include "trackphys/io/regular_file.hpp"

namespace trackphys::cli {
namespace {

// The longest string Chromium holds (2^29 - 24 UTF-16 units): the page decodes a longer
// recording to an empty text, without a word.
constexpr std::uintmax_t max_page_recording_bytes = 536'870'888;

std::string read_recording(const std::filesystem::path& path) {
    require_regular_file(path, "recording '" + path.string() + "'");
    std::error_code error;
    const std::uintmax_t size = std::filesystem::file_size(path, error);
    if (!error && size > max_page_recording_bytes)
        throw Error("recording '" + path.string() + "': " + std::to_string(size >> 20) +
                    " MiB is more than a browser holds as text (512 MiB): record fewer cars, "
                    "laps or seconds");
    std::ifstream in(path, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw Error("recording '" + path.string() + "': cannot read it");
    return text;
}

std::string deflate(std::string_view bytes) {
    uLongf size = compressBound(static_cast<uLong>(bytes.size()));
    std::string out(size, '\0');
    const int status = compress2(reinterpret_cast<Bytef*>(out.data()), &size,
                                 reinterpret_cast<const Bytef*>(bytes.data()),
                                 static_cast<uLong>(bytes.size()), Z_DEFAULT_COMPRESSION);
    if (status != Z_OK)
        throw Error("cannot compress the replay's data (zlib " + std::to_string(status) + ")");
    out.resize(size);
    return out;
}

std::string base64(std::string_view bytes) {
    static constexpr char kAlphabet[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
        std::uint32_t word = 0;
        for (std::size_t k = 0; k < 3; ++k)
            word = (word << 8) | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
        for (std::size_t k = 0; k < 4; ++k)
            out += k <= n ? kAlphabet[(word >> (18 - 6 * k)) & 63] : '=';
    }
    return out;
}

// The track as the viewer reads it: every vertex coordinate in whole millimetres minus the
// previous vertex's, then every triangle index minus the previous index, all int32
// little-endian (docs/viewer.md, "The page"). Neighbouring vertices and indices are close,
// so the differences are small numbers that deflate well: 0.7 MB for the default track,
// against 2.4 MB as float32 and uint32. A millimetre is far below a pixel.
std::string pack_track(const TriangleMesh& mesh, const std::filesystem::path& file) {
    std::vector<std::int32_t> values;
    values.reserve(mesh.vertices.size() * 3 + mesh.triangles.size() * 3);
    std::array<std::int64_t, 3> previous{};
    for (const glm::dvec3& v : mesh.vertices) {
        for (int k = 0; k < 3; ++k) {
            const double mm = std::round(v[k] * 1000.0);
            // Within 1,000 km, so that a difference of two fits in int32 too.
            if (!(std::abs(mm) < 1.0e9))
                throw Error("track '" + file.string() +
                            "': a vertex is more than 1,000 km from the origin, beyond what "
                            "the viewer shows");
            const auto whole = static_cast<std::int64_t>(mm);
            values.push_back(static_cast<std::int32_t>(whole - previous[k]));
            previous[k] = whole;
        }
    }
    // Modulo 2^32, as the viewer adds them up again.
    std::uint32_t previous_index = 0;
    for (const auto& t : mesh.triangles) {
        for (const std::uint32_t index : t) {
            values.push_back(static_cast<std::int32_t>(index - previous_index));
            previous_index = index;
        }
    }
    std::string out(values.size() * sizeof(std::int32_t), '\0');
    std::memcpy(out.data(), values.data(), out.size());
    return out;
}

// Text inside <script> ends at "</script" and an attribute at '"': neither may occur.
std::string attribute(std::string text) {
    std::string out;
    for (char c : text) {
        if (c == '&')
            out += "&amp;";
        else if (c == '"')
            out += "&quot;";
        else if (c == '<')
            out += "&lt;";
        else
            out += c;
    }
    return out;
}

}  // namespace

ReplayRecording read_replay_recording(const std::filesystem::path& file) {
    ReplayRecording recording{file, read_recording(file), {}};
    const RecordingLines lines = check_recording_lines(recording.text, file);
    if (lines.track_mesh) {
        const std::filesystem::path track = *lines.track_mesh;
        if (track.empty() || track != track.filename() || track == "." || track == "..")
            throw Error("recording '" + file.string() + "': its track " +
                        quoted_text(track.string()) +
                        " is not a plain file name in the recording's folder (a recording "
                        "names the track drive --record wrote beside it)");
        const std::filesystem::path folder =
            file.parent_path().empty() ? std::filesystem::path(".") : file.parent_path();
        recording.track_file = folder / track;
        std::error_code error;
        if (std::filesystem::exists(recording.track_file, error) &&
            !lies_inside(recording.track_file, folder))
            throw Error("recording '" + file.string() + "': its track " +
                        quoted_text(track.string()) +
                        " leads out of the recording's folder through a symbolic link");
    }
    return recording;
}

std::string make_replay_page(const ReplayRecording& recording, std::string_view bundle,
                             const MeshLoadLimits& mesh_limits, ReplayPageStats& stats) {
    const std::string& text = recording.text;
    stats.recording_bytes = text.size();
    const std::string name = attribute(recording.file.filename().string());

    std::string track;
    if (!recording.track_file.empty()) {
        TriangleMesh mesh;
        try {
            mesh = read_mesh(recording.track_file, mesh_limits);
        } catch (const Error& e) {
            throw Error("recording '" + recording.file.string() + "': its track: " + e.what());
        }
        stats.track_triangles = mesh.triangles.size();
        track =
            "<script type=\"application/x-trackphys-track\" id=\"trackphys-track\" "
            "data-vertices=\"" +
            std::to_string(mesh.vertices.size()) + "\" data-triangles=\"" +
            std::to_string(mesh.triangles.size()) + "\">" +
            base64(deflate(pack_track(mesh, recording.track_file))) + "</script>\n";
    }

    std::string page =
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
        "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
        // Nothing on the page may reach the network: it works offline or not at all.
        "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; "
        "script-src 'unsafe-inline'; style-src 'unsafe-inline'; img-src data: blob:\">\n"
        "<title>trackphys replay: " +
        name + "</title>\n</head>\n<body>\n";
    page +=
        "<script type=\"application/x-trackphys-recording\" id=\"trackphys-recording\" "
        "data-name=\"" +
        name + "\">" + base64(deflate(text)) + "</script>\n";
    page += track;
    page += "<script>";
    page += bundle;
    page += "</script>\n</body>\n</html>\n";
    stats.page_bytes = page.size();
    return page;
}

}  // namespace trackphys::cli
