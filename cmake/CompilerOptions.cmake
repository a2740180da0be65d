# Flags every trackphys target shares, carried by an interface target so that they never
# leak into a consumer's build through the installed package.
add_library(trackphys_options INTERFACE)

# Same inputs, same build -> bit-identical results: no fused multiply-add contraction.
# No errno from the math functions either: nothing reads it, and setting it puts a branch
# after every square root, which keeps the cull's three roots from running side by side.
# Results do not change (IEEE square roots are correctly rounded with or without it).
target_compile_options(trackphys_options INTERFACE
  -ffp-contract=off -fno-math-errno
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
  $<$<BOOL:${TRACKPHYS_WARNINGS_AS_ERRORS}>:-Werror>)

# The x86-64 level the library is built for: v2 (SSE3 to SSE4.2 and POPCNT: Intel since
# 2008, AMD since 2011) by default, v1, the 2003 baseline (SSE2 only), or none (no -march:
# the compiler's default, or whatever CMAKE_CXX_FLAGS asks for). Results are the same at
# every level (no contraction, the same IEEE operations; scripts/determinism.sh compares a
# v1 clang++ build with the v2 g++ one); v2 lets the BVH box query pack the triangles it
# reports with byte shuffles (src/collision/lane_compaction.hpp), 7-8% faster on car boxes.
# A v2 build run on an older CPU would crash: the trackphys command checks first
# (src/core/build_target.cpp).
set(TRACKPHYS_X86_64_LEVEL v2 CACHE STRING "x86-64 level to build for: v2 (default), v1 (SSE2 only) or none (no -march)")
set_property(CACHE TRACKPHYS_X86_64_LEVEL PROPERTY STRINGS v2 v1 none)
if(NOT TRACKPHYS_X86_64_LEVEL MATCHES "^(v1|v2|none)$")
  message(FATAL_ERROR "TRACKPHYS_X86_64_LEVEL must be v2, v1 or none, got '${TRACKPHYS_X86_64_LEVEL}'")
endif()
if(CMAKE_SYSTEM_PROCESSOR MATCHES "^(x86_64|AMD64|amd64)$")
  if(TRACKPHYS_X86_64_LEVEL STREQUAL "v2")
    target_compile_options(trackphys_options INTERFACE -march=x86-64-v2)
  elseif(TRACKPHYS_X86_64_LEVEL STREQUAL "v1")
    target_compile_options(trackphys_options INTERFACE -march=x86-64)
  endif()
endif()

if(TRACKPHYS_SANITIZE)
  target_compile_options(trackphys_options INTERFACE
    -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  target_link_options(trackphys_options INTERFACE -fsanitize=address,undefined)
endif()

# A sanitizer build is a checking build: its RelWithDebInfo defines NDEBUG, which would
# compile every TP_ASSERT out, so the internal checks are turned back on.
if(TRACKPHYS_SANITIZE OR TRACKPHYS_SANITIZE_THREADS)
  target_compile_definitions(trackphys_options INTERFACE TRACKPHYS_ENABLE_ASSERT)
endif()

# ThreadSanitizer cannot share a build with AddressSanitizer.
if(TRACKPHYS_SANITIZE_THREADS)
  if(TRACKPHYS_SANITIZE)
    message(FATAL_ERROR "TRACKPHYS_SANITIZE_THREADS and TRACKPHYS_SANITIZE exclude each other")
  endif()
  target_compile_options(trackphys_options INTERFACE -fsanitize=thread -fno-omit-frame-pointer)
  target_link_options(trackphys_options INTERFACE -fsanitize=thread)
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
