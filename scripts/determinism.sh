#!/usr/bin/env bash
# Cross-compiler determinism (issue 8): builds the trackphys command in Release with g++ and
# with clang++ (each in its own build folder) and checks that the same drive gives the same
# state hash and final position, bit for bit.
#   scripts/determinism.sh [seconds]     (default 10 simulated seconds, seed 7)
# Exits 0 when they match, 1 when they differ, 2 when a build or run fails.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds="${1:-10}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT

# The state hash and final position of a drive's JSON report, on one line each.
summary() {
  tr -d ' \n' <"$1" | grep -o '"state_hash":"[0-9a-f]*"\|"final_position":\[[^]]*\]'
}

for compiler in g++ clang++; do
  build="build/determinism-${compiler}"
  if ! { cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER="$compiler" \
           -DTRACKPHYS_BUILD_TESTS=OFF -DTRACKPHYS_BUILD_BENCHMARKS=OFF >"$out/configure.log" &&
         cmake --build "$build" --target trackphys_app --parallel 2 >"$out/build.log"; }; then
    cat "$out/configure.log" "$out/build.log" >&2 || true
    echo "determinism: the $compiler build failed" >&2
    exit 2
  fi
  "$build/trackphys" drive --seed 7 --seconds "$seconds" --json "$out/$compiler.json" >/dev/null ||
    { echo "determinism: the $compiler drive failed" >&2; exit 2; }
  summary "$out/$compiler.json" >"$out/$compiler.txt"
  echo "$compiler: $(tr '\n' ' ' <"$out/$compiler.txt")"
done

if cmp -s "$out/g++.txt" "$out/clang++.txt"; then
  echo "determinism: g++ and clang++ agree after $seconds s"
else
  echo "determinism: g++ and clang++ DIFFER after $seconds s" >&2
  exit 1
fi
