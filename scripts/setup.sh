#!/usr/bin/env bash
# Installs every Debian package trackphys needs that is missing, and nothing else, then the
# replay viewer's npm packages (viewer/package-lock.json) when they are missing or stale.
# Safe to run again: when everything is present it says so and changes nothing.
# Needs root (as on the project's machines) only when something is missing.
set -euo pipefail

# package          why (also in docs/building.md, "Dependencies")
required=(
  cmake # the build (>= 3.25)
  g++ # the compiler
  libgtest-dev # tests
  libbenchmark-dev # benchmarks
  libglm-dev # vector, quaternion and matrix types in double (public headers)
  libassimp-dev # mesh import and export (the formats docs/building.md lists)
  zlib1g-dev # libassimp-dev's CMake target links /usr/lib/x86_64-linux-gnu/libz.so by path
             # but does not depend on the package that holds it: without it every link
             # against assimp::assimp fails ("No rule to make target .../libz.so")
  nlohmann-json3-dev # car spec and scenario files (src/io), JSON output of the command line tool
  libcli11-dev # command line parsing of the trackphys tool
  libbullet-dev # peer benchmarks (bench/peers): Bullet's GJK/EPA and quantized BVH, float
                # and double builds; optional: without it those programs are not built
  libfcl-dev # peer benchmarks (bench/peers): FCL's ellipsoid-triangle contact (libccd and
             # its own GJK); optional like libbullet-dev
  libmujoco-dev # peer benchmark (bench/peers): MuJoCo's ellipsoid-ellipsoid collision;
                # optional like libbullet-dev
  clang # the second compiler: scripts/determinism.sh checks that g++ and clang++ builds
        # give the same state hash, and the fuzzers (fuzz preset) need clang's libFuzzer
  libclang-rt-14-dev # clang's runtimes: libFuzzer (-fsanitize=fuzzer) and its sanitizers;
                     # clang-14 only recommends it, and this script installs without
                     # recommends
  clang-format-14 # scripts/check_format.sh (CI's format check): one version, since another
                  # major version breaks lines differently
  python3 # the mesh tests' generated files: tests/io/make_valid_meshes.py and the hostile
          # corpus of tests/cli
  llvm # llvm-symbolizer: function names and lines in sanitizer and fuzzer reports
  nodejs # the replay viewer (viewer/): esbuild bundles it at build time, and its browser
         # tests run under node
  chromium # the browser the viewer's tests drive headless (playwright-core never
           # downloads one of its own)
)

missing=()
for package in "${required[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

# npm comes with Debian's nodejs as a package of its own, but inside NodeSource's nodejs;
# asking apt for npm beside the latter would replace it.
command -v npm >/dev/null || missing+=(npm)

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#required[@]} required packages are installed"
else
  echo "setup: installing ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  # The package index of a fresh machine is stale: refresh it before installing.
  "${sudo_cmd[@]}" apt-get update -q
  "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
  echo "setup: done"
fi

# The viewer's packages, exactly as locked; again only when the lock file changed since.
viewer="$(dirname "$0")/../viewer"
stamp="$viewer/node_modules/.trackphys-package-lock.json"
if cmp -s "$viewer/package-lock.json" "$stamp"; then
  echo "setup: the viewer's npm packages are installed"
else
  echo "setup: installing the viewer's npm packages (npm ci in viewer/)"
  # playwright-core drives Debian's chromium and must not fetch a browser of its own.
  # No install scripts: the only one, esbuild's, checks a binary that npm already placed.
  (cd "$viewer" && PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --ignore-scripts --no-audit --no-fund)
  cp "$viewer/package-lock.json" "$stamp"
fi
