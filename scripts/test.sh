#!/usr/bin/env bash
# The README's test command: installs what is missing, builds Release and runs every test
# (the soak, the fuzzers' short runs, the 20-car races and most of the lap sweep are behind
# the ctest labels "long" and "fuzz", see docs/testing.md). Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh
cmake --preset release
cmake --build --preset release --parallel "$(nproc)"
# The real-world track meshes some tests run on, into build/torcs once (a 333 MB download:
# see the script); without network the script says so and those tests skip.
scripts/fetch_torcs_track.sh build/torcs || [ $? -eq 77 ]
# Every test but the long ones (labels "long" and "fuzz": the soak, the fuzzers' short runs,
# the 20-car races and most of the lap sweep); a label of the caller's own (-L LABEL)
# chooses instead: scripts/test.sh -L fuzz.
skip=(--label-exclude 'long|fuzz')
for arg in "$@"; do
  case "$arg" in -L* | --label-regex*) skip=() ;; esac
done
ctest --preset release "${skip[@]}" "$@"
