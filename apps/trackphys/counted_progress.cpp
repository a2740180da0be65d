#include "counted_progress.hpp"

#include "interrupt_guard.hpp"

namespace trackphys::cli {

std::function<void(std::size_t done, std::size_t total)> CountedProgress::callback() {
    return [this](std::size_t done, std::size_t total) {
        InterruptGuard::check();
        if (!bar_) bar_.emplace(static_cast<double>(total));
        bar_->show_count(static_cast<double>(done), unit_);
    };
}

}  // namespace trackphys::cli
