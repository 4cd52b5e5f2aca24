#!/usr/bin/env bash
# Builds a minimal Trilinos 13.2 with Kokkos OpenMP (+ Serial) and MPI from Debian's own
# source package, installs it to a prefix, then builds Stentor against it in
# ./build-openmp. Debian's binary Trilinos has a Serial-only Kokkos; this is the
# threaded path (README: "Threads").
#
#   bash ci/build-trilinos-openmp.sh           # ~25-30 min the first time on 2 cores
#   STENTOR_TRILINOS_OMP_PREFIX=/some/dir bash ci/build-trilinos-openmp.sh
#
# Idempotent and cached by prefix: when $PREFIX/.stentor-trilinos-stamp matches the
# package set below, the Trilinos part is skipped. Packages: Kokkos, KokkosKernels,
# Teuchos, Tpetra, Belos, Ifpack2, Amesos2 (KLU2 only; the `direct` linear solver and
# most small tests use it). MueLu, FROSch, Zoltan2 are left out: they would add an
# estimated 50-75 min to the build, and Stentor builds without them (the `muelu`
# preconditioner is then reported as unavailable in this build).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$(pwd)
PREFIX=${STENTOR_TRILINOS_OMP_PREFIX:-/opt/stentor/trilinos-13.2-openmp}
WORK=${STENTOR_TRILINOS_OMP_WORK:-/var/tmp/stentor-trilinos-src}
JOBS=${STENTOR_JOBS:-$(nproc)}
PACKAGES="Kokkos KokkosKernels Teuchos Tpetra Belos Ifpack2 Amesos2"
STAMP="trilinos-13.2 openmp+serial mpi double/int/longlong packages: $PACKAGES v2"

SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
log() { echo "[trilinos-openmp] $*"; }

# --- 1. Debian packages: the Stentor build set, compilers, the threaded OpenBLAS -----
STENTOR_EXTRA_PKGS="dpkg-dev libblas-dev liblapack-dev libopenblas0-openmp" bash ci/setup.sh --packages-only
# libopenblas0-openmp registers itself as the libblas.so.3/liblapack.so.3 alternative
# with the highest priority; say which one is live so a run log can be trusted.
log "BLAS in use: $(readlink -f /usr/lib/x86_64-linux-gnu/libblas.so.3 2>/dev/null || echo unknown)"

# --- 2. Trilinos, unless the prefix already holds this exact package set -------------
if [ -f "$PREFIX/.stentor-trilinos-stamp" ] && [ "$(cat "$PREFIX/.stentor-trilinos-stamp")" = "$STAMP" ]; then
  log "cached: $PREFIX ($STAMP)"
else
  mkdir -p "$WORK"
  SRC=$(find "$WORK" -maxdepth 1 -type d -name 'trilinos-13.2*' | head -n1)
  if [ -z "$SRC" ]; then
    # Debian's images ship binary entries only: add the matching source entry once.
    if ! grep -rqs '^Types:.*deb-src\|^deb-src' /etc/apt/sources.list /etc/apt/sources.list.d/; then
      log "adding a deb-src entry for bookworm (/etc/apt/sources.list.d/stentor-deb-src.sources)"
      $SUDO tee /etc/apt/sources.list.d/stentor-deb-src.sources >/dev/null <<'SRCS'
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm bookworm-updates
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SRCS
      $SUDO apt-get update -qq
    fi
    log "apt-get source trilinos (Debian's 13.2 with its patches) into $WORK"
    (cd "$WORK" && apt-get source -qq trilinos >/dev/null)
    SRC=$(find "$WORK" -maxdepth 1 -type d -name 'trilinos-13.2*' | head -n1)
  fi
  [ -n "$SRC" ] || { echo "error: no trilinos-13.2 source tree under $WORK" >&2; exit 1; }
  log "source: $SRC"

  LAUNCHER=""
  command -v ccache >/dev/null && LAUNCHER="-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache"
  ENABLES=""
  for p in $PACKAGES; do ENABLES="$ENABLES -DTrilinos_ENABLE_$p=ON"; done
  BUILD="$WORK/build"
  rm -rf "$BUILD"
  # Only the OpenMP node is instantiated (Tpetra's default node when OpenMP is on):
  # instantiating Serial as well would double the build for a node Stentor never uses.
  cmake -S "$SRC" -B "$BUILD" -G Ninja $LAUNCHER \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$PREFIX" \
    -DBUILD_SHARED_LIBS=ON -DCMAKE_INSTALL_RPATH="$PREFIX/lib" \
    -DCMAKE_C_COMPILER=mpicc -DCMAKE_CXX_COMPILER=mpicxx \
    -DTPL_ENABLE_MPI=ON -DTrilinos_ENABLE_OpenMP=ON \
    -DTrilinos_ENABLE_Fortran=OFF \
    -DTrilinos_ENABLE_ALL_PACKAGES=OFF -DTrilinos_ENABLE_ALL_OPTIONAL_PACKAGES=OFF \
    $ENABLES \
    -DKokkos_ENABLE_SERIAL=ON -DKokkos_ENABLE_OPENMP=ON \
    -DTpetra_INST_OPENMP=ON -DTpetra_INST_SERIAL=OFF \
    -DTpetra_INST_DOUBLE=ON -DTpetra_INST_FLOAT=OFF -DTpetra_INST_COMPLEX_DOUBLE=OFF \
    -DTpetra_INST_COMPLEX_FLOAT=OFF -DTpetra_INST_INT_INT=OFF -DTpetra_INST_INT_LONG_LONG=ON \
    -DTpetra_INST_INT_LONG=OFF -DTpetra_INST_INT_UNSIGNED=OFF -DTpetra_INST_INT_UNSIGNED_LONG=OFF \
    -DAmesos2_ENABLE_KLU2=ON \
    -DTPL_ENABLE_BLAS=ON -DTPL_ENABLE_LAPACK=ON \
    -DTrilinos_ENABLE_TESTS=OFF -DTrilinos_ENABLE_EXAMPLES=OFF \
    -DTrilinos_ENABLE_EXPLICIT_INSTANTIATION=ON \
    -DTrilinos_ENABLE_SECONDARY_TESTED_CODE=ON \
    -DTrilinos_WARNINGS_AS_ERRORS_FLAGS="" \
    -DCMAKE_CXX_FLAGS="-w" > "$WORK/configure.log" 2>&1 \
    || { tail -n 40 "$WORK/configure.log"; echo "error: Trilinos configure failed (log: $WORK/configure.log)" >&2; exit 1; }
  log "building Trilinos with $JOBS jobs (log: $WORK/build.log)"
  start=$(date +%s)
  cmake --build "$BUILD" -j "$JOBS" > "$WORK/build.log" 2>&1 \
    || { tail -n 60 "$WORK/build.log"; echo "error: Trilinos build failed (log: $WORK/build.log)" >&2; exit 1; }
  $SUDO cmake --install "$BUILD" > "$WORK/install.log" 2>&1
  echo "$STAMP" | $SUDO tee "$PREFIX/.stentor-trilinos-stamp" >/dev/null
  log "Trilinos built and installed in $(( ($(date +%s) - start) / 60 )) min: $PREFIX"
  rm -rf "$BUILD"
fi

# --- 3. Stentor against it ------------------------------------------------------------
BUILD_DIR=${STENTOR_OMP_BUILD_DIR:-build-openmp}
if [ ! -f "$BUILD_DIR/build.ninja" ]; then
  cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DTrilinos_DIR="$PREFIX/lib/cmake/Trilinos" ${STENTOR_CMAKE_ARGS:-}
fi
# STENTOR_OMP_TARGETS: build only these targets (ci/test-openmp.sh); default everything.
# shellcheck disable=SC2086
cmake --build "$BUILD_DIR" -j "$JOBS" ${STENTOR_OMP_TARGETS:+--target $STENTOR_OMP_TARGETS}
log "Stentor built in $BUILD_DIR against $PREFIX"
