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
    if (!enabled_) return;
    const int percent = static_cast<int>(100.0 * std::min(done / total_, 1.0));
    if (percent == last_) return;
    last_ = percent;
    const int filled = percent / 4;
    std::fprintf(stderr, "\r[%.*s%*s] %3d%%  %6.1f km/h", filled, "#########################",
                 25 - filled, "", percent, speed_kmh);
    std::fflush(stderr);
}

}  // namespace trackphys::cli
