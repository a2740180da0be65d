// Snapshot files (see snapshot_file.hpp for the layout).

#include "trackphys/io/snapshot_file.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <fstream>
#include <system_error>

#include "core/fnv1a.hpp"
#include "trackphys/error.hpp"
#include "trackphys/io/regular_file.hpp"

namespace trackphys {
namespace {

constexpr char kSnapshotMagic[8] = {'T', 'P', 'S', 'N', 'A', 'P', '\x1a', '\n'};
constexpr std::size_t kHeaderBytes = 32;
// The fewest payload bytes one collider, car, ellipsoid and touching pair take: a count claiming more
// than the bytes left is rejected before anything is allocated for it.
constexpr std::size_t kColliderBytes = 24;
constexpr std::size_t kCarBytes = 8 + 13 * 8 + 3 * 8 + 4 + 8 + 8 + 4;
constexpr std::size_t kWheelBytes = 4 * 8;
constexpr std::size_t kEllipsoidBytes = 8 * 8 + 2 * 4;
constexpr std::size_t kTouchingBytes = 2 * 4 + 8;

std::uint64_t checksum(std::string_view bytes) {
    core::Fnv1a hash;
    hash.add(bytes.data(), bytes.size());
    return hash.value;
}

// Little-endian, whatever the host's byte order.
class Writer {
  public:
    void u32(std::uint32_t x) { put(x, 4); }
    void u64(std::uint64_t x) { put(x, 8); }
    void f64(double x) { put(std::bit_cast<std::uint64_t>(x), 8); }
    void vec(const glm::dvec3& v) { f64(v.x), f64(v.y), f64(v.z); }
    void bytes(std::string_view b) { out_.append(b); }
    std::string& out() { return out_; }

  private:
    void put(std::uint64_t x, int n) {
        for (int i = 0; i < n; ++i) out_.push_back(static_cast<char>((x >> (8 * i)) & 0xff));
    }
    std::string out_;
};

class Reader {
  public:
    explicit Reader(std::string_view in) : in_(in) {}
    std::uint32_t u32(const char* what) { return static_cast<std::uint32_t>(get(4, what)); }
    std::uint64_t u64(const char* what) { return get(8, what); }
    double f64(const char* what) { return std::bit_cast<double>(get(8, what)); }
    glm::dvec3 vec(const char* what) {
        const double x = f64(what), y = f64(what);
        return {x, y, f64(what)};
    }
    std::string_view bytes(std::size_t n, const char* what) {
        need(n, what);
        const std::string_view b = in_.substr(at_, n);
        at_ += n;
        return b;
    }
    // A count of records of at least `record` bytes each, checked against the bytes left.
    std::size_t count(std::uint64_t n, std::size_t record, const char* what) {
        if (n > (in_.size() - at_) / record)
            throw Error(std::string("snapshot: the payload is truncated: ") + what + " count " +
                        std::to_string(n) + " needs more bytes than the " +
                        std::to_string(in_.size() - at_) + " left");
        return static_cast<std::size_t>(n);
    }
    std::size_t left() const { return in_.size() - at_; }

  private:
    void need(std::size_t n, const char* what) const {
        if (in_.size() - at_ < n)
            throw Error(std::string("snapshot: the payload is truncated at byte ") +
                        std::to_string(at_) + " reading " + what);
    }
    std::uint64_t get(int n, const char* what) {
        need(static_cast<std::size_t>(n), what);
        std::uint64_t x = 0;
        for (int i = 0; i < n; ++i)
            x |= static_cast<std::uint64_t>(
                     static_cast<unsigned char>(in_[at_ + static_cast<std::size_t>(i)]))
                 << (8 * i);
        at_ += static_cast<std::size_t>(n);
        return x;
    }
    std::string_view in_;
    std::size_t at_ = 0;
};

struct SnapshotHeader {
    std::uint64_t payload_bytes;
    std::uint64_t checksum;
};

// The header's fields, checked; `bytes` begins with the file's first bytes.
SnapshotHeader read_header(std::string_view bytes) {
    if (bytes.size() < kHeaderBytes)
        throw Error("snapshot: " + std::to_string(bytes.size()) + " bytes, shorter than the " +
                    std::to_string(kHeaderBytes) + "-byte header (truncated or not a snapshot)");
    if (std::memcmp(bytes.data(), kSnapshotMagic, sizeof kSnapshotMagic) != 0)
        throw Error("snapshot: wrong magic (not a trackphys snapshot file)");
    Reader header(bytes.substr(sizeof kSnapshotMagic, kHeaderBytes - sizeof kSnapshotMagic));
    const std::uint32_t version = header.u32("format version");
    if (version != kSnapshotFormatVersion)
        throw Error("snapshot: format version " + std::to_string(version) +
                    ", this build reads only version " + std::to_string(kSnapshotFormatVersion));
    if (const std::uint32_t reserved = header.u32("reserved"); reserved != 0)
        throw Error("snapshot: the reserved header field is " + std::to_string(reserved) +
                    ", not 0");
    const std::uint64_t length = header.u64("payload length");
    return {length, header.u64("checksum")};
}

void check_payload_size(std::uint64_t announced, std::uint64_t available) {
    if (announced > available)
        throw Error("snapshot: truncated: the header announces " + std::to_string(announced) +
                    " payload bytes, the file has " + std::to_string(available));
    if (announced < available)
        throw Error("snapshot: " + std::to_string(available - announced) +
                    " bytes of trailing garbage after the payload");
}

// decode_snapshot's messages begin "snapshot: "; a file's messages name it there instead.
[[noreturn]] void fail_naming(const std::string& source, std::string_view why) {
    constexpr std::string_view prefix = "snapshot: ";
    if (why.starts_with(prefix)) why.remove_prefix(prefix.size());
    throw Error(source + ": " + std::string(why));
}

// Every field but `profile`, `threads` and `jobs`, which do not change results, and
// `surfaces`, the environment (world_snapshot.cpp's settings_difference). (A new field
// also needs a new format version, and settings_difference in world_snapshot.cpp.)
static_assert(sizeof(WorldSettings) == 160,
              "a new WorldSettings field must join the snapshot file");

void write_settings(Writer& w, const WorldSettings& s) {
    w.f64(s.dt_update);
    w.u32(static_cast<std::uint32_t>(s.steps));
    w.u32(static_cast<std::uint32_t>(s.substeps));
    w.vec(s.gravity);
    w.f64(s.broad_phase_margin);
    w.u32(static_cast<std::uint32_t>(s.mid_phase));
    w.u32(static_cast<std::uint32_t>(s.mid_phase_look_ahead));
    w.f64(s.mid_phase_slack);
    w.f64(s.max_car_speed);
    w.f64(s.max_car_angular_speed);
    w.f64(s.max_spawn_distance);
}

WorldSettings read_settings(Reader& r) {
    WorldSettings s;
    s.dt_update = r.f64("settings.dt_update");
    s.steps = static_cast<int>(r.u32("settings.steps"));
    s.substeps = static_cast<int>(r.u32("settings.substeps"));
    s.gravity = r.vec("settings.gravity");
    s.broad_phase_margin = r.f64("settings.broad_phase_margin");
    const std::uint32_t mode = r.u32("settings.mid_phase");
    if (mode > static_cast<std::uint32_t>(MidPhaseMode::precomputed_tree))
        throw Error("snapshot: settings.mid_phase " + std::to_string(mode) +
                    " is not a mid-phase mode");
    s.mid_phase = static_cast<MidPhaseMode>(mode);
    s.mid_phase_look_ahead = static_cast<int>(r.u32("settings.mid_phase_look_ahead"));
    s.mid_phase_slack = r.f64("settings.mid_phase_slack");
    s.max_car_speed = r.f64("settings.max_car_speed");
    s.max_car_angular_speed = r.f64("settings.max_car_angular_speed");
    s.max_spawn_distance = r.f64("settings.max_spawn_distance");
    return s;
}

void write_car(Writer& w, const CarSnapshot& car) {
    w.u64(car.spec_fingerprint);
    w.vec(car.state.position);
    w.f64(car.state.orientation.w), w.f64(car.state.orientation.x), w.f64(car.state.orientation.y),
        w.f64(car.state.orientation.z);
    w.vec(car.state.linear_velocity);
    w.vec(car.state.angular_velocity);
    w.f64(car.inputs.throttle), w.f64(car.inputs.brake), w.f64(car.inputs.steer);
    w.u32(static_cast<std::uint32_t>(car.suspension.size()));
    for (std::size_t i = 0; i < car.suspension.size(); ++i) {
        w.f64(car.suspension[i]);
        w.f64(car.contacts[i].depth);
        w.vec(car.contacts[i].normal);
        w.vec(car.contacts[i].point);
        w.u32(car.deepest_refs[i].collider);
        w.u32(car.deepest_refs[i].triangle);
    }
    w.u64(car.empty_lists);
    w.u64(car.resets);
    if (!car.vehicle) {
        w.u32(0);
        return;
    }
    w.u32(static_cast<std::uint32_t>(car.vehicle->wheels.size() + 1));
    for (const WheelState& wheel : car.vehicle->wheels)
        w.f64(wheel.spin), w.f64(wheel.slip_ratio), w.f64(wheel.lateral_slip),
            w.f64(wheel.road_torque);
    w.u32(static_cast<std::uint32_t>(car.vehicle->gear));
    w.f64(car.vehicle->shift_time_left), w.f64(car.vehicle->clutch);
}

CarSnapshot read_car(Reader& r) {
    CarSnapshot car;
    car.spec_fingerprint = r.u64("car spec fingerprint");
    car.state.position = r.vec("car position");
    const double qw = r.f64("car orientation"), qx = r.f64("car orientation"),
                 qy = r.f64("car orientation"), qz = r.f64("car orientation");
    car.state.orientation = glm::dquat(qw, qx, qy, qz);
    car.state.linear_velocity = r.vec("car linear velocity");
    car.state.angular_velocity = r.vec("car angular velocity");
    car.inputs.throttle = r.f64("car throttle");
    car.inputs.brake = r.f64("car brake");
    car.inputs.steer = r.f64("car steer");
    const std::size_t n = r.count(r.u32("ellipsoid count"), kEllipsoidBytes, "ellipsoid");
    car.suspension.resize(n);
    car.contacts.resize(n);
    car.deepest_refs.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        car.suspension[i] = r.f64("ellipsoid suspension");
        car.contacts[i].depth = r.f64("contact depth");
        car.contacts[i].normal = r.vec("contact normal");
        car.contacts[i].point = r.vec("contact point");
        car.deepest_refs[i].collider = r.u32("contact collider");
        car.deepest_refs[i].triangle = r.u32("contact triangle");
    }
    car.empty_lists = r.u64("car empty lists");
    car.resets = r.u64("car resets");
    const std::uint32_t wheels_and_one = r.u32("vehicle wheel count");
    if (wheels_and_one == 0) return car;
    VehicleState& vehicle = car.vehicle.emplace();
    vehicle.wheels.resize(r.count(wheels_and_one - 1, kWheelBytes, "vehicle wheel"));
    for (WheelState& wheel : vehicle.wheels) {
        wheel.spin = r.f64("wheel spin");
        wheel.slip_ratio = r.f64("wheel slip ratio");
        wheel.lateral_slip = r.f64("wheel lateral slip");
        wheel.road_torque = r.f64("wheel road torque");
    }
    vehicle.gear = static_cast<int>(r.u32("vehicle gear"));
    vehicle.shift_time_left = r.f64("vehicle shift time");
    vehicle.clutch = r.f64("vehicle clutch");
    return car;
}

}  // namespace

std::string encode_snapshot(const WorldSnapshot& snapshot, std::string_view user_data) {
    Writer payload;
    payload.u32(static_cast<std::uint32_t>(snapshot.colliders.size()));
    for (const ColliderFingerprint& c : snapshot.colliders) {
        payload.u64(c.mesh_triangles);
        payload.u64(c.kept_triangles);
        payload.u64(c.content_hash);
    }
    write_settings(payload, snapshot.settings);
    payload.u64(snapshot.update_count);
    payload.u32(static_cast<std::uint32_t>(snapshot.cars.size()));
    for (const CarSnapshot& car : snapshot.cars) write_car(payload, car);
    payload.u32(static_cast<std::uint32_t>(snapshot.touching.size()));
    for (const CarTouchSnapshot& t : snapshot.touching) {
        payload.u32(t.car_a);
        payload.u32(t.car_b);
        payload.f64(t.deepest);
    }
    payload.u64(user_data.size());
    payload.bytes(user_data);

    Writer file;
    file.bytes(std::string_view(kSnapshotMagic, sizeof kSnapshotMagic));
    file.u32(kSnapshotFormatVersion);
    file.u32(0);
    file.u64(payload.out().size());
    file.u64(checksum(payload.out()));
    file.bytes(payload.out());
    return std::move(file.out());
}

SnapshotFile decode_snapshot(std::string_view bytes) {
    const SnapshotHeader header = read_header(bytes);
    check_payload_size(header.payload_bytes, bytes.size() - kHeaderBytes);
    const std::string_view payload = bytes.substr(kHeaderBytes);
    if (checksum(payload) != header.checksum)
        throw Error("snapshot: checksum mismatch (the file is corrupted)");

    Reader r(payload);
    SnapshotFile file;
    WorldSnapshot& s = file.world;
    s.colliders.resize(r.count(r.u32("collider count"), kColliderBytes, "collider"));
    for (ColliderFingerprint& c : s.colliders) {
        c.mesh_triangles = r.u64("collider mesh triangles");
        c.kept_triangles = r.u64("collider kept triangles");
        c.content_hash = r.u64("collider content hash");
    }
    s.settings = read_settings(r);
    s.update_count = r.u64("update count");
    const std::size_t cars = r.count(r.u32("car count"), kCarBytes, "car");
    s.cars.reserve(cars);
    for (std::size_t i = 0; i < cars; ++i) s.cars.push_back(read_car(r));
    s.touching.resize(r.count(r.u32("touching count"), kTouchingBytes, "touching pair"));
    for (CarTouchSnapshot& t : s.touching) {
        t.car_a = r.u32("touching car_a");
        t.car_b = r.u32("touching car_b");
        t.deepest = r.f64("touching deepest");
    }
    const std::size_t user = r.count(r.u64("user data length"), 1, "user data byte");
    file.user_data = std::string(r.bytes(user, "user data"));
    if (r.left() != 0)
        throw Error("snapshot: " + std::to_string(r.left()) +
                    " unread bytes at the end of the payload");
    if (std::string why = s.validate(); !why.empty())
        throw Error("snapshot: invalid contents: " + why);
    return file;
}

void save_snapshot(const std::filesystem::path& path, const WorldSnapshot& snapshot,
                   std::string_view user_data) {
    const std::string bytes = encode_snapshot(snapshot, user_data);
    const std::filesystem::path temporary = path.string() + ".partial";
    std::error_code ignored;
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out)
            throw Error("cannot write the snapshot '" + path.string() + "': cannot create '" +
                        temporary.string() + "'");
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        if (!out.flush()) {
            out.close();
            std::filesystem::remove(temporary, ignored);
            throw Error("cannot write the snapshot '" + temporary.string() + "'");
        }
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error) {
        std::filesystem::remove(temporary, ignored);
        throw Error("cannot move the snapshot into place at '" + path.string() +
                    "': " + error.message());
    }
}

SnapshotFile load_snapshot(const std::filesystem::path& path) {
    const std::string source = "snapshot '" + path.string() + "'";
    require_regular_file(path, source);
    std::error_code error;
    const std::uintmax_t size = std::filesystem::file_size(path, error);
    if (error) throw Error(source + ": cannot read its size: " + error.message());
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(source + ": cannot open it for reading");
    // The header first: its payload length must match the file's size before the payload is
    // read, so a file is never read past what it announces.
    std::string bytes(static_cast<std::size_t>(std::min<std::uintmax_t>(size, kHeaderBytes)), '\0');
    try {
        in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        const SnapshotHeader header = read_header(bytes);
        check_payload_size(header.payload_bytes, size - kHeaderBytes);
        bytes.resize(kHeaderBytes + static_cast<std::size_t>(header.payload_bytes));
        in.read(bytes.data() + kHeaderBytes, static_cast<std::streamsize>(header.payload_bytes));
        if (!in) throw Error("snapshot: cannot read it (did it change while it was read?)");
        return decode_snapshot(bytes);
    } catch (const Error& e) {
        fail_naming(source, e.what());
    }
}

}  // namespace trackphys
