#!/usr/bin/env bash
# The README's test command: installs what is missing, builds Release and runs every test
# (the long soak and fuzz runs are behind the ctest label "long", see README.md).
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh
cmake --preset release
cmake --build --preset release --parallel "$(nproc)"
ctest --preset release --label-exclude long "$@"
