#!/usr/bin/env bash
# The long fuzz run (docs/testing.md, "Bad input and long runs"): builds the fuzz preset (clang, libFuzzer,
# AddressSanitizer + UndefinedBehaviorSanitizer) and runs every fuzzer for MINUTES each
# (default 60), one after the other, each from its corpus (build/fuzz/fuzz/corpus/<name>,
# kept between runs and shared with the short CTest runs) and its seeds, with a random search
# seed. Findings land in build/fuzz/fuzz/findings/ as crash-*, timeout-*, leak-*, oom-*;
# replay one with build/fuzz/fuzz/<fuzzer> <file>.
#   scripts/fuzz_long.sh [MINUTES] [FUZZER...]
# Exits 1 when a fuzzer found something, 0 when none did.
set -euo pipefail
cd "$(dirname "$0")/.."

minutes="${1:-60}"
shift || true
# Every fuzzer and its longest input (bytes), as fuzz/CMakeLists.txt declares them
# (trackphys_add_fuzzer(<name> <max_len> ...)).
declare -A max_len=()
while read -r name length; do
  max_len[$name]=$length
done < <(sed -n 's/^trackphys_add_fuzzer(\([a-z_]*\) \([0-9]*\).*/\1 \2/p' fuzz/CMakeLists.txt)
fuzzers=("$@")
[ ${#fuzzers[@]} -gt 0 ] || mapfile -t fuzzers < <(printf '%s\n' "${!max_len[@]}" | sort)
for fuzzer in "${fuzzers[@]}"; do
  [ -n "${max_len[$fuzzer]:-}" ] || { echo "fuzz_long: no fuzzer '$fuzzer' in fuzz/CMakeLists.txt" >&2; exit 2; }
done

scripts/setup.sh
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz --parallel 2 --target "${fuzzers[@]}"

bin=build/fuzz/fuzz
mkdir -p "$bin/findings"
# No allocation may fail quietly: one beyond -rss_limit_mb is a finding, as in the short runs
# (fuzz/CMakeLists.txt; load_mesh checks every count against the file, issue 19).
export LSAN_OPTIONS=print_suppressions=0
failed=0
for fuzzer in "${fuzzers[@]}"; do
  seeds=()
  [ -d "fuzz/seeds/$fuzzer" ] && seeds=("fuzz/seeds/$fuzzer")
  mkdir -p "$bin/corpus/$fuzzer"
  echo "fuzz_long: $fuzzer for $minutes min"
  if ! "$bin/$fuzzer" -max_total_time=$((minutes * 60)) -max_len="${max_len[$fuzzer]}" -timeout=10 \
         -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$bin/findings/$fuzzer-" \
         "$bin/corpus/$fuzzer" "${seeds[@]}" 2>"$bin/findings/$fuzzer.log"; then
    echo "fuzz_long: $fuzzer FOUND something: see $bin/findings/$fuzzer.log" >&2
    failed=1
  fi
  grep -E "^stat::number_of_executed_units|^stat::new_units_added" "$bin/findings/$fuzzer.log" || true
done
exit $failed
