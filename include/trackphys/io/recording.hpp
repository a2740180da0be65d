#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "trackphys/dynamics/car.hpp"
#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/export.hpp"
#include "trackphys/geometry/contact.hpp"
#include "trackphys/math/types.hpp"
#include "trackphys/vehicle/vehicle.hpp"
#include "trackphys/world/debug_draw.hpp"

namespace trackphys {

class World;

/// What a recording's header says about the scene: enough for a viewer to draw it without
/// anything else (docs/recording.md).
struct RecordingHeader {
    double dt = 0.01;   ///< seconds between recorded updates
    std::string scene;  ///< what was driven, for people ("generated track, seed 7, ...")
    /// The track's mesh file, relative to the recording's folder (a generic path with '/'
    /// separators is written); empty when the recording carries no track.
    std::filesystem::path track_mesh;
    /// Each car's ellipsoids in its body frame, in the order of the frames' cars.
    std::vector<std::vector<CarEllipsoid>> car_ellipsoids;
};

/// What a car's vehicle model did in one recorded update (Vehicle's telemetry).
struct RecordedVehicle {
    double engine_rpm = 0.0;  ///< rev/min
    int gear = 1;             ///< 1 = first
    /// Each wheel's last sub-step, in the order of the car's wheel ellipsoids.
    std::span<const WheelTelemetry> wheels;
};

/// One car in one recorded update.
struct RecordedCar {
    glm::dvec3 position{0.0};                    ///< centre of mass, world (m)
    glm::dquat orientation{1.0, 0.0, 0.0, 0.0};  ///< world from body
    double speed = 0.0;                          ///< of the centre of mass (m/s)
    /// Each ellipsoid's suspension compression (m, CarSpec order; 0 for the body).
    std::span<const double> suspension;
    /// Each ellipsoid's deepest contact (CarSpec order); only those that overlap are written.
    std::span<const Contact> contacts;
    std::optional<CarInputs> inputs;  ///< the driver's controls during the update
    std::optional<int> laps;          ///< laps completed, when someone counts them
    /// The vehicle model's telemetry, for a car that has one (CarSpec::vehicle).
    std::optional<RecordedVehicle> vehicle;
};

/// Writes a drive as JSON Lines for a viewer to replay (format version 2, docs/recording.md):
/// a header line, then one line per recorded update with every car's pose, speed,
/// suspension, inputs, the contacts of its ellipsoids and, for a car with a vehicle model,
/// its engine speed, gear and wheels, and the contacts between cars (only when some touch).
///
///     {"format":"trackphys-recording","version":2,"dt":0.01,"cars":1,"scene":"...",
///      "track":{"mesh":"drive.track.glb"},"car_ellipsoids":[[{"center":[..],...}]]}
///     {"t":0.01,"hash":"...","us":61.2,"cars":[{"p":[x,y,z],"q":[w,x,y,z],"v":speed,
///       "s":[...],"in":[throttle,brake,steer],"lap":0,
///       "contacts":[[px,py,pz,nx,ny,nz,depth,ellipsoid],...],
///       "vehicle":{"rpm":6500,"gear":3,"wheels":[[slip_ratio,slip_angle_deg,load_n,
///                  spin_rad_s],...]}}],
///      "car_contacts":[[car_a,car_b,ellipsoid_a,ellipsoid_b,px,py,pz,nx,ny,nz,depth],...]}
///
/// Units are SI, world +Y up; q maps the car's body frame (+X left, +Y up, +Z forward) to
/// the world. The file is written under a temporary name and renamed by finish(), so a
/// run that fails never leaves a partial recording behind.
///
/// write_frame records a World through its DebugDraw callbacks, so a recording holds what a
/// game's debug draw shows; begin_frame, add_car and end_frame write a line by hand.
class TRACKPHYS_API RecordingWriter : private DebugDraw {
  public:
    /// Opens path's temporary sibling and writes the header; throws trackphys::Error when
    /// it cannot.
    RecordingWriter(const std::filesystem::path& path, const RecordingHeader& header);
    /// Removes the temporary file unless finish() succeeded.
    ~RecordingWriter();
    RecordingWriter(const RecordingWriter&) = delete;
    RecordingWriter& operator=(const RecordingWriter&) = delete;

    /// Writes the line of the update `world` ran last: its time, state hash and update time (when
    /// settings().profile), and each car's pose, speed, suspension, inputs and contacts as
    /// World::debug_draw reports them, with its vehicle model's telemetry if it has one, and
    /// the contacts between cars (World::car_contacts). Allocates nothing once the writer has
    /// written a frame of as many cars; laps[k]:
    /// car k's laps completed, when someone counts them (empty: no one does). The world's cars must
    /// be the header's, as many with as many ellipsoids each: throws trackphys::Error, writing
    /// nothing, when they are not.
    void write_frame(const World& world, std::span<const std::optional<int>> laps = {});

    /// Starts the line of the update that ended at time t (s), with the world's state hash
    /// and, when measured, how long the update took (us).
    void begin_frame(double t, std::uint64_t state_hash,
                     std::optional<double> update_us = std::nullopt);
    /// Adds the next car to the current line; cars come in the header's order. Throws
    /// trackphys::Error for a car past the header's or with another number of ellipsoids
    /// (a suspension for each, and a contact for each or none), as end_frame does for a line
    /// short of the header's cars;
    /// the line is then unfinished, and finish() refuses to put the file in place.
    void add_car(const RecordedCar& car);
    /// Ends the line with the pairs of cars touching (World::car_contacts; only those with
    /// depth > 0 are written). Throws trackphys::Error for a line short of the header's cars
    /// or a contact naming a car or an ellipsoid the header has not (car_a < car_b).
    void end_frame(std::span<const CarPairContact> car_contacts = {});

    /// Flushes and renames the file into place; throws trackphys::Error on failure or after a
    /// line was left unfinished.
    void finish();

  private:
    // write_frame's callbacks: a car's line waits for its ellipsoids and contacts.
    void draw_car(std::size_t index, const Car& car) override;
    void draw_ellipsoid(const DebugEllipsoid& ellipsoid) override;
    void draw_contact(const DebugContact& contact) override;
    // Writes the car draw_car started, if any.
    void add_drawn_car();

    std::filesystem::path path_;
    std::filesystem::path temporary_;
    std::ofstream out_;
    std::vector<std::size_t> ellipsoids_;  // per car, the header's
    std::size_t line_cars_ = 0;            // cars on the current line
    bool unfinished_line_ = false;         // an error left a line half written
    bool finished_ = false;
    // The car write_frame is drawing and its laps, suspension and contacts so far (the
    // vectors keep their capacity: no allocation per frame).
    const Car* drawn_car_ = nullptr;
    std::optional<int> drawn_laps_;
    std::vector<double> drawn_suspension_;
    std::vector<Contact> drawn_contacts_;
    std::span<const std::optional<int>> frame_laps_;
};

}  // namespace trackphys
