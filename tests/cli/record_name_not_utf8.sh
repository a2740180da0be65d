#!/usr/bin/env bash
# tests/cli: drive and race refuse a --record file name that is not UTF-8 before they run (the
# recording names its track file in JSON, so it could not be viewed), and write nothing.
#   record_name_not_utf8.sh TRACKPHYS FOLDER
set -uo pipefail
trackphys="$1"
folder="$2"
rm -rf "$folder" && mkdir -p "$folder"
failed=0
for command in "drive --seconds 0.1" "race --cars 2 --seconds 0.1"; do
  code=0
  # shellcheck disable=SC2086 # the command's words
  message="$("$trackphys" $command --record "$folder/lap"$'\xff'".jsonl" 2>&1)" || code=$?
  if [ "$code" -ne 1 ] || [[ "$message" != *"the file name is not UTF-8"* ]]; then
    echo "trackphys $command: exit $code, output: $message"
    failed=1
  fi
done
if [ -n "$(ls -A "$folder")" ]; then
  echo "left behind: $(ls -A "$folder")"
  failed=1
fi
exit "$failed"
