#!/usr/bin/env bash
# Installs the Debian packages this project builds against, and only those that are missing.
# Idempotent: a second run installs nothing. Uses sudo when not run as root.
set -euo pipefail

packages=(
  cmake g++ make pkg-config
  libeigen3-dev libopenmesh-dev libembree-dev libtbb-dev
  libvtk9-dev libopenexr-dev python3-imath
  libgtest-dev libbenchmark-dev libcli11-dev nlohmann-json3-dev libboost-dev
  xvfb xauth
  clang-format python3
  clang libclang-rt-14-dev
  libopenmpi-dev openmpi-bin
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present" >&2
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi

echo "install-deps: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done" >&2
