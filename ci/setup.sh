#!/usr/bin/env bash
# Installs the Debian packages Stentor needs (skipped when present), then configures
# and builds into ./build. Idempotent: a second run only rebuilds what changed.
# ParaView (paraview, python3-paraview, xvfb: 146 MB, about 70 s) is for the pictures
# (tools/stentor_pictures.py under pvbatch) and their tests.
#   --packages-only          install, do not build
#   STENTOR_EXTRA_PKGS="..." more packages (ci/build-trilinos-openmp.sh uses it)
set -euo pipefail
cd "$(dirname "$0")/.."
PKGS="build-essential cmake ninja-build ccache pkg-config trilinos-all-dev libptscotch-dev
      openmpi-bin libopenmpi-dev libmetis-dev libhdf5-openmpi-dev gmsh libgmsh-dev
      libgtest-dev googletest gnuplot-nox python3-meshio python3-h5py python3-numpy
      paraview python3-paraview xvfb xauth ${STENTOR_EXTRA_PKGS:-}"
missing=""
for p in $PKGS; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
  echo "[setup] installing:$missing"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
fi
[ "${1:-}" = "--packages-only" ] && exit 0
BUILD_DIR=${STENTOR_BUILD_DIR:-build}
if [ ! -f "$BUILD_DIR/build.ninja" ]; then
  cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release ${STENTOR_CMAKE_ARGS:-}
fi
cmake --build "$BUILD_DIR" -j "${STENTOR_JOBS:-$(nproc)}"
