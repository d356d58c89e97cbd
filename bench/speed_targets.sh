#!/usr/bin/env bash
# Issue 36's first target in one run (bench/speed_targets.cpp): the demo's solution at 512 x 512,
# tolerance 0.01, both exact methods against Monte Carlo 1024, the bound checked on a grid of
# pixels against the tolerance-0 gather. Writes bench/results/speed_targets.md. About 20 minutes
# on 2 cores.
# Usage: bash bench/speed_targets.sh [BUILD_DIR] [SIZE] [TOLERANCE] [STRIDE]   (build 512 0.01 8)
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/provenance.sh
build=${1:-build}
size=${2:-512}
tolerance=${3:-0.01}
stride=${4:-8}
out=bench/results/speed_targets.md
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
{
  echo "# The certified 1% image against issue 36's first target"
  echo
  echo "Produced by \`bash bench/speed_targets.sh $build $size $tolerance $stride\`."
  provenance geometry scene hemisphere vertex radiosity octree localpass render bench
  echo
  echo "Seconds are the render's own (rays and gathers, all cores), one run each, all in one run"
  echo "of this program. The target: at most 10 s, and at most 0.25 of a 1024-ray Monte Carlo"
  echo "image in the same run, with no bound violation. Errors are relative on the brightest"
  echo "channel; a violation is a checked pixel whose error exceeds its certified bound. Each"
  echo "method runs twice: every pixel on its own, and with the certified interpolation over"
  echo "cells of 8 x 8 pixels (localpass/tile_gather.h; \"pixels interpolated\": those whose"
  echo "smooth part a cell interpolated, the rest gathered at the pixel)."
  echo
  "$build/bench/speed_targets" "$size" "$tolerance" "$stride"
} >"$tmp"
mv "$tmp" "$out"
echo "wrote $out" >&2
