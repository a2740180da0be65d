#!/usr/bin/env bash
# tests/cli: `drive --mesh` builds the colliders `bake` would (the mesh split into 100 m cells),
# so a free drive on the mesh and on its baked map end in the same state hash.
#   mesh_drives_as_its_map.sh TRACKPHYS MESH FOLDER
set -euo pipefail
trackphys="$1"
mesh="$2"
folder="$3"
rm -rf "$folder" && mkdir -p "$folder"
baked="$("$trackphys" bake "$mesh" --out "$folder/m.tpmap")"
colliders="$(sed -n 's/^colliders *\([0-9]*\),.*/\1/p' <<<"$baked")"
[ "${colliders:-0}" -gt 1 ] || { echo "the mesh should bake to several colliders: $baked"; exit 1; }
drive=(drive --spawn 0,3,0 --throttle 1 --steer 0.3 --seconds 6)
on_mesh="$("$trackphys" "${drive[@]}" --mesh "$mesh" | grep "state hash")"
on_map="$("$trackphys" "${drive[@]}" --map "$folder/m.tpmap" | grep "state hash")"
[ "$on_mesh" == "$on_map" ] || { echo "on the mesh: $on_mesh; on its map: $on_map"; exit 1; }
echo "$colliders colliders; both: $on_mesh"
