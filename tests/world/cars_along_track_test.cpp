// The race's nearest car in a lane from the field in track order, against a scan of every
// car (the rule as RaceDrivers read it before the field was ordered).
#include "world/cars_along_track.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace trackphys::detail {
namespace {

CarInLane every_car_scanned(const std::vector<RoadPosition>& positions, std::size_t i,
                            const LaneQuery& query) {
    CarInLane nearest{i, std::numeric_limits<double>::infinity()};
    for (std::size_t j = 0; j < positions.size(); ++j) {
        if (j == i) continue;
        if (std::abs(positions[j].across - query.line) > query.width) continue;
        const double gap =
            gap_along(positions[i].along, positions[j].along, query.from, query.length);
        if (gap > query.look_ahead || !(gap < nearest.gap)) continue;
        nearest = {j, gap};
    }
    return nearest;
}

// A field as the race reads it: along at one of a centreline's samples (so cars share
// places, and the gaps tie), across in or between the two lanes.
struct RandomField {
    std::mt19937 random;
    double length;
    std::vector<double> samples;

    RandomField(unsigned seed, double length_m, std::size_t sample_count)
        : random(seed), length(length_m) {
        for (std::size_t k = 0; k < sample_count; ++k)
            samples.push_back(length * double(k) / double(sample_count));
    }
    RoadPosition car() {
        std::uniform_int_distribution<std::size_t> sample(0, samples.size() - 1);
        std::uniform_int_distribution<int> lane(0, 2);
        std::uniform_real_distribution<double> off(-1.5, 1.5);
        const double across = (lane(random) - 1) * 2.0 + (lane(random) == 0 ? off(random) : 0.0);
        return {across, samples[sample(random)]};
    }
};

// Every car of random fields on short and long loops (the gaps wrap near both ends of the
// order), bunched on few samples or spread on many, asks every query the race asks.
TEST(CarsAlongTrack, TheNearestCarAheadIsTheOneEveryCarScannedFinds) {
    int found = 0, none = 0, tied = 0;
    unsigned seed = 1;
    for (const double length : {61.0, 250.0, 3200.0}) {
        for (const std::size_t sample_count : {7, 40, 1600}) {
            for (const std::size_t cars : {1, 2, 5, 20, 64, 128}) {
                RandomField field(seed++, length, sample_count);
                std::vector<RoadPosition> positions;
                for (std::size_t c = 0; c < cars; ++c) positions.push_back(field.car());
                std::vector<std::uint32_t> order;
                order_along_track(positions, order);
                for (std::size_t i = 0; i < cars; ++i) {
                    for (const double from : {-20.0, -6.0, 1.0}) {
                        for (const double line : {-2.0, 2.0, 0.7}) {
                            const LaneQuery query{line, 2.5, from, 60.0, length};
                            const CarInLane fast = nearest_car_ahead(positions, order, i, query);
                            const CarInLane slow = every_car_scanned(positions, i, query);
                            ASSERT_EQ(fast.car, slow.car) << "car " << i << " of " << cars;
                            ASSERT_EQ(fast.gap, slow.gap);
                            if (slow.car == i) {
                                ++none;
                                continue;
                            }
                            ++found;
                            for (std::size_t j = 0; j < cars; ++j)
                                if (j != slow.car && j != i &&
                                    positions[j].along == positions[slow.car].along &&
                                    std::abs(positions[j].across - line) <= 2.5)
                                    ++tied;
                        }
                    }
                }
            }
        }
    }
    // The fields asked both kinds of answer and ties of index.
    EXPECT_GT(found, 1000);
    EXPECT_GT(none, 1000);
    EXPECT_GT(tied, 1000);
}

// Where other - me - from is exactly -length or +length, gap_along's remainder is a zero
// (-0 and +0): such a car is at `from`, the nearest a lane can hold, and must sit in the run
// that starts there, not at the end of the run before it, where the reading stops before it.
// A power-of-two loop with places on sixteenths of it lands there exactly (+length from
// -1/16 of a lap: me 0, other 15/16; -length from +1/16: me 15/16, other 0), which the
// random fields above, on 61, 250 and 3200 m, never do. From -1/16 and +1/16 a boundary car
// is alone past its boundary; from -1/2 and +1/2 cars lie on both sides of it, so a car put
// in the wrong run has cars before it there.
TEST(CarsAlongTrack, ACarExactlyALapFromTheQuerysStartIsFoundAsInTheScan) {
    int at_minus_length = 0, at_plus_length = 0;
    unsigned seed = 1000;
    for (const double length : {64.0, 4096.0}) {
        for (const std::size_t cars : {2, 3, 5, 12, 40}) {
            for (int field_count = 0; field_count < 40; ++field_count) {
                RandomField field(seed++, length, 16);
                std::vector<RoadPosition> positions;
                for (std::size_t c = 0; c < cars; ++c) positions.push_back(field.car());
                std::vector<std::uint32_t> order;
                order_along_track(positions, order);
                for (std::size_t i = 0; i < cars; ++i) {
                    for (const double from :
                         {-length / 2.0, -length / 16.0, 0.0, length / 16.0, length / 2.0}) {
                        // Gaps are in [from, from + length).
                        for (const double look_ahead : {from + length / 8.0, from + length / 2.0,
                                                        std::numeric_limits<double>::infinity()}) {
                            for (const double line : {-2.0, 2.0, 0.7}) {
                                const LaneQuery query{line, 2.5, from, look_ahead, length};
                                const CarInLane fast =
                                    nearest_car_ahead(positions, order, i, query);
                                const CarInLane slow = every_car_scanned(positions, i, query);
                                ASSERT_EQ(fast.car, slow.car)
                                    << "car " << i << " of " << cars << ", from " << from;
                                ASSERT_EQ(fast.gap, slow.gap);
                                if (slow.car == i) continue;
                                const double d =
                                    positions[slow.car].along - positions[i].along - from;
                                if (d == -length) ++at_minus_length;
                                if (d == length) ++at_plus_length;
                            }
                        }
                    }
                }
            }
        }
    }
    // Both boundaries held the nearest car, many times.
    EXPECT_GT(at_minus_length, 100);
    EXPECT_GT(at_plus_length, 100);
}

// Two places a rounding apart ahead of a car near the end of the lap: their gaps round to
// one value, and the lower index wins the tie, as in a scan of every car, though the order
// along the track reads the other first.
TEST(CarsAlongTrack, APlaceTiedByRoundingGoesToTheLowerIndex) {
    const double length = 3200.0;
    const std::vector<RoadPosition> positions{
        {0.0, std::nextafter(20.0, 21.0)}, {0.0, 20.0}, {0.0, 3190.0}};
    std::vector<std::uint32_t> order;
    order_along_track(positions, order);
    ASSERT_EQ(order, (std::vector<std::uint32_t>{1, 0, 2}));
    const LaneQuery query{0.0, 2.5, 1.0, 60.0, length};
    ASSERT_EQ(gap_along(3190.0, positions[0].along, 1.0, length),
              gap_along(3190.0, positions[1].along, 1.0, length));
    EXPECT_EQ(every_car_scanned(positions, 2, query).car, 0u);
    EXPECT_EQ(nearest_car_ahead(positions, order, 2, query).car, 0u);
}

// A car moved along (a step or two, or across the start line) keeps the order a sort would
// give, and the answers with it.
TEST(CarsAlongTrack, AMovedCarTakesItsPlaceInTheOrder) {
    RandomField field(99, 400.0, 80);
    std::vector<RoadPosition> positions;
    for (int c = 0; c < 64; ++c) positions.push_back(field.car());
    std::vector<std::uint32_t> order, sorted;
    order_along_track(positions, order);
    std::uniform_int_distribution<std::size_t> any_car(0, positions.size() - 1);
    std::uniform_int_distribution<int> step(-3, 3);
    for (int move = 0; move < 2000; ++move) {
        const std::size_t car = any_car(field.random);
        const double along = positions[car].along;
        const auto sample = static_cast<long>(std::lround(along / 5.0)) + step(field.random);
        positions[car].along = field.samples[static_cast<std::size_t>((sample + 80) % 80)];
        reorder_moved_car(positions, order, car, along);
        order_along_track(positions, sorted);
        ASSERT_EQ(order, sorted) << "move " << move;
        const LaneQuery query{2.0, 2.5, -6.0, 60.0, 400.0};
        ASSERT_EQ(nearest_car_ahead(positions, order, car, query).car,
                  every_car_scanned(positions, car, query).car);
    }
}

}  // namespace
}  // namespace trackphys::detail
