#pragma once

#include <cmath>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

namespace trackphys::detail {

/// Internal to Car's sub-step. A body's forward (+Z), up (+Y) and down (-Y) axes in the
/// world: bit for bit glm's products orientation * (0, 0, 1), orientation * (0, 1, 0) and
/// orientation * (0, -1, 0), which a car's sub-step needs for its wheels, suspension and
/// downforce.
struct BodyAxes {
    glm::dvec3 forward;
    glm::dvec3 up;
    glm::dvec3 down;

    explicit BodyAxes(const glm::dquat& q) {
        const double x = q.x, y = q.y, z = q.z, w = q.w;
        // glm rotates v as v + (uv w + uuv) 2, uv = (x, y, z) x v and uuv = (x, y, z) x uv,
        // and multiplies by the axis's zeros too. With x, y, z and w finite, each product by a
        // zero is a zero, so every value glm forms has this code's bits or is a zero of the
        // other sign (adding a zero to a non-zero or multiplying it keeps that), and the
        // axis's own 0 + or 1 + at the end of each component drops a zero's sign; down is
        // then 0 - up (rounding is symmetric, and 0 - 0 gives glm's +0). A component not
        // finite makes glm's product by a zero a NaN: glm's products.
        if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(z) && std::isfinite(w)))
            [[unlikely]] {
            *this = glms_products(q);
            return;
        }
        const double xz = x * z, zy = z * y, yx = y * x;
        // Forward: uv = (y, -x, 0), uuv = (x z, z y, x (-x) - y y).
        forward = {0.0 + (y * w + xz) * 2.0, 0.0 + (-x * w + zy) * 2.0,
                   1.0 + (x * -x - y * y) * 2.0};
        // Up: uv = (-z, 0, x), uuv = (y x, z (-z) - x x, z y).
        up = {0.0 + (-z * w + yx) * 2.0, 1.0 + (z * -z - x * x) * 2.0, 0.0 + (x * w + zy) * 2.0};
        down = glm::dvec3(0.0) - up;
    }

  private:
    BodyAxes() = default;
    // Out of the way of the sub-step's code, which takes it only for a state not finite.
    [[gnu::cold, gnu::noinline]] static BodyAxes glms_products(const glm::dquat& q) {
        BodyAxes axes;
        axes.forward = q * glm::dvec3(0.0, 0.0, 1.0);
        axes.up = q * glm::dvec3(0.0, 1.0, 0.0);
        axes.down = q * glm::dvec3(0.0, -1.0, 0.0);
        return axes;
    }
};

}  // namespace trackphys::detail
