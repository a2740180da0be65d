# Flags every trackphys target shares, carried by an interface target so that they never
# leak into a consumer's build through the installed package.
add_library(trackphys_options INTERFACE)

# Same inputs, same build -> bit-identical results: no fused multiply-add contraction.
target_compile_options(trackphys_options INTERFACE
  -ffp-contract=off
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
  $<$<BOOL:${TRACKPHYS_WARNINGS_AS_ERRORS}>:-Werror>)

# The x86-64 level the library is built for: v2 (SSSE3, SSE4.1/4.2, POPCNT: every x86-64
# CPU since about 2009) by default, or v1, the 2003 baseline (SSE2 only). Results are the
# same at both levels (no contraction, the same IEEE operations); v2 lets the BVH box query
# pack the triangles it reports with byte shuffles (src/collision/lane_compaction.hpp), 7-8%
# faster on car boxes. A v2 build run on an older CPU stops with an error (the trackphys
# command checks; src/core/cpu_check.cpp).
set(TRACKPHYS_X86_64_LEVEL v2 CACHE STRING "x86-64 level to build for: v2 (default) or v1 (SSE2 only)")
set_property(CACHE TRACKPHYS_X86_64_LEVEL PROPERTY STRINGS v1 v2)
if(CMAKE_SYSTEM_PROCESSOR MATCHES "^(x86_64|AMD64|amd64)$")
  if(TRACKPHYS_X86_64_LEVEL STREQUAL "v2")
    target_compile_options(trackphys_options INTERFACE -march=x86-64-v2)
  elseif(TRACKPHYS_X86_64_LEVEL STREQUAL "v1")
    target_compile_options(trackphys_options INTERFACE -march=x86-64)
  else()
    message(FATAL_ERROR "TRACKPHYS_X86_64_LEVEL must be v1 or v2, got '${TRACKPHYS_X86_64_LEVEL}'")
  endif()
endif()

if(TRACKPHYS_SANITIZE)
  target_compile_options(trackphys_options INTERFACE
    -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  target_link_options(trackphys_options INTERFACE -fsanitize=address,undefined)
endif()

# Fuzzers link libFuzzer (-fsanitize=fuzzer, fuzz/CMakeLists.txt); the library they test is
# compiled with its coverage instrumentation so that the search is guided by our code.
if(TRACKPHYS_BUILD_FUZZERS)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "TRACKPHYS_BUILD_FUZZERS needs clang (libFuzzer), not "
                        "${CMAKE_CXX_COMPILER_ID}: use the 'fuzz' preset")
  endif()
  if(NOT TRACKPHYS_SANITIZE)
    message(FATAL_ERROR "TRACKPHYS_BUILD_FUZZERS needs TRACKPHYS_SANITIZE=ON: a fuzzer without "
                        "AddressSanitizer misses most memory errors. Use the 'fuzz' preset")
  endif()
  target_compile_options(trackphys_options INTERFACE -fsanitize=fuzzer-no-link)
endif()
