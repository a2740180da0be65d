#!/usr/bin/env bash
# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer (the asan preset, built
# in build/asan): CI (.ci/run) runs it after scripts/test.sh. The same tests as
# scripts/test.sh but those labelled "browser" or "release_only" and the lanes' UBSan copies
# (tests/CMakeLists.txt: this build is one); any sanitizer report fails its test. Built at
# -O1 (CMakePresets.json): at -O2, where UndefinedBehaviorSanitizer's checks double a file's
# compile time, the build took half as long again and its tests ran only a ninth faster.
# Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh
cmake --preset asan
cmake --build --preset asan --parallel "$(nproc)"
# Not the browser tests: they test the viewer's JavaScript in chromium, the same with either
# build of the page's writer, whose C++ the cli.view_* tests exercise here. Not the tests
# labelled release_only either: long under the sanitizers, and shorter tests run their code
# (each says which).
ctest --preset asan --label-exclude 'long|browser|release_only' "$@"
