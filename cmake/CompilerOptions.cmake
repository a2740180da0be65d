# Flags every trackphys target shares, carried by an interface target so that they never
# leak into a consumer's build through the installed package.
add_library(trackphys_options INTERFACE)

# Same inputs, same build -> bit-identical results: no fused multiply-add contraction.
target_compile_options(trackphys_options INTERFACE
  -ffp-contract=off
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
  $<$<BOOL:${TRACKPHYS_WARNINGS_AS_ERRORS}>:-Werror>)

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
