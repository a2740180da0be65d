// Vehicle telemetry in recordings (docs/recording.md): a car with a vehicle model carries
// its engine speed, gear and each wheel's slip ratio, slip angle, load and spin in every
// frame, equal to what its Vehicle reported after that update; an arcade car carries none,
// so its lines stay as they were.
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "io_test_support.hpp"
#include "support/error_message.hpp"
#include "trackphys/io/recording.hpp"
#include "trackphys/world/spawn.hpp"
#include "trackphys/world/world.hpp"
#include "world/world_scenes.hpp"

namespace trackphys {
namespace {

using Json = nlohmann::json;

// What the recording must say of a vehicle car after one update.
struct ExpectedVehicle {
    double rpm = 0.0;
    int gear = 0;
    std::vector<WheelTelemetry> wheels;
};

// Telemetry is written with 9 significant digits: a relative error of at most 5e-9.
void expect_telemetry(const Json& written, double value, const std::string& what) {
    ASSERT_TRUE(written.is_number()) << what;
    EXPECT_NEAR(written.get<double>(), value, 5e-9 * std::abs(value)) << what;
}

class RecordingVehicleTest : public test::ScratchFolderTest {};

TEST_F(RecordingVehicleTest, EveryFrameCarriesTheVehicleStateOfThatUpdate) {
    // A gt car accelerating out of a turn (4 s: into second gear) beside an arcade car.
    World world(test::static_world_of(test::flat_grid(400.0, 40)));
    const glm::dquat facing_z(1.0, 0.0, 0.0, 0.0);
    const CarSpec gt = CarSpec::preset("gt");
    const CarSpec arcade = CarSpec::default_car();
    world.add_car(gt, place_car_on_surface(world.statics(), gt, {0.0, 5.0, -150.0}, facing_z));
    world.add_car(arcade,
                  place_car_on_surface(world.statics(), arcade, {10.0, 5.0, -150.0}, facing_z));
    RecordingHeader header;
    header.car_ellipsoids = {gt.ellipsoids, arcade.ellipsoids};

    std::vector<ExpectedVehicle> expected;
    {
        RecordingWriter writer(file("r.jsonl"), header);
        for (int update = 0; update < 400; ++update) {
            world.car(0).set_inputs({1.0, 0.0, update < 100 ? 0.5 : 0.0});
            world.car(1).set_inputs({1.0, 0.0, 0.0});
            world.update();
            writer.write_frame(world);
            const Vehicle& vehicle = *world.car(0).vehicle();
            expected.push_back({vehicle.engine_rpm(),
                                vehicle.state().gear,
                                {vehicle.telemetry().begin(), vehicle.telemetry().end()}});
        }
        writer.finish();
    }

    std::istringstream in(test::read_file(file("r.jsonl")));
    std::string line;
    std::getline(in, line);  // the header
    std::size_t frames = 0;
    bool shifted = false, slipped = false;
    for (; std::getline(in, line); ++frames) {
        ASSERT_LT(frames, expected.size());
        const Json frame = Json::parse(line);
        const ExpectedVehicle& want = expected[frames];
        const std::string at = "frame " + std::to_string(frames);
        EXPECT_FALSE(frame["cars"][1].contains("vehicle")) << at << ": the arcade car";
        const Json& vehicle = frame["cars"][0]["vehicle"];
        ASSERT_TRUE(vehicle.is_object()) << at;
        expect_telemetry(vehicle["rpm"], want.rpm, at + " rpm");
        EXPECT_EQ(vehicle["gear"], want.gear) << at;
        ASSERT_EQ(vehicle["wheels"].size(), want.wheels.size()) << at;
        for (std::size_t w = 0; w < want.wheels.size(); ++w) {
            const Json& wheel = vehicle["wheels"][w];
            const WheelTelemetry& t = want.wheels[w];
            const std::string of = at + " wheel " + std::to_string(w);
            ASSERT_EQ(wheel.size(), 4u) << of;
            expect_telemetry(wheel[0], t.slip_ratio, of + " slip ratio");
            expect_telemetry(wheel[1], std::atan(t.lateral_slip) * 180.0 / std::numbers::pi,
                             of + " slip angle (deg)");
            expect_telemetry(wheel[2], t.load, of + " load");
            expect_telemetry(wheel[3], t.spin, of + " spin");
            slipped = slipped || std::abs(wheel[1].get<double>()) > 1.0;
        }
        shifted = shifted || want.gear > 1;
    }
    EXPECT_EQ(frames, expected.size());
    // The drive exercised what is recorded: a gear change, a turn's slip angles.
    EXPECT_TRUE(shifted) << "the gt car never left first gear";
    EXPECT_TRUE(slipped) << "no wheel reached a 1 degree slip angle";
    EXPECT_GT(expected.back().rpm, 1000.0);
    EXPECT_GT(expected.back().wheels[0].load, 1000.0);
}

TEST_F(RecordingVehicleTest, VehicleComesAfterTheContactsWithNineDigits) {
    RecordingHeader header;
    header.car_ellipsoids = {CarSpec::default_car().ellipsoids};
    const std::vector<WheelTelemetry> wheels = {{0.125, std::tan(0.1), 4000.0, 55.5},
                                                {-0.5, 0.0, 0.0, -1.0}};
    {
        RecordingWriter writer(file("r.jsonl"), header);
        writer.begin_frame(0.01, 1);
        const std::vector<double> suspension(header.car_ellipsoids[0].size(), 0.0);
        RecordedCar car;
        car.suspension = suspension;
        car.vehicle = RecordedVehicle{7123.456789012, 4, wheels};
        writer.add_car(car);
        writer.end_frame();
        writer.finish();
    }
    std::istringstream in(test::read_file(file("r.jsonl")));
    std::string header_line, line;
    std::getline(in, header_line);
    std::getline(in, line);
    EXPECT_NE(line.find("\"contacts\":[],\"vehicle\":{\"rpm\":7123.45679,\"gear\":4,"),
              std::string::npos)
        << line;
    const Json frame = Json::parse(line);
    const Json& vehicle = frame["cars"][0]["vehicle"];
    EXPECT_EQ(vehicle["wheels"][0], Json::array({0.125, 5.72957795, 4000.0, 55.5}));
    EXPECT_EQ(vehicle["wheels"][1], Json::array({-0.5, 0.0, 0.0, -1.0}));
}

// write_frame checks the world's cars against the header before the line starts: a world
// of two cars under a one-car header writes nothing and leaves the file good to finish.
TEST_F(RecordingVehicleTest, AWorldWhoseCarsAreNotTheHeadersWritesNothing) {
    World world(test::static_world_of(test::flat_grid(400.0, 40)));
    const CarSpec arcade = CarSpec::default_car();
    for (const double x : {0.0, 10.0})
        world.add_car(arcade, place_car_on_surface(world.statics(), arcade, {x, 5.0, -150.0},
                                                   glm::dquat(1.0, 0.0, 0.0, 0.0)));
    world.update();
    RecordingHeader header;
    header.car_ellipsoids = {arcade.ellipsoids};
    RecordingWriter writer(file("r.jsonl"), header);
    const std::string why = test::error_of([&] { writer.write_frame(world); });
    EXPECT_NE(why.find("the world's 2 cars are not the header's 1"), std::string::npos) << why;
    writer.finish();
    std::istringstream in(test::read_file(file("r.jsonl")));
    std::string line;
    int lines = 0;
    while (std::getline(in, line)) ++lines;
    EXPECT_EQ(lines, 1) << "the header only";
}

}  // namespace
}  // namespace trackphys
