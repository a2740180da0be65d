#!/usr/bin/env bash
# tests/cli: a drive stopped by SIGTERM (or Ctrl-C) part way exits 1 with a message and
# leaves no output and no temporary file in its output folder.
#   interrupt_leaves_nothing.sh TRACKPHYS FOLDER
set -euo pipefail
trackphys="$1"
folder="$2"
rm -rf "$folder"
mkdir -p "$folder"
"$trackphys" drive --seconds 3600 --json "$folder/d.json" --svg "$folder/d.svg" --record "$folder/d.jsonl" \
  --trace "$folder/d.trace.json" >/dev/null 2>"$folder.err" &
pid=$!
sleep 3
kill -TERM "$pid"
code=0
wait "$pid" || code=$?
message="$(cat "$folder.err")"
left="$(ls -A "$folder")"
[ "$code" -eq 1 ] || { echo "expected exit 1, got $code: $message"; exit 1; }
[[ "$message" == *"interrupted by signal 15"* ]] || { echo "unexpected message: $message"; exit 1; }
[ -z "$left" ] || { echo "left behind in $folder: $left"; exit 1; }
echo "stopped with: $message"
