#pragma once

#include "trackphys/export.hpp"

namespace trackphys {

/// The instruction set the library was built for (CMake's TRACKPHYS_X86_64_LEVEL):
/// "x86-64-v2" (the default: SSSE3, SSE4.1, SSE4.2 and POPCNT), "x86-64" (the SSE2
/// baseline), or "portable" on other processors.
TRACKPHYS_API const char* build_target() noexcept;

/// True when this CPU has every instruction set extension the library was built for. A
/// program that may run on x86-64 CPUs older than about 2009 should check it first and stop
/// with a message (the trackphys command does): the library's code would crash there on an
/// illegal instruction.
TRACKPHYS_API bool cpu_runs_build_target() noexcept;

}  // namespace trackphys
