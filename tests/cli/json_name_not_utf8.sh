#!/usr/bin/env bash
# tests/cli: a mesh whose file name is not UTF-8 (a name in another encoding) drives and is
# described with --json: the report names it with U+FFFD for the bad byte, where the JSON
# library threw after the whole drive had run and no report was written.
#   json_name_not_utf8.sh TRACKPHYS QUADS_OBJ FOLDER
set -uo pipefail
trackphys="$1"
quads="$2"
folder="$3"
rm -rf "$folder" && mkdir -p "$folder"
mesh="$folder/quads"$'\xff'".obj"
cp "$quads" "$mesh"
failed=0
replaced=$'\xef\xbf\xbd'
if ! "$trackphys" drive --mesh "$mesh" --spawn 0,3,0 --seconds 0.1 --json "$folder/drive.json" \
    >"$folder/drive.log" 2>&1; then
  echo "drive --json: $(cat "$folder/drive.log")"
  failed=1
elif ! grep -q "quads$replaced.obj" "$folder/drive.json"; then
  echo "drive --json: the report does not name the mesh with U+FFFD: $(head -c 400 "$folder/drive.json")"
  failed=1
fi
if ! "$trackphys" info "$mesh" --json >"$folder/info.json" 2>"$folder/info.log"; then
  echo "info --json: $(cat "$folder/info.log")"
  failed=1
elif ! grep -q "quads$replaced.obj" "$folder/info.json"; then
  echo "info --json: the report does not name the mesh with U+FFFD: $(head -c 400 "$folder/info.json")"
  failed=1
fi
exit "$failed"
