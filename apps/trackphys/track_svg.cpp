#include "track_svg.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "trackphys/error.hpp"

namespace trackphys::cli {
namespace {

constexpr double kMapWidthPx = 1200.0;  // drawing area for the track
constexpr double kMarginPx = 40.0;
constexpr double kLegendWidthPx = 230.0;
constexpr double kCaptionHeightPx = 50.0;
// Bank angles are drawn in this many colour steps; neighbouring row steps of one step
// merge into one polygon, which keeps the file small (a few hundred kB).
constexpr int kBankSteps = 21;

// Diverging map for t in [-1, 1]: blue (right side low) - light grey (flat) - red (left low).
std::string bank_colour(double t) {
    const std::array<double, 3> grey{225, 225, 220}, blue{33, 102, 172}, red{178, 24, 43};
    const std::array<double, 3>& end = t < 0.0 ? blue : red;
    const double f = std::min(1.0, std::abs(t));
    char text[8];
    std::snprintf(text, sizeof text, "#%02x%02x%02x",
                  static_cast<int>(std::lround(grey[0] + f * (end[0] - grey[0]))),
                  static_cast<int>(std::lround(grey[1] + f * (end[1] - grey[1]))),
                  static_cast<int>(std::lround(grey[2] + f * (end[2] - grey[2]))));
    return text;
}

// The colour step of a bank angle (0 .. kBankSteps - 1), as a signed fraction of max bank.
int bank_step(double bank, double max_bank) {
    const double t = max_bank > 0.0 ? std::clamp(bank / max_bank, -1.0, 1.0) : 0.0;
    return static_cast<int>(std::lround((t + 1.0) * 0.5 * (kBankSteps - 1)));
}
double step_fraction(int step) { return 2.0 * step / (kBankSteps - 1) - 1.0; }

// Map from world (x, z) to picture pixels.
struct View {
    double min_x, min_z, scale;
    glm::dvec2 operator()(const glm::dvec3& p) const {
        return {kMarginPx + (p.x - min_x) * scale,
                kCaptionHeightPx + kMarginPx + (p.z - min_z) * scale};
    }
};

void point(std::ostringstream& out, const glm::dvec2& p) { out << p.x << ',' << p.y << ' '; }

}  // namespace

std::string track_svg(const Track& track) {
    const TrackParams& params = track.params;
    const std::vector<CenterlineSample>& rows = track.centerline;
    const std::size_t n = rows.size();
    const double half = 0.5 * params.width_m;
    const double max_bank = params.max_bank_deg * std::numbers::pi / 180.0;

    // Road edges and wall centre lines (half a thickness outside the edges), per row.
    std::vector<glm::dvec3> left(n), right(n), left_wall(n), right_wall(n);
    for (std::size_t r = 0; r < n; ++r) {
        const CenterlineSample& s = rows[r];
        const glm::dvec3 flat = glm::normalize(glm::dvec3(s.tangent.z, 0.0, -s.tangent.x));
        left[r] = s.position + half * s.left;
        right[r] = s.position - half * s.left;
        left_wall[r] = left[r] + 0.5 * params.wall_thickness_m * flat;
        right_wall[r] = right[r] - 0.5 * params.wall_thickness_m * flat;
    }

    double min_x = left_wall[0].x, max_x = min_x, min_z = left_wall[0].z, max_z = min_z;
    for (const auto* edge : {&left_wall, &right_wall})
        for (const glm::dvec3& p : *edge) {
            min_x = std::min(min_x, p.x);
            max_x = std::max(max_x, p.x);
            min_z = std::min(min_z, p.z);
            max_z = std::max(max_z, p.z);
        }
    const View view{min_x, min_z, kMapWidthPx / std::max(max_x - min_x, max_z - min_z)};
    const double width_px = kMarginPx * 2.0 + (max_x - min_x) * view.scale + kLegendWidthPx;
    const double height_px =
        std::max(kCaptionHeightPx + kMarginPx * 2.0 + (max_z - min_z) * view.scale, 480.0);

    std::ostringstream out;
    out.setf(std::ios::fixed);
    out.precision(1);
    out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width_px << "\" height=\""
        << height_px << "\" viewBox=\"0 0 " << width_px << ' ' << height_px
        << "\" font-family=\"sans-serif\">\n"
        << "<rect width=\"100%\" height=\"100%\" fill=\"#eef3e6\"/>\n";

    // Caption.
    out << "<text x=\"" << kMarginPx << "\" y=\"28\" font-size=\"18\">trackphys track: seed "
        << params.seed << ", " << track.length_m << " m, " << params.width_m << " m wide, "
        << track.triangle_count() << " triangles, " << track.chunks.size() << " colliders</text>\n"
        << "<text x=\"" << kMarginPx
        << "\" y=\"46\" font-size=\"12\" fill=\"#555\">top view: x right, z down;"
        << " colour = bank angle; dark lines = walls</text>\n";

    // Road: consecutive row steps of one colour step make one polygon (left edge forward,
    // right edge back). A thin stroke of the same colour hides anti-aliasing seams.
    out << "<g stroke-width=\"0.8\" stroke-linejoin=\"round\">\n";
    std::size_t r = 0;
    while (r < n) {
        const int step = bank_step(rows[r].bank, max_bank);
        std::size_t end = r + 1;
        while (end < n && bank_step(rows[end].bank, max_bank) == step) ++end;
        const std::string colour = bank_colour(step_fraction(step));
        out << "<polygon fill=\"" << colour << "\" stroke=\"" << colour << "\" points=\"";
        for (std::size_t k = r; k <= end; ++k) point(out, view(left[k % n]));
        for (std::size_t k = end + 1; k-- > r;) point(out, view(right[k % n]));
        out << "\"/>\n";
        r = end;
    }
    out << "</g>\n";

    // Walls: closed paths through the wall centre lines, points closer than a pixel skipped.
    for (const auto* wall : {&left_wall, &right_wall}) {
        out << "<polygon fill=\"none\" stroke=\"#333\" stroke-width=\"1.3\" "
               "stroke-linejoin=\"round\" points=\"";
        glm::dvec2 last = view((*wall)[0]);
        point(out, last);
        for (const glm::dvec3& p : *wall) {
            const glm::dvec2 q = view(p);
            if (glm::distance(q, last) < 1.0) continue;
            point(out, q);
            last = q;
        }
        out << "\"/>\n";
    }

    // Start line across the road at sample 0 (black under white dashes: a chequer), an
    // arrow along the direction of travel, and the label beside the road.
    const glm::dvec2 start_left = view(left_wall[0]), start_right = view(right_wall[0]);
    for (const char* style : {"stroke=\"#000\"", "stroke=\"#fff\" stroke-dasharray=\"3 3\""})
        out << "<line x1=\"" << start_left.x << "\" y1=\"" << start_left.y << "\" x2=\""
            << start_right.x << "\" y2=\"" << start_right.y << "\" " << style
            << " stroke-width=\"6\"/>\n";
    const glm::dvec2 centre = view(rows[0].position);
    const glm::dvec2 forward = glm::normalize(glm::dvec2(rows[0].tangent.x, rows[0].tangent.z));
    const glm::dvec2 side = glm::normalize(start_left - start_right);
    const glm::dvec2 tip = centre + 34.0 * forward, base = centre + 14.0 * forward;
    out << "<polygon fill=\"#000\" points=\"";
    point(out, tip);
    point(out, base + 7.0 * side);
    point(out, base - 7.0 * side);
    out << "\"/>\n";
    const glm::dvec2 label = start_left + 30.0 * side;
    out << "<text x=\"" << label.x << "\" y=\"" << label.y + 5.0
        << "\" font-size=\"14\" font-weight=\"bold\" text-anchor=\"middle\">START</text>\n";

    // Legend: bank colour bar from +max (top) to -max (bottom), ticks every quarter.
    const double legend_x = width_px - kLegendWidthPx + 20.0;
    const double bar_top = kCaptionHeightPx + kMarginPx + 30.0, bar_height = 300.0,
                 bar_width = 24.0;
    out << "<text x=\"" << legend_x << "\" y=\"" << bar_top - 14.0
        << "\" font-size=\"14\">bank angle</text>\n";
    for (int step = 0; step < kBankSteps; ++step) {
        const double y = bar_top + bar_height * (kBankSteps - 1 - step) / kBankSteps;
        out << "<rect x=\"" << legend_x << "\" y=\"" << y << "\" width=\"" << bar_width
            << "\" height=\"" << bar_height / kBankSteps + 0.5 << "\" fill=\""
            << bank_colour(step_fraction(step)) << "\"/>\n";
    }
    out << "<rect x=\"" << legend_x << "\" y=\"" << bar_top << "\" width=\"" << bar_width
        << "\" height=\"" << bar_height << "\" fill=\"none\" stroke=\"#333\"/>\n";
    for (int tick = 0; tick <= 4; ++tick) {
        const double fraction = 1.0 - 0.5 * tick;  // +1 .. -1
        const double y =
            bar_top + bar_height * (0.5 - 0.5 * fraction * (kBankSteps - 1) / kBankSteps);
        out << "<line x1=\"" << legend_x + bar_width << "\" y1=\"" << y << "\" x2=\""
            << legend_x + bar_width + 5 << "\" y2=\"" << y << "\" stroke=\"#333\"/>\n"
            << "<text x=\"" << legend_x + bar_width + 9 << "\" y=\"" << y + 4
            << "\" font-size=\"12\">" << (fraction > 0 ? "+" : "") << fraction * params.max_bank_deg
            << "\u00b0</text>\n";
    }
    out << "<text x=\"" << legend_x << "\" y=\"" << bar_top + bar_height + 22
        << "\" font-size=\"11\" fill=\"#555\">"
        << "+ : left side low (left turn)</text>\n"
        << "<text x=\"" << legend_x << "\" y=\"" << bar_top + bar_height + 38
        << "\" font-size=\"11\" fill=\"#555\">"
        << "\u2212 : right side low</text>\n";

    // Scale bar: the largest of 1-2-5 x 10^k metres that fits in 150 px.
    double bar_m = 1.0;
    while (bar_m * 10.0 * view.scale <= 150.0) bar_m *= 10.0;
    if (bar_m * 5.0 * view.scale <= 150.0)
        bar_m *= 5.0;
    else if (bar_m * 2.0 * view.scale <= 150.0)
        bar_m *= 2.0;
    const double scale_y = bar_top + bar_height + 80.0;
    out << "<line x1=\"" << legend_x << "\" y1=\"" << scale_y << "\" x2=\""
        << legend_x + bar_m * view.scale << "\" y2=\"" << scale_y
        << "\" stroke=\"#000\" stroke-width=\"3\"/>\n"
        << "<text x=\"" << legend_x << "\" y=\"" << scale_y + 18 << "\" font-size=\"12\">" << bar_m
        << " m</text>\n";
    out << "</svg>\n";
    return out.str();
}

void write_track_svg(const Track& track, const std::filesystem::path& path) {
    std::ofstream file(path, std::ios::binary);
    if (!file) throw Error("cannot open '" + path.string() + "' for writing the track picture");
    file << track_svg(track);
    if (!file.flush()) throw Error("cannot write the track picture to '" + path.string() + "'");
}

}  // namespace trackphys::cli
