#pragma once

namespace trackphys::cli {

/// While it lives, SIGINT (Ctrl-C), SIGTERM and SIGHUP do not kill the process: they are
/// noted, and a long loop calls check() to stop with a trackphys::Error. The error unwinds
/// like any other, so the command's staged outputs (staged_outputs.hpp) are removed rather
/// than left behind as temporary files. The previous handlers come back in the destructor.
class InterruptGuard {
  public:
    InterruptGuard();
    ~InterruptGuard();
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;

    /// Throws trackphys::Error ("interrupted by signal 2 (Interrupt)") once a signal came.
    static void check();
};

}  // namespace trackphys::cli
