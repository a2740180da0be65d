#!/usr/bin/env bash
# The fuzzers' short runs (TRACKPHYS_FUZZ_SECONDS each, 20 s by default): builds the fuzz
# preset (clang, libFuzzer, AddressSanitizer + UndefinedBehaviorSanitizer, in build/fuzz)
# and runs its CTest tests, labelled "fuzz". The README's test command runs this as the
# test fuzz.short_runs behind the labels "fuzz" and "long": scripts/test.sh -L fuzz.
# Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh
cmake --preset fuzz
cmake --build --preset fuzz --parallel "$(nproc)"
ctest --preset fuzz "$@"
