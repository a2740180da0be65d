#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "trackphys/dynamics/car_spec.hpp"
#include "trackphys/export.hpp"

/// Car specs as JSON files, the format `trackphys drive --car FILE` reads and
/// `trackphys drive --print-car` writes. Every key is optional: a key left out keeps the
/// value of CarSpec::default_car(), so a file can hold only what it changes. Units are SI.
///
///     {
///       "mass": {"mass": 1200, "principal_inertia": [x, y, z]},
///       "ellipsoids": [{"center": [x, y, z], "semi_axes": [a, b, c],
///                       "orientation": [w, x, y, z], "role": "front_wheel"}, ...],
///       "body_contact": {"stiffness": k, "damping": c, "friction": mu, "slip_speed": v},
///       "wheel_contact": {...as body_contact}, "car_contact": {...as body_contact},
///       "suspension": {"stiffness": k, "damping": c, "travel": s},
///       "rear_grip_factor": 1.15, "max_drive_force": 2e4, "front_drive_share": 0.4,
///       "traction_limit": 0.8, "max_drive_power": 6e6, "max_brake_force": 3e4,
///       "front_brake_share": 0.6, "max_steer_angle": 0.6, "deep_contact_fraction": 0.5,
///       "drag_area": 0.35, "downforce_area": 0.9, "air_density": 1.2
///     }
///
/// The keys are CarSpec's field names. "ellipsoids", when present, replaces the whole list;
/// each entry needs "center", "semi_axes" and "role" ("body", "front_wheel" or
/// "rear_wheel"); "orientation" (body from ellipsoid local, a quaternion [w, x, y, z])
/// defaults to the identity. Inside "mass", the three materials and
/// "suspension", a key left out keeps the default car's value too.

namespace trackphys {

/// The car spec in text (JSON). source names the text in messages (e.g. "car spec
/// 'car.json'"). Throws trackphys::Error with a message
/// that names source, and:
/// - malformed JSON: the line and column ("malformed JSON, parse error at line 3, column 7");
/// - a key given twice in an object, or one the format does not have: the key and its JSON
///   path ("ellipsoids[1].colour: unknown key (expected one of: center, semi_axes, ...)");
/// - a value of the wrong type, a non-finite number, an ellipsoid without center,
///   semi_axes or role, an unknown role: the JSON path of the value;
/// - a spec CarSpec::validate() rejects (mass <= 0, a semi-axis <= 0...): its message.
TRACKPHYS_API CarSpec parse_car_spec(std::string_view json_text,
                                     const std::string& source = "car spec");

/// parse_car_spec of a file's contents; the message also names the file when it is
/// missing, a folder or a device, unreadable, empty or larger than 16 MiB.
TRACKPHYS_API CarSpec load_car_spec(const std::filesystem::path& file);

/// spec as a JSON document (2-space indent, every key, numbers that read back to the same
/// bits): what parse_car_spec reads back into an identical spec.
TRACKPHYS_API std::string car_spec_to_json(const CarSpec& spec);

}  // namespace trackphys
