#!/usr/bin/env bash
# The README's main command: installs what is missing, builds Release and runs the main
# job, writing its files to out/.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh
cmake --preset release
cmake --build --preset release --parallel "$(nproc)" --target trackphys_app
mkdir -p out
build/release/trackphys track --seed 7 --out out/track.glb --svg out/track.svg "$@"
build/release/trackphys info out/track.glb
