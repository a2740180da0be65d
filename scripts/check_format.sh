#!/usr/bin/env bash
# Fails when a tracked C++ file differs from what clang-format makes of it (.clang-format at
# the root); CI (.ci/run) runs it first. `scripts/check_format.sh --fix` rewrites them instead.
set -euo pipefail
cd "$(dirname "$0")/.."

# One clang-format for everyone: another major version breaks lines differently.
formatter=clang-format-14
if ! command -v "$formatter" >/dev/null; then
  scripts/setup.sh
fi

mapfile -t files < <(git ls-files '*.cpp' '*.hpp' '*.h' '*.cc')
if [ "${1:-}" = "--fix" ]; then
  "$formatter" -i "${files[@]}"
  exit 0
fi
if ! "$formatter" --dry-run --Werror "${files[@]}" 2>"${TMPDIR:-/tmp}/format.log"; then
  grep -E '^[^ ].*: (error|warning):' "${TMPDIR:-/tmp}/format.log" | cut -d: -f1 | sort -u |
    sed 's/^/  /' >&2
  echo "check_format: the files above are not formatted; run scripts/check_format.sh --fix" >&2
  exit 1
fi
echo "check_format: ${#files[@]} files formatted"
