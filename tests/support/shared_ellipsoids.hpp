#pragma once

#include <cstddef>

#include "trackphys/dynamics/car.hpp"

namespace trackphys::test {

/// Whether every body ellipsoid of a is the same object as b's: the two cars read one copy.
inline bool share_one_copy(const Car& a, const Car& b) {
    if (a.ellipsoid_count() != b.ellipsoid_count()) return false;
    for (std::size_t i = 0; i < a.ellipsoid_count(); ++i)
        if (&a.body_ellipsoid(i) != &b.body_ellipsoid(i)) return false;
    return true;
}

}  // namespace trackphys::test
