#!/usr/bin/env bash
# Issue 15's benchmark of the local pass: both methods at tolerances 0 to 0.2 at the camera's
# 512 x 512 on the demo's solution (the default solve) and at 256 x 256 on the 2,948-element
# uniform one, against the hemisphere's exact image and Monte Carlo in the same run; then the
# cost per pixel against the element count. Writes bench/results/local_pass_targets.md.
# About an hour on 2 cores (the vertex tracer's exact image at 512 x 512 is left out: about
# 36 ms per pixel on one core, 75 minutes; its rows are judged against the hemisphere's).
# Usage: bash bench/local_pass_targets.sh [BUILD_DIR]   (a build with -DRAD_BUILD_BENCH=ON)
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/provenance.sh
build=${1:-build}
out=bench/results/local_pass_targets.md
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
{
  echo "# The local pass against issue 15's targets"
  echo
  echo "Produced by \`bash bench/local_pass_targets.sh $build\`."
  provenance geometry scene hemisphere vertex radiosity octree localpass formats render experiments viz cli
  echo
  echo "Seconds are the render's own (rays and gathers, all cores; scene loading and the solve left"
  echo "out), one run each, all in one run of this script. Errors are relative, per pixel on the"
  echo "brightest channel, against the hemisphere's tolerance-0 image; \"error / bound\" is the"
  echo "actual error over the certified bound (1 is tight); a violation is a pixel whose error"
  echo "exceeds its bound. \"elements gathered\": faces summed exactly (Lambert or a gather);"
  echo "\"clusters\": cluster intervals computed; \"projected\": faces and blocking polygons sent to"
  echo "the visibility structure. The last column: what Monte Carlo final gather needs for the same"
  echo "RMS error (log-log interpolation in its series below, or its samples^-1/2 law beyond it)."
  echo
  echo "## 512 x 512, the demo's solution"
  echo
  "$build/bench/local_pass_bench" 512 default 0 0
  echo
  echo "## 256 x 256, the uniform 2,948-element solution"
  echo
  "$build/bench/local_pass_bench" 256 0.07 0 1
  echo
  echo "## Cost per pixel against elements (tolerance 0.01, hemisphere, 64 x 64, one thread)"
  echo
  "$build/bench/local_pass_scaling" 64 0.01 hemisphere
} >"$tmp"
mv "$tmp" "$out"
echo "wrote $out" >&2
