#include "progress_bar.hpp"

#include <algorithm>
#include <cstdio>

#include <unistd.h>

namespace trackphys::cli {

ProgressBar::ProgressBar(double total) : total_(total), enabled_(total > 0.0 && isatty(2)) {}

ProgressBar::~ProgressBar() {
    if (enabled_ && last_ >= 0) std::fprintf(stderr, "\n");
}

void ProgressBar::show(double done, double speed_kmh) {
    if (!advances(done)) return;
    char note[32];
    std::snprintf(note, sizeof note, "%6.1f km/h", speed_kmh);
    draw(note);
}

void ProgressBar::show_count(double done, const char* unit) {
    if (!advances(done)) return;
    char note[96];
    std::snprintf(note, sizeof note, "%.0f of %.0f %s", done, total_, unit);
    draw(note);
}

bool ProgressBar::advances(double done) {
    if (!enabled_) return false;
    const int percent = static_cast<int>(100.0 * std::min(done / total_, 1.0));
    if (percent == last_) return false;
    last_ = percent;
    return true;
}

void ProgressBar::draw(const char* note) const {
    const int filled = last_ / 4;
    std::fprintf(stderr, "\r[%.*s%*s] %3d%%  %s", filled, "#########################", 25 - filled,
                 "", last_, note);
    std::fflush(stderr);
}

}  // namespace trackphys::cli
