#pragma once

#include "trackphys/export.hpp"

namespace trackphys {

/// The instruction set the library was built for (CMake's TRACKPHYS_X86_64_LEVEL):
/// "x86-64-v2" (the default: SSE3, SSSE3, SSE4.1, SSE4.2 and POPCNT) or "x86-64" (the SSE2
/// baseline). trackphys needs an x86-64 processor (its BVH tests boxes with SSE2).
TRACKPHYS_API const char* build_target() noexcept;

/// True when this CPU has the instruction set extensions the library was built for. A
/// program that may run on older x86-64 CPUs (Intel before 2008, AMD before 2011, Atom
/// before 2013) should check it first and stop with a message (the trackphys command does):
/// the library's code would crash there on an illegal instruction.
TRACKPHYS_API bool cpu_runs_build_target() noexcept;

}  // namespace trackphys
