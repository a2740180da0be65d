#!/usr/bin/env bash
# Puts real-world race track meshes into DIR for the tests that run on them (the real-track
# brute-force match and spawn tests, and the long soak): four tracks of TORCS's Debian
# package torcs-data, AC3D files that assimp reads once named .ac:
#   g-track-1   road course, flat, kerbs and walls
#   c-speedway  banked oval, long thin kerb and wall triangles
#   e-track-4   road course with elevation, bridges
#   alpine-1    mountain road: steep, twisting, cut into slopes
# Each lands as DIR/<name>.ac, taken
#   1. from an installed torcs-data (/usr/share/games/torcs, or $TRACKPHYS_TORCS_ROOT);
#   2. else from one `apt-get download torcs-data` (333 MB), deleted once the missing
#      tracks are out of it.
# Tracks already in DIR are kept: DIR (build/torcs for every preset) downloads once.
#   scripts/fetch_torcs_track.sh DIR
# Exits 0 when every track is in DIR, 77 (CTest: skipped) when they cannot be had, with the
# reason.
set -euo pipefail

dir="$1"
tracks=(road/g-track-1/g-track-1.acc oval/c-speedway/c-speedway.ac road/e-track-4/e-track-4.acc
        road/alpine-1/alpine-1.acc)

# The packaged path (under usr/share/games/torcs/tracks/) of each track DIR lacks.
missing=()
for track in "${tracks[@]}"; do
  name="$(basename "${track%.*}")"
  [ -s "$dir/$name.ac" ] || missing+=("$track")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "fetch_torcs_track: all ${#tracks[@]} tracks are in $dir"
  exit 0
fi
mkdir -p "$dir"

for root in "${TRACKPHYS_TORCS_ROOT:-}" /usr/share/games/torcs; do
  [ -n "$root" ] || continue
  copied=0
  for track in "${missing[@]}"; do
    [ -f "$root/tracks/$track" ] || continue
    cp "$root/tracks/$track" "$dir/.$$.tmp" && mv "$dir/.$$.tmp" "$dir/$(basename "${track%.*}").ac"
    copied=$((copied + 1))
  done
  if [ $copied -eq ${#missing[@]} ]; then
    echo "fetch_torcs_track: copied ${#missing[@]} tracks from $root"
    exit 0
  fi
done

work="$(mktemp -d "$dir/torcs-data.XXXXXX")"
trap 'rm -rf "$work"' EXIT
if ! (cd "$work" && apt-get download -q torcs-data); then
  echo "fetch_torcs_track: SKIPPED: 'apt-get download torcs-data' failed (no network or no package" \
       "index: run apt-get update), and torcs-data is not installed" >&2
  exit 77
fi
members=()
for track in "${missing[@]}"; do members+=("./usr/share/games/torcs/tracks/$track"); done
dpkg-deb --fsys-tarfile "$work"/torcs-data_*.deb | tar -x -C "$work" "${members[@]}"
for track in "${missing[@]}"; do
  mv "$work/usr/share/games/torcs/tracks/$track" "$dir/$(basename "${track%.*}").ac"
done
echo "fetch_torcs_track: extracted ${#missing[@]} tracks from $(basename "$work"/torcs-data_*.deb)"
