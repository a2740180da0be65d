// Recordings (format version 2, docs/recording.md): the header names the track mesh and
// every car's ellipsoids, each line carries every car with its suspension, inputs, laps and
// overlapping contacts, numbers read back bit for bit, and the file appears only once
// finished.
#include "trackphys/io/recording.hpp"

#include <array>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "io_test_support.hpp"
#include "support/error_message.hpp"

namespace trackphys {
namespace {

using Json = nlohmann::json;

std::vector<Json> read_lines(const std::filesystem::path& path) {
    std::istringstream in(test::read_file(path));
    std::vector<Json> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(Json::parse(line));
    return lines;
}

RecordingHeader two_car_header() {
    RecordingHeader header;
    header.dt = 0.01;
    header.scene = "a \"quoted\" scene";
    header.track_mesh = std::filesystem::path("meshes") / "track.glb";
    const CarSpec car = CarSpec::default_car();
    CarEllipsoid ball;
    ball.semi_axes = {0.5, 0.5, 0.5};
    header.car_ellipsoids = {car.ellipsoids, {ball}};
    return header;
}

class RecordingTest : public test::ScratchFolderTest {};

// A line of two_car_header's cars at rest, apart from everything.
void write_cars_at_rest(RecordingWriter& writer, double t, std::uint64_t hash,
                        std::optional<double> update_us = std::nullopt,
                        std::span<const CarPairContact> car_contacts = {}) {
    const std::vector<double> suspension(CarSpec::default_car().ellipsoids.size(), 0.0);
    const std::vector<Contact> apart(suspension.size(),
                                     Contact{-1.0, {0.0, 1.0, 0.0}, {0.0, 0.0, 0.0}});
    writer.begin_frame(t, hash, update_us);
    writer.add_car({{0.0, 1.0, 0.0}, {1.0, 0.0, 0.0, 0.0}, 0.0, suspension, apart, {}, {}, {}});
    writer.add_car({{4.0, 1.0, 0.0},
                    {1.0, 0.0, 0.0, 0.0},
                    0.0,
                    std::span(suspension).first(1),
                    std::span(apart).first(1),
                    {},
                    {},
                    {}});
    writer.end_frame(car_contacts);
}

TEST_F(RecordingTest, HeaderNamesTheTrackAndEveryCarsEllipsoids) {
    const RecordingHeader header = two_car_header();
    RecordingWriter writer(file("r.jsonl"), header);
    writer.finish();
    const std::vector<Json> lines = read_lines(file("r.jsonl"));
    ASSERT_EQ(lines.size(), 1u);
    const Json& h = lines[0];
    EXPECT_EQ(h["format"], "trackphys-recording");
    EXPECT_EQ(h["version"], 2);
    EXPECT_EQ(h["dt"], 0.01);
    EXPECT_EQ(h["cars"], 2);
    EXPECT_EQ(h["scene"], "a \"quoted\" scene");
    EXPECT_EQ(h["track"]["mesh"], "meshes/track.glb");
    ASSERT_EQ(h["car_ellipsoids"].size(), 2u);
    const std::vector<CarEllipsoid>& first = header.car_ellipsoids[0];
    ASSERT_EQ(h["car_ellipsoids"][0].size(), first.size());
    for (std::size_t i = 0; i < first.size(); ++i) {
        const Json& e = h["car_ellipsoids"][0][i];
        EXPECT_EQ(e["center"],
                  Json::array({first[i].center.x, first[i].center.y, first[i].center.z}));
        EXPECT_EQ(e["semi_axes"][1], first[i].semi_axes.y);
        EXPECT_EQ(e["role"], first[i].role == EllipsoidRole::body          ? "body"
                             : first[i].role == EllipsoidRole::front_wheel ? "front_wheel"
                                                                           : "rear_wheel");
    }
    EXPECT_EQ(h["car_ellipsoids"][1][0]["role"], "body");
}

TEST_F(RecordingTest, NoTrackMeansNoTrackKey) {
    RecordingHeader header = two_car_header();
    header.track_mesh.clear();
    RecordingWriter writer(file("r.jsonl"), header);
    writer.finish();
    EXPECT_FALSE(read_lines(file("r.jsonl"))[0].contains("track"));
}

TEST_F(RecordingTest, FramesCarryEveryCarBitForBit) {
    RecordingWriter writer(file("r.jsonl"), two_car_header());
    std::vector<double> suspension(CarSpec::default_car().ellipsoids.size(), 0.0);
    suspension[0] = 0.1 / 3.0;
    Contact touching{0.012345678901234567, {0.0, 1.0, 0.0}, {1.0 / 3.0, 2.0, -7.25}};
    Contact apart{-0.5, {0.0, 1.0, 0.0}, {0.0, 0.0, 0.0}};
    std::vector<Contact> contacts(suspension.size(), apart);
    contacts[1] = touching;
    const std::array<double, 1> ball_suspension = {0.0};
    const std::array<Contact, 1> ball_contacts = {apart};
    writer.begin_frame(0.01, 0xfedcba9876543210ull, 61.25);
    writer.add_car({{1.0 / 7.0, 2.0, 3.0},
                    {0.5, 0.5, 0.5, 0.5},
                    std::numeric_limits<double>::denorm_min(),
                    suspension,
                    contacts,
                    CarInputs{1.0, 0.25, -0.125},
                    3,
                    std::nullopt});
    writer.add_car(
        {{4.0, 5.0, 6.0}, {1.0, 0.0, 0.0, 0.0}, 20.0, ball_suspension, ball_contacts, {}, {}, {}});
    const std::array<CarPairContact, 2> car_contacts = {
        CarPairContact{0, 1, 3, 0, {0.0025 / 3.0, {0.0, 0.0, -1.0}, {1.0 / 3.0, 0.5, 2.0}}},
        CarPairContact{0, 1, 2, 0, {-0.25, {0.0, 0.0, -1.0}, {0.0, 0.0, 0.0}}}};  // apart
    writer.end_frame(car_contacts);
    write_cars_at_rest(writer, 0.02, 1);  // no update time measured
    writer.finish();

    const std::vector<Json> lines = read_lines(file("r.jsonl"));
    ASSERT_EQ(lines.size(), 3u);
    const Json& frame = lines[1];
    EXPECT_EQ(frame["t"], 0.01);
    EXPECT_EQ(frame["hash"], "fedcba9876543210");
    EXPECT_EQ(frame["us"], 61.25);
    ASSERT_EQ(frame["cars"].size(), 2u);
    const Json& car = frame["cars"][0];
    EXPECT_EQ(car["p"], Json::array({1.0 / 7.0, 2.0, 3.0}));
    EXPECT_EQ(car["q"], Json::array({0.5, 0.5, 0.5, 0.5}));
    EXPECT_EQ(car["v"].get<double>(), std::numeric_limits<double>::denorm_min());
    EXPECT_EQ(car["s"][0], 0.1 / 3.0);
    EXPECT_EQ(car["s"].size(), suspension.size());
    EXPECT_EQ(car["in"], Json::array({1.0, 0.25, -0.125}));
    EXPECT_EQ(car["lap"], 3);
    // Only the overlapping contact, tagged with its ellipsoid's index.
    ASSERT_EQ(car["contacts"].size(), 1u);
    EXPECT_EQ(car["contacts"][0],
              Json::array({1.0 / 3.0, 2.0, -7.25, 0.0, 1.0, 0.0, 0.012345678901234567, 1.0}));
    const Json& other = frame["cars"][1];
    EXPECT_FALSE(other.contains("in"));
    EXPECT_FALSE(other.contains("lap"));
    EXPECT_EQ(other["contacts"], Json::array());
    // Only the overlapping pair, after the cars.
    ASSERT_EQ(frame["car_contacts"].size(), 1u);
    EXPECT_EQ(frame["car_contacts"][0],
              Json::array({0.0, 1.0, 3.0, 0.0, 1.0 / 3.0, 0.5, 2.0, 0.0, 0.0, -1.0, 0.0025 / 3.0}));
    EXPECT_FALSE(lines[2].contains("car_contacts")) << "no key for a frame where no cars touch";
    EXPECT_FALSE(lines[2].contains("us"));
    EXPECT_EQ(lines[2]["cars"].size(), 2u);
}

TEST_F(RecordingTest, UpdateTimesAreWrittenToTheNanosecond) {
    RecordingWriter writer(file("r.jsonl"), two_car_header());
    write_cars_at_rest(writer, 0.01, 1, 61.2345678912);
    writer.finish();
    const std::string text = test::read_file(file("r.jsonl"));
    EXPECT_NE(text.find(",\"us\":61.235,"), std::string::npos) << text;
}

TEST_F(RecordingTest, AppearsOnlyWhenFinished) {
    {
        RecordingWriter writer(file("r.jsonl"), two_car_header());
        write_cars_at_rest(writer, 0.01, 1);
        EXPECT_FALSE(std::filesystem::exists(file("r.jsonl")));
    }
    EXPECT_TRUE(folder_listing().empty());
}

// A line whose cars are not the header's (another count, another number of ellipsoids) is
// refused naming the car, and the file is not put in place: a viewer would draw each car
// with another's shape.
TEST_F(RecordingTest, CarsThatAreNotTheHeadersAreRefused) {
    const auto refused = [&](const std::function<void(RecordingWriter&)>& write) {
        RecordingWriter writer(file("r.jsonl"), two_car_header());
        write_cars_at_rest(writer, 0.01, 1);
        const std::string why = test::error_of([&] { write(writer); });
        const std::string unfinished = test::error_of([&] { writer.finish(); });
        EXPECT_FALSE(std::filesystem::exists(file("r.jsonl")));
        EXPECT_NE(unfinished.find("not put in place"), std::string::npos) << unfinished;
        return why;
    };
    const std::vector<double> one(1, 0.0);
    const std::vector<Contact> none(1, Contact{-1.0, {0.0, 1.0, 0.0}, {0.0, 0.0, 0.0}});
    const RecordedCar ball{{0.0, 1.0, 0.0}, {1.0, 0.0, 0.0, 0.0}, 0.0, one, none, {}, {}, {}};
    EXPECT_NE(refused([&](RecordingWriter& w) {
                  w.begin_frame(0.02, 1);
                  w.add_car(ball);
              }).find("car 0 has 1 ellipsoids' suspension and 1 contacts, its header 8"),
              std::string::npos);
    EXPECT_NE(refused([&](RecordingWriter& w) {
                  w.begin_frame(0.02, 1);
                  w.end_frame();
              }).find("a line of 0 cars, the header's 2"),
              std::string::npos);
    // Contacts between cars name two of the header's cars, the lower first, and an
    // ellipsoid of each: the default car has 8, the ball 1.
    const Contact touching{0.001, {0.0, 0.0, 1.0}, {0.0, 1.0, 0.0}};
    for (const CarPairContact& bad :
         {CarPairContact{1, 0, 0, 0, touching}, CarPairContact{0, 0, 0, 0, touching},
          CarPairContact{0, 2, 0, 0, touching}, CarPairContact{0, 1, 8, 0, touching},
          CarPairContact{0, 1, 0, 1, touching}}) {
        const std::array<CarPairContact, 1> one_bad = {bad};
        const std::string why = refused(
            [&](RecordingWriter& w) { write_cars_at_rest(w, 0.02, 1, std::nullopt, one_bad); });
        EXPECT_NE(why.find("a contact between car " + std::to_string(bad.car_a) + "'s ellipsoid " +
                           std::to_string(bad.ellipsoid_a) + " and car " +
                           std::to_string(bad.car_b) + "'s ellipsoid " +
                           std::to_string(bad.ellipsoid_b) + ": not two of the header's cars"),
                  std::string::npos)
            << why;
    }
}

}  // namespace
}  // namespace trackphys
