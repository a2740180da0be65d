#!/usr/bin/env bash
# The README's main command: installs what is missing, builds Release and runs the main
# job: the default car drives a lap of the default track by autopilot and prints its
# profile. Files go to out/ (the track mesh and picture, the drive's JSON, trace,
# recording and plot, and out/replay.html, the drive in a 3D viewer: open it in a browser);
# then a short race of 8 cars on 2 threads, its classification printed, into out/race.json,
# out/race.svg and out/race_replay.html. Extra arguments go to `trackphys drive`.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh
cmake --preset release
cmake --build --preset release --parallel "$(nproc)" --target trackphys_app
mkdir -p out
build/release/trackphys track --seed 7 --out out/track.glb --svg out/track.svg
build/release/trackphys drive --seed 7 --laps 1 --target-speed 600 \
  --json out/drive.json --trace out/drive.trace.json --record out/drive.jsonl --svg out/drive.svg "$@"
build/release/trackphys view out/drive.jsonl --out out/replay.html
build/release/trackphys race --cars 8 --seconds 25 --threads 2 \
  --json out/race.json --record out/race.jsonl --svg out/race.svg
build/release/trackphys view out/race.jsonl --out out/race_replay.html
