#include "interrupt_guard.hpp"

#include <csignal>
#include <cstring>
#include <string>

#include "trackphys/error.hpp"

namespace trackphys::cli {
namespace {

constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
// The signal that came, 0 for none: all a handler may safely do is set it.
volatile std::sig_atomic_t g_signal = 0;
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
    if (g_signal != 0)
        throw Error("interrupted by signal " + std::to_string(g_signal) + " (" +
                    strsignal(g_signal) + "): no output written");
}

}  // namespace trackphys::cli
