#include "interrupt_guard.hpp"

#include <atomic>
#include <csignal>
#include <cstring>
#include <string>

namespace trackphys::cli {
namespace {

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
// The signal that came, 0 for none: all a handler may safely do is set it. Atomic rather
// than volatile sig_atomic_t because a bake's worker threads read it too; a lock-free atomic
// is as safe in a handler.
std::atomic<int> g_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);
struct sigaction g_previous[3];

extern "C" void note_signal(int signal) { g_signal = signal; }

}  // namespace

InterruptGuard::InterruptGuard() {
    g_signal = 0;
    struct sigaction action {};
    action.sa_handler = note_signal;
    sigemptyset(&action.sa_mask);
    for (int i = 0; i < 3; ++i) sigaction(kSignals[i], &action, &g_previous[i]);
}

InterruptGuard::~InterruptGuard() {
    for (int i = 0; i < 3; ++i) sigaction(kSignals[i], &g_previous[i], nullptr);
}

void InterruptGuard::check() {
    if (const int signal = g_signal; signal != 0)
        throw Interrupted("interrupted by signal " + std::to_string(signal) + " (" +
                          strsignal(signal) + "): no output written");
}

}  // namespace trackphys::cli
