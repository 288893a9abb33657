#!/usr/bin/env bash
# One command from a fresh Debian 12 clone to a working drape:
#   1. installs every build dependency with apt-get (sudo only when not root),
#   2. configures (Release) and builds into $BUILD_DIR (default: build),
#   3. runs the main job on built-in defaults.
# Environment: BUILD_DIR (build folder, default build), SKIP_APT=1 (dependencies
# already installed), JOBS (parallel build jobs, default nproc).
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."
BUILD_DIR=${BUILD_DIR:-build}
JOBS=${JOBS:-$(nproc)}

# The time and the CPU time (user + system) its commands have used so far: where
# a set-up's minutes go, even on a busy machine (scripts/ci_timing.sh reads them).
step() {
  local t="${TMPDIR:-/tmp}/drape-setup-times.$$" cpu
  times >"$t"  # in this shell: its children's CPU time is the second line
  cpu=$(awk 'NR == 2 { split($1, u, /[ms]/); split($2, s, /[ms]/); printf "%.1f", 60 * (u[1] + s[1]) + u[2] + s[2] }' "$t")
  rm -f "$t"
  printf '\n==> [%s, %s s CPU] %s\n' "$(date +%T)" "$cpu" "$*"
}
fail() { printf 'setup.sh: error: %s\n' "$*" >&2; exit 1; }

PACKAGES=(
  build-essential cmake pkg-config
  ccache  # a rebuild of what this machine compiled before takes seconds (cmake/DrapeCompilerCache.cmake)
  libeigen3-dev libspectra-dev libyaml-cpp-dev libhdf5-dev zlib1g-dev libassimp-dev
  libboost-dev libboost-program-options-dev libboost-filesystem-dev
  catch2 libnanoflann-dev libopenblas-dev libsuitesparse-dev
  chromium  # headless, for the test that the 3D viewer pages of drape render draw
  valgrind  # tests/memcheck.sh: the energies' derivatives under memcheck
  # the Python package (python/, docs/python.md): built for Debian's /usr/bin/python3; tests and example
  pybind11-dev python3-dev python3-numpy python3-scipy python3-h5py python3-pytest python3-torch
  python3-yaml  # scripts/check_dataset_drapes.py reads the scene a dataset records
  libopenmpi-dev openmpi-bin  # optional: mpirun -np N drape train (docs/cluster.md)
)

install_dependencies() {
  if [[ "${SKIP_APT:-0}" == 1 ]]; then
    step "Skipping apt-get (SKIP_APT=1)"
    return
  fi
  command -v apt-get >/dev/null || fail "apt-get not found: install these packages by hand, then rerun with SKIP_APT=1: ${PACKAGES[*]}"
  local sudo=()
  if [[ $(id -u) -ne 0 ]]; then
    command -v sudo >/dev/null || fail "not root and sudo is missing: run as root or install: ${PACKAGES[*]}"
    sudo=(sudo)
  fi
  step "Installing dependencies with apt-get: ${PACKAGES[*]}"
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${PACKAGES[@]}"
}

build() {
  step "Configuring (Release, unity build) into $BUILD_DIR"
  # Unity build: each target's sources compiled in batches of 8, which parse and
  # instantiate their shared Eigen/yaml-cpp/HDF5 code once per batch instead of
  # once per file (a clean build's CPU time about a third less, docs/ci.md). An edit then
  # recompiles its batch; -DCMAKE_UNITY_BUILD=OFF on the folder for file by file.
  # With ccache installed every compile goes through it (CMakeLists.txt), so a
  # second clone, a deleted build folder or CI's next run reuses the objects.
  cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON
  step "Building with $JOBS jobs"
  cmake --build "$BUILD_DIR" -j "$JOBS"
}

# The main job on built-in defaults, end to end on the default body and
# T-shirt: a body, the template's assets, one simulated drape, the graphs, and
# finally the shipped pretrained model's prediction on a BMI 35 body.
main_job() {
  local DRAPE="$BUILD_DIR/bin/drape"
  [[ -x "$DRAPE" ]] || fail "$DRAPE was not built"
  mkdir -p out
  step "Plugins"
  "$DRAPE" plugins --brief
  step "A body of BMI 35 from the built-in parametric model"
  "$DRAPE" body --bmi 35 --height 1.75 --out out/body_bmi35.obj
  step "Assets of the default T-shirt (built once, then cached)"
  "$DRAPE" assets
  step "Simulating the coarse T-shirt on the BMI 35 body (only the effects the scene names)"
  # Exit code 1 with a written mesh means the drape did not reach the settle
  # tolerance (it says why, docs/scenes.md): reported,
  # not fatal. Anything else is a failure.
  local rc=0
  rm -f out/garment_simulated.obj
  "$DRAPE" simulate graphs/scenes/tshirt_coarse.yaml --bmi 35 --out out/garment_simulated.obj --body-out out/body_simulated.obj || rc=$?
  if [[ $rc -ne 0 ]]; then
    [[ $rc -eq 1 && -s out/garment_simulated.obj ]] || fail "drape simulate failed (exit $rc)"
    echo "note: the drape did not settle; the lines above say why (see docs/scenes.md)"
  fi
  step "Checking the seed's model graph against the template"
  "$DRAPE" graph check graphs/drape.yaml --resolution coarse | tail -n 1
  step "A page to look at: the shipped model's drape in a 3D viewer, coloured by its distance to the body (open out/drape.html)"
  "$DRAPE" render --bmi 35 --out out/drape.html
  step "Predicting the T-shirt on a BMI 35 body with the shipped pretrained model (no training needed)"
  "$DRAPE" predict --bmi 35 --out out/garment.obj --body-out out/body.obj --svg out/garment.svg
}

install_dependencies
build
main_job
step "Done. Run the tests with: ctest --test-dir $BUILD_DIR --output-on-failure --no-tests=error -j2"
