// libFuzzer target: the default car on the default track (seed 7) under fuzzed starts and
// controls.
//
// Bytes -> a start (centreline sample, height above the road, speed along the road up to
// ~1100 km/h, a sideways slip and a spin) and up to 25 updates of controls. Byte 0 picks the
// controls' decoding: even, one byte each for throttle, brake and steer in their ranges;
// odd, raw doubles (infinities and out of range: Car::set_inputs clamps them; NaN: it must
// reject them with trackphys::Error). A start inside the road (the lowest starts sink the
// wheels into it) must be rejected by World::add_car with trackphys::Error. After every
// update the car's state must be finite.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "trackphys/collision/mid_phase.hpp"
#include "trackphys/collision/static_collider.hpp"
#include "trackphys/collision/static_world.hpp"
#include "trackphys/dynamics/car.hpp"
#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/error.hpp"
#include "trackphys/math/types.hpp"
#include "trackphys/track/track.hpp"
#include "trackphys/track/track_params.hpp"
#include "trackphys/world/world.hpp"

namespace {

using trackphys::CarInputs;
using trackphys::RigidBodyState;

constexpr std::size_t kStartBytes = 12;  // sample 2, height 2, speed 2, slip 2, spin 4
constexpr std::size_t kMaxUpdates = 25;

struct Scene {
    trackphys::Track track;
    std::shared_ptr<const trackphys::StaticWorld> statics;
    trackphys::ColliderPlaneTrees trees;
};

// Built once per process: generating and indexing the track (and its plane trees, which a
// World would otherwise build for every input: seconds under the sanitizers) takes far
// longer than a run.
const Scene& scene() {
    static const Scene built = [] {
        trackphys::TrackParams params;
        params.seed = 7;
        Scene s{trackphys::generate_track(params), nullptr, {}};
        auto statics = std::make_shared<trackphys::StaticWorld>();
        for (const trackphys::TrackChunk& chunk : s.track.chunks)
            statics->add(std::make_shared<trackphys::StaticCollider>(chunk.mesh));
        s.statics = std::move(statics);
        s.trees = trackphys::make_collider_plane_trees(*s.statics);
        return s;
    }();
    return built;
}

// Little-endian integers from data at offset, zero past the end.
template <class T>
T read(const std::uint8_t* data, std::size_t size, std::size_t offset) {
    T value{};
    if (offset + sizeof(T) <= size) std::memcpy(&value, data + offset, sizeof(T));
    return value;
}

RigidBodyState decode_start(const trackphys::Track& track, const std::uint8_t* data,
                            std::size_t size) {
    const auto& line = track.centerline;
    const auto& at = line[read<std::uint16_t>(data, size, 1) % line.size()];
    RigidBodyState state;
    // 0.3 m (wheels near the road) to ~4 m above it: a drop onto the road.
    const double height = 0.3 + read<std::uint16_t>(data, size, 3) / 16384.0;
    state.position = at.position + at.up * height;
    state.orientation = glm::normalize(glm::quat_cast(glm::dmat3(at.left, at.up, at.tangent)));
    const double speed = read<std::int16_t>(data, size, 5) / 100.0;  // +-328 m/s
    const double slip = read<std::int16_t>(data, size, 7) / 1000.0;  // +-33 m/s sideways
    state.linear_velocity = at.tangent * speed + at.left * slip;
    const double yaw_rate = read<std::int16_t>(data, size, 9) / 8192.0;  // +-4 rad/s
    const double roll_rate = read<std::int16_t>(data, size, 11) / 8192.0;
    state.angular_velocity = at.up * yaw_rate + at.tangent * roll_rate;
    return state;
}

CarInputs decode_inputs(bool raw, const std::uint8_t* data, std::size_t size, std::size_t offset) {
    CarInputs in;
    if (raw) {
        in.throttle = read<double>(data, size, offset);
        in.brake = read<double>(data, size, offset + 8);
        in.steer = read<double>(data, size, offset + 16);
    } else {
        in.throttle = (read<std::uint8_t>(data, size, offset) - 127.5) / 127.5;  // < 0 reverse
        in.brake = read<std::uint8_t>(data, size, offset + 1) / 255.0;
        in.steer = (read<std::uint8_t>(data, size, offset + 2) - 127.5) / 127.5;
    }
    return in;
}

bool finite(const RigidBodyState& s) {
    return trackphys::is_finite(s.position) && trackphys::is_finite(s.orientation) &&
           trackphys::is_finite(s.linear_velocity) && trackphys::is_finite(s.angular_velocity);
}

}  // namespace

// The scene is built before the first input, outside libFuzzer's per-input timeout (it takes
// longer than that under the sanitizers on a loaded machine).
extern "C" int LLVMFuzzerInitialize(int*, char***) {
    scene();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const bool raw = size > 0 && data[0] % 2 == 1;
    const std::size_t per_update = raw ? 24 : 3;
    if (size < 1 + kStartBytes || size > 1 + kStartBytes + kMaxUpdates * per_update) return -1;
    const Scene& s = scene();
    trackphys::World world(s.statics, trackphys::WorldSettings{}, s.trees);
    std::size_t car = 0;
    try {
        car = world.add_car(trackphys::CarSpec::default_car(), decode_start(s.track, data, size));
    } catch (const trackphys::Error&) {
        return 0;  // a start inside the road
    }
    const std::size_t updates = std::max<std::size_t>(1, (size - 1 - kStartBytes) / per_update);
    for (std::size_t u = 0; u < updates; ++u) {
        const CarInputs in = decode_inputs(raw, data, size, 1 + kStartBytes + u * per_update);
        const bool nan = std::isnan(in.throttle) || std::isnan(in.brake) || std::isnan(in.steer);
        try {
            world.car(car).set_inputs(in);
            if (nan) {
                std::fprintf(stderr, "fuzz_world: a NaN input was accepted\n");
                std::abort();
            }
        } catch (const trackphys::Error&) {
            if (!nan) throw;  // an error for finite inputs is a finding
        }
        world.update();
        if (!finite(world.car(car).state())) {
            std::fprintf(stderr, "fuzz_world: non-finite car state after update %zu\n", u + 1);
            std::abort();
        }
    }
    return 0;
}
