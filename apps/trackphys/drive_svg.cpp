#include "drive_svg.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <tuple>
#include <vector>

#include "trackphys/error.hpp"
#include "trackphys/profile/profile_statistics.hpp"

namespace trackphys::cli {
namespace {

constexpr double kPanelWidth = 900.0;
constexpr double kMapHeight = 700.0;
constexpr double kChartHeight = 260.0;
constexpr double kMargin = 50.0;
// Line segments drawn over all paths, at most: every point of a lap, every few of a race.
constexpr std::size_t kMaxSegments = 50000;

// Blue (slow) to red (fast).
std::string speed_colour(double t) {
    t = std::clamp(t, 0.0, 1.0);
    std::ostringstream c;
    c << "rgb(" << static_cast<int>(40 + 215 * t) << ','
      << static_cast<int>(90 + 60 * (1 - std::abs(2 * t - 1))) << ','
      << static_cast<int>(220 - 190 * t) << ')';
    return c.str();
}

struct Frame {  // world (x, z) -> map pixels, z down as seen from above
    double min_x, min_z, scale;
    double x(const glm::dvec3& p) const { return kMargin + (p.x - min_x) * scale; }
    double y(const glm::dvec3& p) const { return kMargin + 30 + (p.z - min_z) * scale; }
};

}  // namespace

void write_drive_svg(const DrivePlot& plot, const std::optional<Track>& track,
                     const std::filesystem::path& path) {
    // Map extent: the path, and the road edges when there is a track.
    std::vector<glm::dvec3> left, right;
    if (track) {
        const double half = 0.5 * track->params.width_m;
        for (const CenterlineSample& s : track->centerline) {
            left.push_back(s.position + half * s.left);
            right.push_back(s.position - half * s.left);
        }
    }
    double min_x = 1e300, max_x = -1e300, min_z = 1e300, max_z = -1e300;
    std::vector<const std::vector<glm::dvec3>*> extent{&left, &right};
    std::size_t points = 0;
    for (const PlotPath& car : plot.paths) {
        extent.push_back(&car.points);
        points += car.points.size();
    }
    for (const std::vector<glm::dvec3>* from : extent)
        for (const glm::dvec3& p : *from) {
            min_x = std::min(min_x, p.x), max_x = std::max(max_x, p.x);
            min_z = std::min(min_z, p.z), max_z = std::max(max_z, p.z);
        }
    if (!(max_x >= min_x)) min_x = max_x = min_z = max_z = 0.0;
    const double span = std::max({max_x - min_x, max_z - min_z, 1.0});
    const Frame frame{min_x, min_z,
                      std::min((kPanelWidth - 2 * kMargin) / span, kMapHeight / span)};
    const double chart_top = kMargin + 30 + (max_z - min_z) * frame.scale + 60;
    const double height = chart_top + kChartHeight + 60;

    std::ostringstream svg;
    svg.setf(std::ios::fixed);
    svg.precision(1);
    svg << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" "
           "width=\""
        << kPanelWidth << "\" height=\"" << height << "\" font-family=\"sans-serif\">\n"
        << "<rect width=\"100%\" height=\"100%\" fill=\"#f7f7f2\"/>\n"
        << "<text x=\"" << kMargin << "\" y=\"30\" font-size=\"18\">trackphys " << plot.command
        << ": path coloured by speed "
        << "(blue slow, red fast), top view x right, z down</text>\n";
    for (const auto* edge : {&left, &right}) {
        if (edge->empty()) continue;
        svg << "<polygon fill=\"none\" stroke=\"#888\" stroke-width=\"1\" points=\"";
        for (const glm::dvec3& p : *edge) svg << frame.x(p) << ',' << frame.y(p) << ' ';
        svg << "\"/>\n";
    }
    double top_speed = 1.0;
    for (const PlotPath& car : plot.paths)
        for (const double kmh : car.speed_kmh) top_speed = std::max(top_speed, kmh);
    const std::size_t stride = std::max<std::size_t>(1, (points + kMaxSegments - 1) / kMaxSegments);
    for (const PlotPath& car : plot.paths)
        for (std::size_t i = stride; i < car.points.size(); i += stride)
            svg << "<line x1=\"" << frame.x(car.points[i - stride]) << "\" y1=\""
                << frame.y(car.points[i - stride]) << "\" x2=\"" << frame.x(car.points[i])
                << "\" y2=\"" << frame.y(car.points[i]) << "\" stroke=\""
                << speed_colour(car.speed_kmh[i] / top_speed) << "\" stroke-width=\"2\"/>\n";
    svg << "<text x=\"" << kMargin << "\" y=\"" << chart_top - 25
        << "\" font-size=\"12\">top speed " << top_speed << " km/h</text>\n";

    // Update-time chart on a log scale (1 us .. the largest), with median and p99 lines.
    const Summary summary = summarize(plot.update_us);
    const double top_us = std::max(summary.max, 10.0);
    const double chart_w = kPanelWidth - 2 * kMargin;
    const auto chart_y = [&](double us) {
        const double t = std::log10(std::max(us, 1.0)) / std::log10(top_us);
        return chart_top + kChartHeight * (1.0 - t);
    };
    svg << "<rect x=\"" << kMargin << "\" y=\"" << chart_top << "\" width=\"" << chart_w
        << "\" height=\"" << kChartHeight << "\" fill=\"#fff\" stroke=\"#999\"/>\n"
        << "<polyline fill=\"none\" stroke=\"#246\" stroke-width=\"0.7\" points=\"";
    const std::size_t n = plot.update_us.size();
    for (std::size_t i = 0; i < n; ++i)
        svg << kMargin + chart_w * static_cast<double>(i) /
                             static_cast<double>(std::max<std::size_t>(n - 1, 1))
            << ',' << chart_y(plot.update_us[i]) << ' ';
    svg << "\"/>\n";
    for (const auto& [value, label, colour] :
         {std::tuple{summary.p50, "p50", "#2a2"}, std::tuple{summary.p99, "p99", "#c22"}}) {
        svg << "<line x1=\"" << kMargin << "\" x2=\"" << kMargin + chart_w << "\" y1=\""
            << chart_y(value) << "\" y2=\"" << chart_y(value) << "\" stroke=\"" << colour
            << "\" stroke-dasharray=\"6 4\"/>\n"
            << "<text x=\"" << kMargin + chart_w - 120 << "\" y=\"" << chart_y(value) - 4
            << "\" font-size=\"12\" fill=\"" << colour << "\">" << label << " " << value
            << " us</text>\n";
    }
    svg << "<text x=\"" << kMargin << "\" y=\"" << chart_top + kChartHeight + 20
        << "\" font-size=\"12\">update time (log scale, up to " << top_us << " us) over "
        << static_cast<double>(n) * plot.dt << " simulated seconds</text>\n</svg>\n";

    std::ofstream file(path, std::ios::binary);
    if (!file)
        throw Error("cannot open '" + path.string() + "' for the " + plot.command + " picture");
    file << svg.str();
    if (!file.flush())
        throw Error("cannot write the " + plot.command + " picture '" + path.string() + "'");
}

}  // namespace trackphys::cli
