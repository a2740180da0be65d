#!/usr/bin/env bash
# Cross-compiler determinism (issue 8): the trackphys command in Release from g++ (the
# release preset's build, build/release, as scripts/test.sh makes it, for x86-64-v2) and
# from clang++ (its own build folder, build/determinism-clang++, for the SSE2 baseline,
# TRACKPHYS_X86_64_LEVEL=v1, so that the other instruction-set paths run too) must give the
# same state hash and final position of the same drive, bit for bit. CI (.ci/run) runs it after scripts/test.sh.
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

# Builds the trackphys command with `compiler` into folder `build`; fails with its logs.
build_with() {
  local compiler="$1" build="$2"
  shift 2
  if ! { cmake "$@" >"$out/configure.log" &&
         cmake --build "$build" --target trackphys_app --parallel "$(nproc)" >"$out/build.log"; }; then
    cat "$out/configure.log" "$out/build.log" >&2 || true
    echo "determinism: the $compiler build failed" >&2
    exit 2
  fi
}

build_with g++ build/release --preset release
build_with clang++ build/determinism-clang++ -S . -B build/determinism-clang++ \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++ -DTRACKPHYS_X86_64_LEVEL=v1 \
  -DTRACKPHYS_BUILD_TESTS=OFF -DTRACKPHYS_BUILD_BENCHMARKS=OFF

for compiler in g++ clang++; do
  build=build/release
  [ "$compiler" = g++ ] || build=build/determinism-clang++
  "$build/trackphys" drive --seed 7 --seconds "$seconds" --json "$out/$compiler.json" >/dev/null ||
    { echo "determinism: the $compiler drive failed" >&2; exit 2; }
  summary "$out/$compiler.json" >"$out/$compiler.txt"
  echo "$compiler: $(tr '\n' ' ' <"$out/$compiler.txt")"
done

if cmp -s "$out/g++.txt" "$out/clang++.txt"; then
  echo "determinism: g++ (x86-64-v2) and clang++ (x86-64) agree after $seconds s"
else
  echo "determinism: g++ and clang++ DIFFER after $seconds s" >&2
  exit 1
fi
