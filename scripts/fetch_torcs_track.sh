#!/usr/bin/env bash
# Puts a real-world race track mesh at DEST for the long soak (tests/soak, CTest label
# "long"): g-track-1, a road course from TORCS's Debian package torcs-data (AC3D; assimp
# reads it once named .ac). That package is a 333 MB download, so scripts/setup.sh does not
# install it; this script takes the one file it needs, only when the soak runs:
#   1. from an installed torcs-data (/usr/share/games/torcs, or $TRACKPHYS_TORCS_ROOT);
#   2. else with `apt-get download torcs-data`, extracting that file into DEST's folder.
#   scripts/fetch_torcs_track.sh DEST.ac
# Exits 0 when DEST is in place, 77 (CTest: skipped) when it cannot be had, with the reason.
set -euo pipefail

dest="$1"
file=usr/share/games/torcs/tracks/road/g-track-1/g-track-1.acc
if [ -s "$dest" ]; then
  echo "fetch_torcs_track: $dest is there"
  exit 0
fi
mkdir -p "$(dirname "$dest")"
for root in "${TRACKPHYS_TORCS_ROOT:-}" /usr/share/games/torcs; do
  if [ -n "$root" ] && [ -f "$root/${file#usr/share/games/torcs/}" ]; then
    cp "$root/${file#usr/share/games/torcs/}" "$dest"
    echo "fetch_torcs_track: copied from $root"
    exit 0
  fi
done

work="$(mktemp -d "$(dirname "$dest")/torcs-data.XXXXXX")"
trap 'rm -rf "$work"' EXIT
if ! (cd "$work" && apt-get download -q torcs-data); then
  echo "fetch_torcs_track: SKIPPED: 'apt-get download torcs-data' failed (no network or no package" \
       "index: run apt-get update), and torcs-data is not installed" >&2
  exit 77
fi
dpkg-deb --fsys-tarfile "$work"/torcs-data_*.deb | tar -x -C "$work" "./$file"
mv "$work/$file" "$dest"
echo "fetch_torcs_track: extracted $file from $(basename "$work"/torcs-data_*.deb)"
