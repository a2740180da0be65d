#!/usr/bin/env bash
# tests/cli: a command stopped by a signal part way (SIGTERM, or SIGINT as Ctrl-C sends)
# exits 1 with a message and leaves no output and no temporary file in its output folder.
#   interrupt_leaves_nothing.sh SIGNAL FOLDER COMMAND...
# COMMAND writes its outputs into FOLDER, which is emptied first. The signal comes a second
# after COMMAND has staged its first file there, so while it works (the outputs are staged
# before the work begins).
set -euo pipefail
signal="$1"
folder="$2"
shift 2
rm -rf "$folder"
mkdir -p "$folder"
"$@" >/dev/null 2>"$folder.err" &
pid=$!
for _ in $(seq 600); do
  [ -z "$(ls -A "$folder")" ] || break
  sleep 0.1
done
[ -n "$(ls -A "$folder")" ] || { echo "nothing staged in $folder after 60 s"; exit 1; }
sleep 1
kill -s "$signal" "$pid"
code=0
wait "$pid" || code=$?
message="$(cat "$folder.err")"
left="$(ls -A "$folder")"
[ "$code" -eq 1 ] || { echo "expected exit 1, got $code: $message"; exit 1; }
number="$(kill -l "$signal")"
[[ "$message" == *"interrupted by signal $number "* ]] || { echo "unexpected message: $message"; exit 1; }
[ -z "$left" ] || { echo "left behind in $folder: $left"; exit 1; }
echo "stopped with: $message"
