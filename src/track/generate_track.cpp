#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

#include "track/road_profile.hpp"
#include "track/track_mesher.hpp"
#include "track/track_shape.hpp"
#include "trackphys/track/track.hpp"

namespace trackphys {

std::size_t Track::triangle_count() const {
    std::size_t count = 0;
    for (const TrackChunk& chunk : chunks) count += chunk.mesh.triangles.size();
    return count;
}

std::size_t Track::road_triangle_count() const {
    std::size_t count = 0;
    for (const TrackChunk& chunk : chunks) count += chunk.road_triangle_count;
    return count;
}

namespace {

// The road frame at one row. Unbanked, left_flat = normalize(+Y x tangent) is horizontal
// and up_flat = tangent x left_flat is the road normal; banking by b rotates both about the
// tangent so that for b > 0 the left edge goes down (the inside of a left turn):
//     left = cos b left_flat - sin b up_flat,   up = sin b left_flat + cos b up_flat,
// which keeps left = up x tangent.
CenterlineSample make_sample(const track_detail::BezierLoop::Point& point, double distance,
                             double bank) {
    CenterlineSample sample;
    sample.position = point.position;
    sample.tangent = point.tangent;
    const glm::dvec3 left_flat = glm::normalize(glm::dvec3(point.tangent.z, 0.0, -point.tangent.x));
    const glm::dvec3 up_flat = glm::cross(point.tangent, left_flat);
    sample.left = std::cos(bank) * left_flat - std::sin(bank) * up_flat;
    sample.up = std::sin(bank) * left_flat + std::cos(bank) * up_flat;
    sample.curvature = point.horizontal_curvature;
    sample.bank = bank;
    sample.distance = distance;
    return sample;
}

}  // namespace

Track generate_track(const TrackParams& params) {
    validate_track_params(params);
    track_detail::TrackShape shape = track_detail::make_track_shape(params);
    const track_detail::RoadProfile profile = track_detail::make_road_profile(shape.loop, params);

    Track track;
    track.params = params;
    track.length_m = shape.loop.length();
    track.bezier_segment_count = shape.loop.segment_count();
    track.rejected_shapes = shape.rejected;
    track.centerline.reserve(profile.row_distance.size());
    for (const double s : profile.row_distance)
        track.centerline.push_back(make_sample(shape.loop.at(s), s, profile.bank_at(s)));
    track.chunks = track_detail::build_chunks(track.centerline, track.length_m, params);
    return track;
}

}  // namespace trackphys
