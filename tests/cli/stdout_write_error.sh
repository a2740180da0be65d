#!/usr/bin/env bash
# tests/cli: every command that prints to standard output exits non-zero, with a message
# on stderr, when that output cannot be written (/dev/full: every write fails with ENOSPC).
#   stdout_write_error.sh TRACKPHYS MESH
set -uo pipefail
trackphys="$1"
mesh="$2"
if [ ! -e /dev/full ]; then
  echo "skipped: this system has no /dev/full"
  exit 77
fi
failed=0
check() {
  local code=0 message
  message="$("$trackphys" "$@" 2>&1 >/dev/full)" || code=$?
  if [ "$code" -eq 0 ] || [[ "$message" != *"cannot write to standard output: No space left on device"* ]]; then
    echo "trackphys $*: exit $code, stderr: $message"
    failed=1
  fi
}
check drive --print-car
check drive --print-scenario
check drive --mesh "$mesh" --spawn 0,3,0 --seconds 0.1
check race --cars 2 --seconds 0.1
check track --seed 3
check info "$mesh"
check info --json "$mesh"
check --help
exit "$failed"
