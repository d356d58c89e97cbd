#!/usr/bin/env bash
# Installs the Debian packages this project needs, and only those that are missing.
#   install-deps.sh run    what building and running the radiosity executable needs (make demo)
#   install-deps.sh all    that and what the tests, benchmarks, formatting and fuzzing need
#                          (make test, make format-check, make fuzz)
# Idempotent: a second run installs nothing. Uses sudo when not run as root.
set -euo pipefail

set_name=${1:-all}
run_packages=(
  cmake g++ make ninja-build pkg-config
  libeigen3-dev libopenmesh-dev libembree-dev libtbb-dev
  libvtk9-dev libopenexr-dev python3-imath
  libcli11-dev nlohmann-json3-dev libboost-dev
  libopenmpi-dev   # VTK's charts link MPI; with it, render, probe and sweep run under mpirun
  xvfb xauth       # export draws patch_mesh.png offscreen
)
test_packages=(
  libgtest-dev libbenchmark-dev
  openmpi-bin      # mpirun, for the MPI tests
  assimp-testmodels  # OBJ+MTL models from the wild (tests/scene/mtl_test.cpp)
  clang-format python3
  clang libclang-rt-14-dev  # libFuzzer (make fuzz)
)
case "$set_name" in
  run) packages=("${run_packages[@]}") ;;
  all) packages=("${run_packages[@]}" "${test_packages[@]}") ;;
  *) echo "install-deps: unknown set '$set_name' (run or all)" >&2; exit 2 ;;
esac

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages ($set_name) present" >&2
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi

echo "install-deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done" >&2
