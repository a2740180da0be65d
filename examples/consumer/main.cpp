// Builds against an installed trackphys: one include, one target.
#include <cstdio>

#include <trackphys/trackphys.hpp>

int main() {
    const trackphys::Triangle road({0.0, 0.0, 0.0}, {0.0, 0.0, -4.0}, {4.0, 0.0, 0.0});
    const trackphys::NormalizedTriangle normalized(road);
    const trackphys::Ellipsoid wheel({1.0, 0.3, -1.0}, glm::dquat(1.0, 0.0, 0.0, 0.0),
                                     {0.35, 0.35, 0.15});

    const bool maybe = normalized.may_touch_sphere(wheel.center(), wheel.bounding_radius());
    std::printf("road normal (%.1f, %.1f, %.1f), wheel may touch: %s\n", normalized.normal.x,
                normalized.normal.y, normalized.normal.z, maybe ? "yes" : "no");
    return maybe ? 0 : 1;
}
