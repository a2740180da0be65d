#pragma once

#include "trackphys/error.hpp"

namespace trackphys::cli {

/// What InterruptGuard::check throws: an Error of its own type, so that a command that
/// words the errors of a step (a refused mesh) can let this one through as it is.
class Interrupted : public Error {
  public:
    using Error::Error;
};

/// While it lives, SIGINT (Ctrl-C), SIGTERM and SIGHUP do not kill the process: they are
/// noted, and a long loop calls check() to stop with a trackphys::Error (Interrupted). The error unwinds
/// like any other, so the command's staged outputs (staged_outputs.hpp) are removed rather
/// than left behind as temporary files. The previous handlers come back in the destructor.
class InterruptGuard {
  public:
    InterruptGuard();
    ~InterruptGuard();
    InterruptGuard(const InterruptGuard&) = delete;
    InterruptGuard& operator=(const InterruptGuard&) = delete;

    /// Throws Interrupted ("interrupted by signal 2 (Interrupt): no output written") once a
    /// signal came. Safe to call from any thread.
    static void check();
};

}  // namespace trackphys::cli
