#pragma once

#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

namespace trackphys::track_detail {

/// A closed loop of cubic Bezier segments through points P_0 .. P_{n-1} (segment i runs
/// from P_i to P_{i+1}, the last one back to P_0) with an arc-length parametrisation.
///
/// Segment i has the control points P_i, P_i + T_i / 3, P_{i+1} - T_{i+1} / 3, P_{i+1}, so
/// its derivative (in its own parameter t in [0, 1]) is T_i at the start and T_{i+1} at
/// the end: both segments meeting at P_i have the derivative T_i there, which makes the
/// loop C1 whatever the tangents are. The tangents are Catmull-Rom's, T_i = (P_{i+1} -
/// P_{i-1}) / 2.
///
/// Arc length: each segment is cut into kSubintervals equal parameter intervals, each
/// integrated with 8-point Gauss-Legendre (the speed |B'(t)| is smooth there, so this is
/// near machine precision); s -> t inverts that with safeguarded Newton.
class BezierLoop {
  public:
    /// Position, derivatives with respect to arc length (unit tangent d1 and curvature
    /// vector d2) at some distance along the loop.
    struct Point {
        glm::dvec3 position{0.0};
        glm::dvec3 tangent{0.0};
        /// Signed curvature of the curve's top view (x, z), > 0 turning left, where left =
        /// +Y x tangent (1/m).
        double horizontal_curvature = 0.0;
    };

    /// points: at least 3, consecutive ones distinct.
    explicit BezierLoop(std::vector<glm::dvec3> points);

    double length() const { return cumulative_.back(); }
    std::size_t segment_count() const { return points_.size(); }
    const std::vector<glm::dvec3>& points() const { return points_; }

    /// The curve at arc length s, taken modulo length(); s = length() gives exactly the
    /// start point P_0.
    Point at(double s) const;

    /// Segment i's position, first and second derivative at parameter t (t in [0, 1]).
    glm::dvec3 segment_position(std::size_t i, double t) const;
    glm::dvec3 segment_derivative(std::size_t i, double t) const;
    glm::dvec3 segment_second_derivative(std::size_t i, double t) const;
    /// Segment i's signed top-view curvature at t (1/m, > 0 turning left; see Point).
    double segment_horizontal_curvature(std::size_t i, double t) const;

    /// Parameter of arc length s (in [0, length()]): the segment and t in [0, 1].
    void locate(double s, std::size_t& segment, double& t) const;

    static constexpr int kSubintervals = 32;

  private:
    /// Arc length of segment i between parameters a and b (Gauss-Legendre, 8 points).
    double arc_length(std::size_t i, double a, double b) const;

    std::vector<glm::dvec3> points_;
    std::vector<glm::dvec3> tangents_;
    /// cumulative_[i * kSubintervals + k]: arc length from the start to subinterval k of
    /// segment i; the last entry is the total length.
    std::vector<double> cumulative_;
};

}  // namespace trackphys::track_detail
