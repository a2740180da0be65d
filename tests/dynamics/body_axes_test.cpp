#include "dynamics/body_axes.hpp"

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include <glm/gtc/quaternion.hpp>

namespace trackphys {
namespace {

// Bits, not values, but any NaN for a NaN: which operand's NaN a sum passes on depends on
// the order the compiler gives its operands, not on the law.
bool same_bits_or_both_nan(const glm::dvec3& a, const glm::dvec3& b) {
    for (int c = 0; c < 3; ++c)
        if (std::isnan(a[c]) ? !std::isnan(b[c]) : std::memcmp(&a[c], &b[c], sizeof(double)) != 0)
            return false;
    return true;
}

// BodyAxes leaves out glm's products by the axes' zeros only where they cannot change a
// bit: every quaternion, with zero components of either sign (a car standing level),
// components whose products cancel or underflow, and ones not finite, must give glm's bits.
TEST(BodyAxes, GiveTheBitsOfGlmsProducts) {
    std::mt19937_64 rng(13);
    std::normal_distribution<double> normal;
    std::uniform_int_distribution<int> pick(0, 15);
    const double inf = std::numeric_limits<double>::infinity();
    const std::array<double, 12> special = {0.0,    -0.0,  0.5,     -0.5, 1e-170, -1e-170,
                                            1e-300, 1e-20, -1e-200, inf,  -inf,   std::nan("")};
    for (int trial = 0; trial < 200000; ++trial) {
        std::array<double, 4> q;
        const int kind = trial % 4;
        for (int c = 0; c < 4; ++c) {
            const int p = pick(rng);
            // Gaussian components, some replaced by special values (a quarter of the trials
            // are only +-0.5 and zeros, whose products cancel to zeros exactly).
            if (kind == 0 || (kind == 1 && p < 12))
                q[c] = normal(rng);
            else if (kind == 2)
                q[c] = special[static_cast<std::size_t>(p % 6)];
            else
                q[c] = p < 12 ? special[static_cast<std::size_t>(p)] : normal(rng);
        }
        glm::dquat rotation(q[0], q[1], q[2], q[3]);
        if (kind < 2) rotation = glm::normalize(rotation);
        const detail::BodyAxes axes(rotation);
        ASSERT_TRUE(same_bits_or_both_nan(axes.forward, rotation * glm::dvec3(0.0, 0.0, 1.0)))
            << "trial " << trial;
        ASSERT_TRUE(same_bits_or_both_nan(axes.up, rotation * glm::dvec3(0.0, 1.0, 0.0)))
            << "trial " << trial;
        ASSERT_TRUE(same_bits_or_both_nan(axes.down, rotation * glm::dvec3(0.0, -1.0, 0.0)))
            << "trial " << trial;
    }
}

// A car standing level, or pitched or rolled only, has zeros in its quaternion; components
// so large that their products overflow are still finite. Both take the short products.
TEST(BodyAxes, GiveTheBitsOfGlmsProductsForZerosAndOverflow) {
    const std::array<double, 4> zeros = {0.0, -0.0, 0.0, -0.0};
    int checked = 0;
    for (int axis = 0; axis < 3; ++axis)
        for (int step = -8; step <= 8; ++step)
            for (int signs = 0; signs < 16; ++signs) {
                const double half = 0.19634954084936207 * step;  // pi / 16 a step
                std::array<double, 4> q = {std::cos(half), zeros[signs % 4], zeros[signs / 4],
                                           zeros[(signs + 1) % 4]};
                q[static_cast<std::size_t>(axis) + 1] = std::sin(half);
                if (step == 0) q[static_cast<std::size_t>(axis) + 1] = zeros[signs % 2];
                for (const double w_sign : {1.0, -1.0}) {
                    const glm::dquat rotation(w_sign * q[0], q[1], q[2], q[3]);
                    const detail::BodyAxes axes(rotation);
                    ASSERT_TRUE(
                        same_bits_or_both_nan(axes.forward, rotation * glm::dvec3(0.0, 0.0, 1.0)))
                        << axis << " " << step << " " << signs;
                    ASSERT_TRUE(
                        same_bits_or_both_nan(axes.up, rotation * glm::dvec3(0.0, 1.0, 0.0)))
                        << axis << " " << step << " " << signs;
                    ASSERT_TRUE(
                        same_bits_or_both_nan(axes.down, rotation * glm::dvec3(0.0, -1.0, 0.0)))
                        << axis << " " << step << " " << signs;
                    ++checked;
                }
            }
    EXPECT_EQ(checked, 3 * 17 * 16 * 2);
    const std::array<double, 5> large = {1e200, -1e200, 1e160, -3e155, 1.7976931348623157e308};
    for (std::size_t a = 0; a < large.size(); ++a)
        for (std::size_t b = 0; b < large.size(); ++b) {
            const glm::dquat rotation(large[a], large[b], large[(a + b) % 5], large[(a + 2) % 5]);
            const detail::BodyAxes axes(rotation);
            ASSERT_TRUE(same_bits_or_both_nan(axes.forward, rotation * glm::dvec3(0.0, 0.0, 1.0)))
                << a << b;
            ASSERT_TRUE(same_bits_or_both_nan(axes.up, rotation * glm::dvec3(0.0, 1.0, 0.0)))
                << a << b;
            ASSERT_TRUE(same_bits_or_both_nan(axes.down, rotation * glm::dvec3(0.0, -1.0, 0.0)))
                << a << b;
        }
}

}  // namespace
}  // namespace trackphys
