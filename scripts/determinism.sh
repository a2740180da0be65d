#!/usr/bin/env bash
# Cross-compiler determinism (issue 8): the trackphys command in Release from g++ (the
# release preset's build, build/release, as scripts/test.sh makes it, for x86-64-v2) and
# from clang++ (its own build folder, build/determinism-clang++, for the SSE2 baseline,
# TRACKPHYS_X86_64_LEVEL=v1, so that the other instruction-set paths run too) must give the
# same state hash and final position of the same drive, bit for bit, and the same state
# hash of the demo's race (8 cars, 25 s, in which cars touch, so that the ellipsoid pair
# kernel is in the hash) on 1, 2 and 4 threads. The clang++ build also
# runs the collision, mid-phase, geometry and contact tests, so that the SSE2 code paths
# are tested, not only driven. The lanes of the cull and of the mid phase's filter are
# chosen at run time, not by the build (four with AVX2, else two): on an AVX2 machine both
# builds drive the four, each drives the two too (TRACKPHYS_LANES=2) to the same result, and
# the contact and mid-phase tests compare each width with the scalar code. CI (.ci/run) runs
# it after scripts/test.sh.
#   scripts/determinism.sh [seconds]     (default 10 simulated seconds, seed 7)
# Exits 0 when they match and the tests pass, 1 when they differ or a test fails, 2 when a
# build or run fails.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds="${1:-10}"
# The demo's race: its cars first touch after about 21 s (149 sub-steps of touching pairs
# by 25 s); a race of 12 cars for 5 s never does.
race_cars=8
race_seconds=25
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT

# The state hash and final position of a drive's JSON report, on one line each.
summary() {
  tr -d ' \n' <"$1" | grep -o '"state_hash":"[0-9a-f]*"\|"final_position":\[[^]]*\]'
}

# Builds the space-separated `targets` with `compiler` into folder `build`, configured with
# the remaining arguments; fails with its logs.
build_with() {
  local compiler="$1" build="$2" targets
  read -ra targets <<<"$3"
  shift 3
  if ! { cmake "$@" >"$out/configure.log" &&
         cmake --build "$build" --target "${targets[@]}" --parallel "$(nproc)" >"$out/build.log"; }; then
    cat "$out/configure.log" "$out/build.log" >&2 || true
    echo "determinism: the $compiler build failed" >&2
    exit 2
  fi
}

# The tests the SSE2 build runs, by their folder under tests/.
sse2_tests=(collision/collision_tests collision/midphase_tests geometry/geometry_tests
  geometry/contact_tests)
build_with g++ build/release trackphys_app --preset release
build_with clang++ build/determinism-clang++ "trackphys_app ${sse2_tests[*]##*/}" \
  -S . -B build/determinism-clang++ -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++ \
  -DTRACKPHYS_X86_64_LEVEL=v1 -DTRACKPHYS_BUILD_TESTS=ON -DTRACKPHYS_BUILD_BENCHMARKS=OFF

for path in "${sse2_tests[@]}"; do
  test="${path##*/}"
  if ! "build/determinism-clang++/tests/$path" --gtest_brief=1 >"$out/$test.log" 2>&1; then
    cat "$out/$test.log" >&2
    echo "determinism: the clang++ (x86-64) build FAILS $test" >&2
    exit 1
  fi
  echo "clang++ (x86-64): $test pass ($(grep -o '[0-9]* tests\? from [0-9]* test suites\? ran' "$out/$test.log"))"
done

for compiler in g++ clang++; do
  build=build/release
  [ "$compiler" = g++ ] || build=build/determinism-clang++
  "$build/trackphys" drive --seed 7 --seconds "$seconds" --json "$out/$compiler.json" >/dev/null ||
    { echo "determinism: the $compiler drive failed" >&2; exit 2; }
  summary "$out/$compiler.json" >"$out/$compiler.txt"
  # The two-lane cull and filter, which an AVX2 machine takes only when told to.
  TRACKPHYS_LANES=2 "$build/trackphys" drive --seed 7 --seconds "$seconds" \
    --json "$out/$compiler-two-lanes.json" >/dev/null ||
    { echo "determinism: the $compiler drive in two lanes failed" >&2; exit 2; }
  if [ "$(summary "$out/$compiler-two-lanes.json")" != "$(cat "$out/$compiler.txt")" ]; then
    echo "determinism: the $compiler drive DIFFERS in two lanes" >&2
    exit 1
  fi
  # A race of cars that touch (issue 16): the same hash on 1, 2 and 4 threads.
  for threads in 1 2 4; do
    "$build/trackphys" race --seed 7 --cars "$race_cars" --seconds "$race_seconds" \
      --threads "$threads" --json "$out/race.json" >/dev/null ||
      { echo "determinism: the $compiler race on $threads threads failed" >&2; exit 2; }
    if ! tr -d ' \n' <"$out/race.json" | grep -q '"car_contacts":[1-9]'; then
      echo "determinism: the $compiler race on $threads threads has no car contacts to compare" >&2
      exit 1
    fi
    echo "race on $threads threads: $(tr -d ' \n' <"$out/race.json" | grep -o '"state_hash":"[0-9a-f]*"')" \
      >>"$out/$compiler.txt"
  done
  echo "$compiler: $(tr '\n' ' ' <"$out/$compiler.txt")"
done

race_hashes=$(grep -ho 'race on .*' "$out/g++.txt" "$out/clang++.txt" | grep -o '"state_hash":"[0-9a-f]*"' | sort -u | wc -l)
if [ "$race_hashes" -ne 1 ]; then
  echo "determinism: the race's hash DIFFERS between thread counts or compilers" >&2
  exit 1
fi
if cmp -s "$out/g++.txt" "$out/clang++.txt"; then
  echo "determinism: g++ (x86-64-v2) and clang++ (x86-64) agree after $seconds s"
else
  echo "determinism: g++ and clang++ DIFFER after $seconds s" >&2
  exit 1
fi
