#!/usr/bin/env bash
# The fuzzers' seeds and short runs: builds the fuzz preset (clang, libFuzzer,
# AddressSanitizer + UndefinedBehaviorSanitizer, in build/fuzz) and runs its CTest tests,
# labelled "fuzz": each fuzzer replays every file of fuzz/seeds/<fuzzer>/ as an input, then
# searches from them for TRACKPHYS_FUZZ_SECONDS (20 s by default) with the fixed -seed=1,
# so that a fresh build's run is repeatable. Findings land in build/fuzz/fuzz/findings/. CI
# (.ci/run) runs it; the README's test command runs it as the test fuzz.short_runs behind
# the labels "fuzz" and "long": scripts/test.sh -L fuzz. Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh
cmake --preset fuzz
cmake --build --preset fuzz --parallel "$(nproc)"
ctest --preset fuzz "$@"
