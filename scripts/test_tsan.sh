#!/usr/bin/env bash
# The threaded tests under ThreadSanitizer (the tsan preset, built in build/tsan): World's
# islands on its own threads and on a plugged-in job system, and PhysicsRunner's physics
# and render threads (tests/world/CMakeLists.txt, world_threaded_tests), and a map baked,
# its progress heard, and loaded on several threads, one mesh's plane tree built apart on
# several (tests/io/CMakeLists.txt, map_tests),
# and the parallel-items helper under them (tests/core, core_tests).
# Only those targets are built, to keep CI short; any ThreadSanitizer report fails its
# test. CI (.ci/run) runs it after the fuzzers. Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh
cmake --preset tsan
cmake --build --preset tsan --parallel "$(nproc)" --target world_threaded_tests map_tests core_tests
# halt_on_error: the first report fails the test (its exit code), rather than a summary.
TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 ${TSAN_OPTIONS:-}" \
  ctest --preset tsan \
  --tests-regex '^((WorldThreads|PhysicsRunner|ParallelItems)\.|Presets/PhysicsRunnerView\.|MapFile\.(BakeGivesTheSameMapOnAnyThreadCount|BakeProgress|AnyThreadCount))' \
  "$@"
