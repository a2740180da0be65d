// Car spec and scenario JSON files: what they read, what they write back, and a message that
// names the key and the reason for every way a file can be wrong.

#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "io_test_support.hpp"
#include "trackphys/error.hpp"
#include "trackphys/io/car_spec_json.hpp"
#include "trackphys/io/scenario.hpp"

namespace trackphys {
namespace {

// The message parse throws for text, or "" when it does not throw.
template <class Parse>
std::string error_of(Parse parse, const std::string& text) {
    try {
        parse(text);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

std::string car_error(const std::string& text) {
    return error_of([](const std::string& t) { parse_car_spec(t, "car spec 'c.json'"); }, text);
}

std::string scenario_error(const std::string& text) {
    return error_of([](const std::string& t) { parse_scenario(t, "scenario 's.json'"); }, text);
}

std::string repeated(const std::string& text, int times) {
    std::string result;
    for (int i = 0; i < times; ++i) result += text;
    return result;
}

// "k0": 0, "k1": 0, ...: an object's keys, each unknown.
std::string keys_of_zero(int count) {
    std::string keys;
    for (int i = 0; i < count; ++i) keys += (i > 0 ? ", \"k" : "\"k") + std::to_string(i) + "\": 0";
    return keys;
}

// [1000, 300], [1001, 300], ...: a torque curve of `count` points.
std::string torque_points(int count) {
    std::string points;
    for (int i = 0; i < count; ++i)
        points += (i > 0 ? ", [" : "[") + std::to_string(1000 + i) + ", 300]";
    return points;
}

const std::string kBall = R"("center": [0, 0, 0], "semi_axes": [0.5, 0.5, 0.5], "role": "body")";

TEST(CarSpecJson, DefaultCarRoundTripsBitForBit) {
    const CarSpec original = CarSpec::default_car();
    const std::string text = car_spec_to_json(original);
    const CarSpec read = parse_car_spec(text);
    EXPECT_EQ(car_spec_to_json(read), text);
    ASSERT_EQ(read.ellipsoids.size(), original.ellipsoids.size());
    EXPECT_EQ(read.mass.principal_inertia, original.mass.principal_inertia);  // 1929.9999999999998
    EXPECT_EQ(read.ellipsoids[5].semi_axes, original.ellipsoids[5].semi_axes);
    EXPECT_EQ(read.ellipsoids[1].role, EllipsoidRole::rear_wheel);
    EXPECT_EQ(read.air_density, original.air_density);
}

TEST(CarSpecJson, KeysLeftOutKeepTheDefaultCar) {
    const CarSpec spec =
        parse_car_spec(R"({"mass": {"mass": 900}, "wheel_contact": {"friction": 1.4},
                                           "ellipsoids": [{)" +
                       kBall + R"(, "orientation": [0, 0, 1, 0]}]})");
    const CarSpec base = CarSpec::default_car();
    EXPECT_EQ(spec.mass.mass, 900.0);
    EXPECT_EQ(spec.mass.principal_inertia, base.mass.principal_inertia);
    EXPECT_EQ(spec.wheel_contact.friction, 1.4);
    EXPECT_EQ(spec.wheel_contact.stiffness, base.wheel_contact.stiffness);
    ASSERT_EQ(spec.ellipsoids.size(), 1u);  // a list replaces the default one
    EXPECT_EQ(spec.ellipsoids[0].orientation, glm::dquat(0, 0, 1, 0));
    EXPECT_EQ(spec.max_drive_power, base.max_drive_power);
    EXPECT_EQ(car_spec_to_json(parse_car_spec("{}")), car_spec_to_json(base));
}

TEST(CarSpecJson, PresetsRoundTripAndModelPicksTheBase) {
    for (const std::string_view name : CarSpec::preset_names()) {
        const CarSpec preset = CarSpec::preset(name);
        const std::string text = car_spec_to_json(preset);
        EXPECT_EQ(car_spec_to_json(parse_car_spec(text)), text) << name;
        EXPECT_EQ(car_spec_to_json(parse_car_spec("{\"model\": \"" + std::string(name) + "\"}")),
                  text)
            << name;
    }
    // Keys beside "model" change the preset.
    const CarSpec gt = parse_car_spec(
        R"({"model": "gt", "drag_area": 0.7, "vehicle": {"gearbox": {"final_drive": 3.9,
            "reverse_ratio": 3.1},
            "rear_differential": {"kind": "open"}, "traction_control": false}})");
    ASSERT_TRUE(gt.vehicle.has_value());
    EXPECT_EQ(gt.vehicle->model, "gt");
    EXPECT_EQ(gt.drag_area, 0.7);
    EXPECT_EQ(gt.vehicle->gearbox.final_drive, 3.9);
    EXPECT_EQ(gt.vehicle->gearbox.reverse_ratio, 3.1);
    EXPECT_EQ(parse_car_spec(R"({"model": "gt", "vehicle": {"rolling_resistance": 0.015}})")
                  .vehicle->rolling_resistance,
              0.015);
    EXPECT_EQ(parse_car_spec(R"({"max_reverse_speed": 6})").max_reverse_speed, 6.0);
    EXPECT_EQ(gt.vehicle->gearbox.ratios, CarSpec::preset("gt").vehicle->gearbox.ratios);
    EXPECT_EQ(gt.vehicle->rear_differential.kind, DifferentialKind::open);
    EXPECT_FALSE(gt.vehicle->traction_control);
    EXPECT_FALSE(parse_car_spec(R"({"model": "arcade"})").vehicle.has_value());
}

TEST(CarSpecJson, EveryBadFileNamesTheKeyAndTheReason) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {R"({"mass": {"mass": -5}})",
         "car spec 'c.json': CarSpec.mass.mass must be finite and > 0, got -5"},
        {R"({"mass": {"mass": 0}})", "CarSpec.mass.mass must be finite and > 0, got 0"},
        {R"({"ellipsoids": [{"center": [0,0,0], "semi_axes": [0.3, 0, 0.3], "role": "body"}]})",
         "CarSpec.ellipsoids[0].semi_axes.y must be finite and > 0, got 0"},
        {R"({"ellipsoids": [{"center": [0,0,0], "semi_axes": [0.3, -1, 0.3], "role": "body"}]})",
         "CarSpec.ellipsoids[0].semi_axes.y must be finite and > 0, got -1"},
        {R"({"ellipsoids": []})", "CarSpec.ellipsoids must hold 1 to 64 ellipsoids, got 0"},
        // Beyond any car, and where the placement checks' squares would overflow.
        {R"({"ellipsoids": [{"center": [1e200, 0, 0], "semi_axes": [1, 1, 1], "role": "body"}]})",
         "CarSpec.ellipsoids[0].center (1e+200, 0, 0) is beyond the 10000 m from the centre of "
         "mass"},
        {R"({"ellipsoids": [{"center": [0, 0, 0], "semi_axes": [1, 2e4, 1], "role": "body"}]})",
         "CarSpec.ellipsoids[0].semi_axes.y must be at most 10000 m, got 20000"},
        {R"({"ellipsoids": [{)" + kBall + R"(, "orientation": [0, 0, 0, 0]}]})",
         "ellipsoids[0].orientation must be a finite unit quaternion"},
        // A key's control characters are escaped: a NUL cut the message short.
        {R"({"ma\u0000ss": 1, "mass": {}})", "unknown key 'ma\\x00ss' (expected one of: model"},
        {R"({"masss": 1})",
         "car spec 'c.json': unknown key 'masss' (expected one of: model, mass, ellipsoids,"},
        {R"({"model": "rally"})",
         "car spec 'c.json': model: unknown car preset 'rally' (expected arcade, gt or "
         "formula)"},
        {R"({"vehicle": {"wheel_inertia": 2}})",
         "vehicle: the arcade car has no vehicle model: give \"model\": \"gt\""},
        {R"({"model": "gt", "vehicle": {"gearbox": {"ratios": [3, 0]}}})",
         "CarSpec.vehicle.gearbox.ratios[1] must be finite and > 0, got 0"},
        {R"({"model": "gt", "vehicle": {"gearbox": {"reverse_ratio": 0}}})",
         "CarSpec.vehicle.gearbox.reverse_ratio must be finite and > 0, got 0"},
        {R"({"model": "gt", "vehicle": {"rolling_resistance": 0.5}})",
         "CarSpec.vehicle.rolling_resistance must be in [0, 0.1], got 0.5"},
        {R"({"max_reverse_speed": -2})",
         "CarSpec.max_reverse_speed must be finite and >= 0, got -2"},
        {R"({"model": "gt", "vehicle": {"gearbox": {"launch_rpm": 9000}}})",
         "CarSpec.vehicle.gearbox.launch_rpm must be in [engine.idle_rpm, "
         "gearbox.shift_up_rpm] = [1000, 8000], got 9000"},
        {R"({"model": "formula", "vehicle": {"gearbox": {"launch_rpm": 3000}}})",
         "CarSpec.vehicle.gearbox.launch_rpm must be in [engine.idle_rpm, "
         "gearbox.shift_up_rpm] = [4000, 12500], got 3000"},
        {R"({"model": "formula", "vehicle": {"rear_tyre": {"lateral": {"shape": 2.5}}}})",
         "CarSpec.vehicle.rear_tyre.lateral.shape must be in (1, 2], got 2.5"},
        {R"({"model": "gt", "vehicle": {"rear_differential": {"kind": "welded"}}})",
         "vehicle.rear_differential.kind: unknown kind 'welded' (expected open or limited_slip)"},
        {R"({"model": "gt", "vehicle": {"engine": {"torque_curve": [[1000, 300], [900, 1]]}}})",
         "CarSpec.vehicle.engine.torque_curve[1].rpm must exceed the previous point's"},
        {R"({"model": "gt", "vehicle": {"engine": {"torque_curve": [)" + torque_points(4097) +
             "]}}}",
         "CarSpec.vehicle.engine.torque_curve must hold 1 to 4096 points"},
        {R"({"model": "gt", "vehicle": {"anti_lock": 1}})",
         "vehicle.anti_lock: expected true or false"},
        {R"({"ellipsoids": [{)" + kBall + R"(}, {)" + kBall + R"(, "colour": "red"}]})",
         "ellipsoids[1]: unknown key 'colour' (expected one of: center, semi_axes, role, "
         "orientation)"},
        {R"({"suspension": {"travel": 0.1, "stiffnes": 5}})", "suspension: unknown key 'stiffnes'"},
        {R"({"mass": {"mass": "heavy"}})",
         "mass.mass: expected a number, got the string \"heavy\""},
        {R"({"drag_area": null})", "drag_area: expected a number, got null"},
        {R"({"drag_area": true})", "drag_area: expected a number, got a boolean"},
        {R"({"mass": 1200})", "mass: expected an object, got the number 1200"},
        {R"({"ellipsoids": {"center": [0, 0, 0]}})", "ellipsoids: expected an array of ellipsoids"},
        {R"({"ellipsoids": [{"center": [0, 0, 0], "role": "body"}]})",
         "ellipsoids[0]: missing key 'semi_axes'"},
        {R"({"ellipsoids": [{"center": [0, 0, 0], "semi_axes": [1, 1], "role": "body"}]})",
         "ellipsoids[0].semi_axes: expected an array of 3 numbers, got an array of 2"},
        {R"({"ellipsoids": [{"center": [0, "x", 0], "semi_axes": [1, 1, 1], "role": "body"}]})",
         "ellipsoids[0].center[1]: expected a number, got the string \"x\""},
        {R"({"ellipsoids": [{"center": [0, 0, 0], "semi_axes": [1, 1, 1], "role": "wing"}]})",
         "ellipsoids[0].role: unknown role 'wing' (expected body, front_wheel or rear_wheel)"},
        {R"({"drag_area": 1e999})",
         "car spec 'c.json': malformed JSON at drag_area, number overflow parsing '1e999'"},
        {R"({"ellipsoids": [{"center": [0, 0, 1e999]}]})",
         "malformed JSON at ellipsoids[0].center[2], number overflow parsing '1e999'"},
        // nlohmann's lexer ends the input at a NUL: what follows would go unread.
        {std::string("{\"drag_area\": 0.3}\n\0 \"mass\": x", 24),
         "car spec 'c.json': malformed JSON, a NUL byte at line 2, column 1"},
        {R"({"mass": )" + std::string(64, '['),
         "car spec 'c.json': mass" + repeated("[0]", 63) + ": nested deeper than 64 levels"},
        {R"({"model": "gt", "vehicle": {)" + keys_of_zero(257) + "}}",
         "car spec 'c.json': vehicle has more than 256 keys"},
        {R"({"mass": [)" + repeated("0, ", 1 << 20) + "0]}",
         "car spec 'c.json': more than 1048576 values"},
        {R"({"drag_area": NaN})", "malformed JSON, parse error at line 1, column 15"},
        {R"({"mass": {"mass": 1}, "mass": {}})", "duplicate key 'mass' in the top-level object"},
        {R"({"ellipsoids": [{}, {"center": [0, 0, 0], "center": [1, 1, 1]}]})",
         "duplicate key 'center' in ellipsoids[1]"},
        {"{\n  \"mass\": {\"mass\": 1200,}\n}", "malformed JSON, parse error at line 2, column 25"},
        {"{\"mass\": ",
         "malformed JSON, parse error at line 1, column 10: syntax error while parsing value - "
         "unexpected end of input"},
        {"", "malformed JSON, parse error at line 1, column 1"},
        {"[1, 2]", "car spec 'c.json': expected an object, got an array"},
        {"{} {}", "malformed JSON, parse error at line 1, column 4"},
    };
    for (const auto& [text, expected] : cases)
        EXPECT_NE(car_error(text).find(expected), std::string::npos)
            << "input: " << text << "\nmessage: " << car_error(text) << "\nexpected: " << expected;
}

TEST(ScenarioJson, EmptyObjectIsOneLapOfTheDefaultTrack) {
    const Scenario s = parse_scenario("{}");
    EXPECT_EQ(s.seed, 7u);
    EXPECT_TRUE(s.mesh.empty());
    EXPECT_FALSE(s.free_mode());
    EXPECT_EQ(s.target_speed_kmh, 600.0);
    EXPECT_EQ(s.laps, 0);
    EXPECT_EQ(s.seconds, 0.0);
    EXPECT_EQ(car_spec_to_json(s.car), car_spec_to_json(CarSpec::default_car()));
}

TEST(ScenarioJson, ReadsEveryKeyAndRoundTrips) {
    const Scenario s = parse_scenario(R"({
        "track": {"mesh": "tracks/g.ac", "spawn": [1, 50, -2], "heading_deg": 90},
        "car": {"mass": {"mass": 1000}},
        "inputs": {"throttle": 0.8, "brake": 0.1, "steer": -0.25},
        "seconds": 12.5})",
                                      "scenario", "/data/s");
    EXPECT_EQ(s.mesh, std::filesystem::path("/data/s/tracks/g.ac"));
    ASSERT_TRUE(s.spawn);
    EXPECT_EQ(*s.spawn, glm::dvec3(1, 50, -2));
    EXPECT_EQ(s.heading_deg, 90.0);
    EXPECT_EQ(s.car.mass.mass, 1000.0);
    EXPECT_EQ(s.inputs.throttle, 0.8);
    EXPECT_EQ(s.inputs.brake, 0.1);
    EXPECT_EQ(s.inputs.steer, -0.25);
    EXPECT_EQ(s.seconds, 12.5);
    const std::string text = scenario_to_json(s);
    EXPECT_EQ(scenario_to_json(parse_scenario(text)), text);

    const Scenario autopilot =
        parse_scenario(R"({"track": {"seed": 3}, "autopilot": {"target_speed_kmh": 1000},
                                                 "laps": 2, "seconds": 500})");
    EXPECT_EQ(autopilot.seed, 3u);
    EXPECT_EQ(parse_scenario(R"({"track": {"seed": -0}})").seed, 0u);  // was "must be >= 0, got 0"
    EXPECT_EQ(autopilot.target_speed_kmh, 1000.0);
    EXPECT_EQ(autopilot.laps, 2);
    EXPECT_EQ(scenario_to_json(parse_scenario(scenario_to_json(autopilot))),
              scenario_to_json(autopilot));

    const Scenario race = parse_scenario(R"({"cars": 20, "laps": 3})");
    EXPECT_EQ(race.cars, 20);
    EXPECT_EQ(parse_scenario(scenario_to_json(race)).cars, 20);
    EXPECT_TRUE(race.surfaces.empty());

    const Scenario icy =
        parse_scenario(R"({"track": {"seed": 7, "surfaces": [{"grip": 0.1}, {}, {"grip": 0.6}]}})");
    ASSERT_EQ(icy.surfaces.size(), 3u);
    EXPECT_EQ(icy.surfaces[0].grip, 0.1);
    EXPECT_EQ(icy.surfaces[1].grip, 1.0) << "a key left out keeps the dry road";
    EXPECT_EQ(icy.surfaces[2].grip, 0.6);
    const Scenario icy_again = parse_scenario(scenario_to_json(icy));
    ASSERT_EQ(icy_again.surfaces.size(), 3u);
    EXPECT_EQ(icy_again.surfaces[2].grip, 0.6);
    EXPECT_EQ(scenario_to_json(icy_again), scenario_to_json(icy));
}

TEST(ScenarioJson, EveryBadFileNamesTheKeyAndTheReason) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {R"({"track": {"seed": 7, "mesh": "a.obj", "spawn": [0, 1, 0]}, "seconds": 1})",
         "scenario 's.json': track: give one of 'seed' (a generated track), 'mesh' (a mesh "
         "file) or 'map' (a baked map)"},
        {R"({"track": {"seed": -3}})", "track.seed: must be >= 0, got -3"},
        {R"({"track": {"seed": 2.5}})", "track.seed: expected a whole number, got the number 2.5"},
        {R"({"track": {"mesh": "a.obj"}})", "Scenario.mesh needs a spawn point"},
        {R"({"track": {"mesh": ""}})", "track.mesh: empty file name"},
        {R"({"track": {"heading_deg": 10}})",
         "track.heading_deg: a heading applies to a spawn point"},
        {R"({"track": {"spawn": [0, 1]}})",
         "track.spawn: expected an array of 3 numbers, got an array of 2"},
        {R"({"track": {"spawn": [0, 1, 0]}, "autopilot": {}, "seconds": 1})",
         "autopilot: the autopilot drives the generated track from its start line"},
        {R"({"inputs": {"throttle": 1}})",
         "inputs: fixed inputs drive in free mode: add track.spawn"},
        {R"({"track": {"spawn": [0, 1, 0]}, "inputs": {}, "autopilot": {}})",
         "give either 'autopilot' or 'inputs'"},
        {R"({"track": {"spawn": [0, 1, 0]}, "inputs": {"throttle": 1.5}, "seconds": 1})",
         "Scenario.inputs.throttle must be in [-1, 1], got 1.5"},
        {R"({"track": {"spawn": [0, 1, 0]}, "inputs": {"throttle": -1.5}, "seconds": 1})",
         "Scenario.inputs.throttle must be in [-1, 1], got -1.5"},
        {R"({"track": {"spawn": [0, 1, 0]}, "inputs": {"steer": -2}, "seconds": 1})",
         "Scenario.inputs.steer must be in [-1, 1], got -2"},
        {R"({"track": {"spawn": [0, 1, 0]}, "inputs": {"gear": 2}, "seconds": 1})",
         "inputs: unknown key 'gear'"},
        {R"({"track": {"spawn": [0, 1, 0]}})", "Scenario.seconds must be > 0 in free mode"},
        {R"({"track": {"spawn": [0, 1, 0]}, "laps": 1, "seconds": 5})",
         "Scenario.laps needs the generated track"},
        {R"({"autopilot": {"target_speed_kmh": 0}})",
         "Scenario.target_speed_kmh must be in (0, 1500], got 0"},
        {R"({"autopilot": {"target_speed_kmh": 2000}})",
         "Scenario.target_speed_kmh must be in (0, 1500], got 2000"},
        {R"({"autopilot": {"speed": 200}})",
         "autopilot: unknown key 'speed' (expected one of: target_speed_kmh)"},
        {R"({"track": {"surfaces": {"grip": 1}}})",
         "track.surfaces: expected an array of surfaces"},
        {R"({"track": {"surfaces": [{"grip": 1}, {"grip": 0}]}})",
         "Scenario.surfaces[1].grip must be in (0, 10], got 0"},
        {R"({"track": {"surfaces": [{"grip": -2}]}})",
         "Scenario.surfaces[0].grip must be in (0, 10], got -2"},
        {R"({"track": {"surfaces": [{"friction": 1}]}})",
         "track.surfaces[0]: unknown key 'friction' (expected one of: grip)"},
        {R"({"track": {"surfaces": [5]}})",
         "track.surfaces[0]: expected an object, got the number 5"},
        {R"({"cars": 0})", "Scenario.cars must be in [1, 128], got 0"},
        {R"({"cars": 129})", "Scenario.cars must be in [1, 128], got 129"},
        {R"({"cars": 2, "track": {"spawn": [0, 1, 0]}, "seconds": 1})",
         "Scenario.cars: a field of 2 cars races from the generated track's grid"},
        {R"({"laps": -1})", "Scenario.laps must be in [0, 1000], got -1"},
        {R"({"laps": 5000000000})", "laps: expected a whole number in int's range"},
        {R"({"seconds": -1})", "Scenario.seconds must be in [0, 86400], got -1"},
        {R"({"seconds": "10"})", "seconds: expected a number, got the string \"10\""},
        {R"({"car": {"mass": {"mass": -1}}})",
         "scenario 's.json': car: CarSpec.mass.mass must be finite and > 0"},
        {R"({"car": {"ellipsoids": [{"center": [0, 0, 0], "role": "body"}]}})",
         "car.ellipsoids[0]: missing key 'semi_axes'"},
        {R"({"car": {"masss": {}}})", "car: unknown key 'masss'"},
        {R"({"car": 5})", "car: expected an object, got the number 5"},
        {R"({"car": ""})", "car: empty file name"},
        {R"({"duration": 10})",
         "unknown key 'duration' (expected one of: track, car, autopilot, inputs, cars, laps, "
         "seconds)"},
        {R"({"laps": 1, "laps": 2})", "duplicate key 'laps' in the top-level object"},
        {"{\"laps\": 1\n\"seconds\": 2}", "malformed JSON, parse error at line 2, column 9"},
    };
    for (const auto& [text, expected] : cases)
        EXPECT_NE(scenario_error(text).find(expected), std::string::npos)
            << "input: " << text << "\nmessage: " << scenario_error(text)
            << "\nexpected: " << expected;
}

class JsonFiles : public test::ScratchFolderTest {};

TEST_F(JsonFiles, FilesAreReadRelativeToTheScenarioAndBadFilesNamed) {
    test::write_file(file("light.json"), R"({"mass": {"mass": 800}})");
    test::write_file(file("s.json"), R"({"car": "light.json", "seconds": 3})");
    const Scenario s = load_scenario(file("s.json"));
    EXPECT_EQ(s.car.mass.mass, 800.0);
    EXPECT_EQ(s.seconds, 3.0);
    EXPECT_EQ(load_car_spec(file("light.json")).mass.mass, 800.0);

    const auto message = [](auto load) {
        try {
            load();
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    test::write_file(file("empty.json"), "");
    test::write_file(file("bad_car.json"), R"({"car": "missing.json"})");
    EXPECT_EQ(message([&] { load_car_spec(file("none.json")); }),
              "car spec '" + file("none.json").string() + "': no such file");
    EXPECT_EQ(message([&] { load_car_spec(folder_); }),
              "car spec '" + folder_.string() + "': is a folder, not a file");
    EXPECT_EQ(message([&] { load_scenario(file("empty.json")); }),
              "scenario '" + file("empty.json").string() + "': the file is empty");
    EXPECT_EQ(message([&] { load_scenario(file("bad_car.json")); }),
              "scenario '" + file("bad_car.json").string() + "': car: car spec '" +
                  file("missing.json").string() + "': no such file");
}

}  // namespace
}  // namespace trackphys
