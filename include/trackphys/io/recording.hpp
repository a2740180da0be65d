#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "trackphys/export.hpp"
#include "trackphys/geometry/contact.hpp"

namespace trackphys {

/// Writes a drive as JSON Lines for a viewer to replay: a header line, then one line per
/// recorded update with every car's pose and the contacts of its ellipsoids.
///
///     {"format":"trackphys-recording","version":1,"dt":0.01,"cars":1,"scene":"..."}
///     {"t":0.01,"hash":"...","cars":[{"p":[x,y,z],"q":[w,x,y,z],"v":speed,
///       "contacts":[[px,py,pz,nx,ny,nz,depth],...]}]}
///
/// Units are SI, world +Y up; q maps the car's body frame (+X left, +Y up, +Z forward) to
/// the world. The file is written under a temporary name and renamed by finish(), so a
/// run that fails never leaves a partial recording behind.
class TRACKPHYS_API RecordingWriter {
  public:
    /// Opens path's temporary sibling; throws trackphys::Error when it cannot.
    RecordingWriter(const std::filesystem::path& path, double dt, std::size_t cars,
                    const std::string& scene);
    /// Removes the temporary file unless finish() succeeded.
    ~RecordingWriter();
    RecordingWriter(const RecordingWriter&) = delete;
    RecordingWriter& operator=(const RecordingWriter&) = delete;

    /// Starts the line of the update that ended at time t (s), with the world's state hash.
    void begin_frame(double t, std::uint64_t state_hash);
    /// Adds one car to the current line: pose, speed (m/s) and its ellipsoids' contacts
    /// (only those that overlap are written).
    void add_car(const glm::dvec3& position, const glm::dquat& orientation, double speed,
                 std::span<const Contact> contacts);
    void end_frame();

    /// Flushes and renames the file into place; throws trackphys::Error on failure.
    void finish();

  private:
    std::filesystem::path path_;
    std::filesystem::path temporary_;
    std::ofstream out_;
    bool first_car_ = true;
    bool finished_ = false;
};

}  // namespace trackphys
