#pragma once

#include <array>
#include <cmath>
#include <string>

#include "trackphys/error.hpp"

namespace trackphys::detail {

/// The public point-ellipse and point-ellipsoid queries in the sorted frame take radii a
/// caller may pass unsorted (an ellipsoid's semi_axes() rather than its sorted_radii()):
/// CriticalSolver's brackets assume the order and would find no root, so such a call is
/// refused, naming the function `what`, rather than answered with garbage.
template <int N>
void check_sorted_query(const char* what, const std::array<double, N>& r,
                        const std::array<double, N>& p) {
    const auto listed = [](const std::array<double, N>& v) {
        std::string text = "(";
        for (int i = 0; i < N; ++i) text += (i > 0 ? ", " : "") + exact_text(v[i]);
        return text + ")";
    };
    bool sorted = std::isfinite(r[0]) && r[N - 1] > 0.0;
    for (int i = 1; i < N; ++i) sorted = sorted && r[i - 1] >= r[i];
    if (!sorted)
        throw Error(std::string(what) + ": the radii must be finite, > 0 and sorted from the " +
                    "largest, got " + listed(r));
    for (int i = 0; i < N; ++i)
        if (!std::isfinite(p[i]))
            throw Error(std::string(what) + ": the point is not finite " + listed(p));
}

}  // namespace trackphys::detail
