#include "trackphys/io/recording.hpp"

#include <cinttypes>
#include <cstdio>
#include <system_error>

#include "trackphys/error.hpp"

namespace trackphys {
namespace {

// %.17g keeps every bit of a double, so a replay sees exactly the simulated values.
void put(std::ofstream& out, double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", x);
    out << text;
}

void put(std::ofstream& out, const glm::dvec3& v) {
    out << '[';
    put(out, v.x), out << ',', put(out, v.y), out << ',', put(out, v.z);
    out << ']';
}

}  // namespace

RecordingWriter::RecordingWriter(const std::filesystem::path& path, double dt, std::size_t cars,
                                 const std::string& scene)
    : path_(path), temporary_(path.string() + ".partial") {
    out_.open(temporary_, std::ios::binary | std::ios::trunc);
    if (!out_) throw Error("cannot open '" + temporary_.string() + "' to write the recording");
    out_ << "{\"format\":\"trackphys-recording\",\"version\":1,\"dt\":";
    put(out_, dt);
    out_ << ",\"cars\":" << cars << ",\"scene\":\"";
    for (char c : scene) {  // a JSON string: escape quotes, backslashes and controls
        if (c == '"' || c == '\\')
            out_ << '\\' << c;
        else if (static_cast<unsigned char>(c) < 0x20)
            out_ << ' ';
        else
            out_ << c;
    }
    out_ << "\"}\n";
}

RecordingWriter::~RecordingWriter() {
    if (finished_) return;
    out_.close();
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
}

void RecordingWriter::begin_frame(double t, std::uint64_t state_hash) {
    char hash[17];
    std::snprintf(hash, sizeof hash, "%016" PRIx64, state_hash);
    out_ << "{\"t\":";
    put(out_, t);
    out_ << ",\"hash\":\"" << hash << "\",\"cars\":[";
    first_car_ = true;
}

void RecordingWriter::add_car(const glm::dvec3& position, const glm::dquat& orientation,
                              double speed, std::span<const Contact> contacts) {
    out_ << (first_car_ ? "" : ",") << "{\"p\":";
    first_car_ = false;
    put(out_, position);
    out_ << ",\"q\":[";
    put(out_, orientation.w), out_ << ',', put(out_, orientation.x), out_ << ',',
        put(out_, orientation.y), out_ << ',', put(out_, orientation.z);
    out_ << "],\"v\":";
    put(out_, speed);
    out_ << ",\"contacts\":[";
    bool first = true;
    for (const Contact& c : contacts) {
        if (!(c.depth > 0.0)) continue;
        out_ << (first ? "[" : ",[");
        first = false;
        put(out_, c.point.x), out_ << ',', put(out_, c.point.y), out_ << ',', put(out_, c.point.z);
        out_ << ',';
        put(out_, c.normal.x), out_ << ',', put(out_, c.normal.y), out_ << ',',
            put(out_, c.normal.z);
        out_ << ',';
        put(out_, c.depth);
        out_ << ']';
    }
    out_ << "]}";
}

void RecordingWriter::end_frame() { out_ << "]}\n"; }

void RecordingWriter::finish() {
    out_.flush();
    if (!out_) throw Error("cannot write the recording '" + temporary_.string() + "'");
    out_.close();
    std::error_code error;
    std::filesystem::rename(temporary_, path_, error);
    if (error)
        throw Error("cannot move the recording into place at '" + path_.string() +
                    "': " + error.message());
    finished_ = true;
}

}  // namespace trackphys
