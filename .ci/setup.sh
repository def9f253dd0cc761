#!/usr/bin/env bash
# Shared set-up of tests/run.sh and demos/run.sh: make sure the Debian 12 packages are there (installing them
# when run as root), then configure and build the Release tree in build/ at the repository root.
# Arguments are extra CMake configure options (tests/run.sh passes -DUNIDIST_BUILD_TESTS=ON).
#   UNIDIST_BUILD_DIR  build directory (default: <repo>/build)
#   UNIDIST_JOBS       parallel build jobs (default: 2)
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${UNIDIST_BUILD_DIR:-$ROOT/build}"
JOBS="${UNIDIST_JOBS:-2}"

REQUIRED=(build-essential cmake pkg-config libeigen3-dev libbullet-dev libode-dev libosmesa6-dev libqhull-dev libpng-dev
          libgtest-dev libbenchmark-dev nlohmann-json3-dev libcli11-dev python3)
# Peers the benchmarks compare against when they are there: FCL (meshes), OpenCASCADE (NURBS; its CMake
# package links TBB), gnuplot (the plots).
OPTIONAL=(libfcl-dev libocct-modeling-algorithms-dev libocct-modeling-data-dev libocct-foundation-dev libtbb-dev
          gnuplot-nox)

installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q '^install ok installed$'; }

missing_of() {
  local p
  for p in "$@"; do installed "$p" || printf '%s\n' "$p"; done
}

if command -v dpkg-query >/dev/null 2>&1; then
  mapfile -t missing < <(missing_of "${REQUIRED[@]}")
  mapfile -t missing_optional < <(missing_of "${OPTIONAL[@]}")
  all_missing=("${missing[@]}" "${missing_optional[@]}")
  if ((${#all_missing[@]} > 0)); then
    if [[ "$(id -u)" == 0 ]]; then
      echo "setup: installing ${all_missing[*]}"
      export DEBIAN_FRONTEND=noninteractive
      apt-get update
      if ((${#missing[@]} > 0)); then
        apt-get install -y --no-install-recommends "${missing[@]}"
      fi
      if ((${#missing_optional[@]} > 0)); then
        apt-get install -y --no-install-recommends "${missing_optional[@]}" ||
          echo "setup: optional ${missing_optional[*]} not installed (benchmarks run without those peers)"
      fi
    elif ((${#missing[@]} > 0)); then
      echo "setup: missing Debian packages: ${missing[*]}" >&2
      echo "setup: as root, run:" >&2
      echo "apt-get update && DEBIAN_FRONTEND=noninteractive apt-get install -y ${all_missing[*]}" >&2
      exit 1
    else
      echo "setup: optional ${missing_optional[*]} missing (benchmarks run without those peers);" \
           "as root: apt-get install -y ${missing_optional[*]}" >&2
    fi
  fi
else
  echo "setup: dpkg-query not found (not Debian?): skipping the package check; CMake names anything missing" >&2
fi

cmake -S "$ROOT" -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build "$BUILD_DIR" -j"$JOBS"
