#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "trackphys/error.hpp"
#include "trackphys/world/world_settings.hpp"

namespace trackphys {
namespace {

TEST(ExactText, ShowsTheShortestTextOfTheDouble) {
    EXPECT_EQ(exact_text(0.1), "0.1");
    EXPECT_EQ(exact_text(10.0000001), "10.0000001");
    EXPECT_EQ(exact_text(2.0), "2");
    EXPECT_EQ(exact_text(-1e-9), "-1e-09");
    EXPECT_EQ(exact_text(1e300), "1e+300");
    EXPECT_EQ(exact_text(-0.0), "-0");
    EXPECT_EQ(exact_text(std::numeric_limits<double>::infinity()), "inf");
    EXPECT_EQ(exact_text(-std::numeric_limits<double>::infinity()), "-inf");
    EXPECT_EQ(exact_text(std::numeric_limits<double>::quiet_NaN()), "nan");
}

TEST(ExactText, ReadsBackAsTheSameDouble) {
    std::mt19937_64 bits(15);
    for (int i = 0; i < 100000; ++i) {
        double x;
        const std::uint64_t word = bits();
        std::memcpy(&x, &word, sizeof x);
        if (!std::isfinite(x)) continue;
        const std::string text = exact_text(x);
        EXPECT_EQ(std::strtod(text.c_str(), nullptr), x) << text;
    }
    EXPECT_EQ(exact_text(std::numeric_limits<double>::denorm_min()), "5e-324");
    EXPECT_EQ(exact_text(-std::numeric_limits<double>::min()), "-2.2250738585072014e-308");
}

// A value just past a bound used to read as the bound: "must be in (0, 1] s, got 1".
TEST(ExactText, ValidationMessagesShowTheValueGiven) {
    WorldSettings settings;
    settings.dt_update = std::nextafter(1.0, 2.0);
    EXPECT_NE(settings.validate().find("got 1.0000000000000002"), std::string::npos)
        << settings.validate();
}

TEST(QuotedText, EscapesControlCharactersAndShortensLongText) {
    EXPECT_EQ(quoted_text("road"), "'road'");
    EXPECT_EQ(quoted_text(std::string("a\0b\x1b[2J\x7f\n", 9)), "'a\\x00b\\x1b[2J\\x7f\\x0a'");
    EXPECT_EQ(quoted_text("stra\xc3\x9f\x65"), "'stra\xc3\x9f\x65'");  // UTF-8 kept
    const std::string long_name(300, 'x');
    EXPECT_EQ(quoted_text(long_name),
              "'" + std::string(120, 'x') + "' (the first 120 of 300 bytes)");
    // A cut never splits a UTF-8 sequence: 119 ASCII bytes, then a 2-byte letter across 120.
    const std::string across = std::string(119, 'x') + "\xc3\x9f" + std::string(10, 'y');
    EXPECT_EQ(quoted_text(across), "'" + std::string(119, 'x') + "' (the first 119 of 131 bytes)");
    // Bytes that are no UTF-8 at all are cut no more than a sequence would be.
    EXPECT_EQ(quoted_text(std::string(200, '\x80')).size(),
              2 + 117 + std::string(" (the first 117 of 200 bytes)").size());
}

}  // namespace
}  // namespace trackphys
