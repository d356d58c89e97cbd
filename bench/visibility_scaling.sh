#!/usr/bin/env bash
# Issue 36's second target: the local pass's cost per pixel against the scene's size, on the
# procedural building of 1, 3 and 9 storeys (5 x 5 rooms each; data/building/make_building.py),
# with the visibility culling (localpass/visible_set.h) and, where it ends in minutes, without.
# Each building is solved with the coarse settings for its first 300 shots (the cost per pixel
# depends on the elements and polygons, not on how far the solve went), then bench/pixel_profile
# runs on one thread over SIZE x SIZE pixels of the building's camera at tolerance 0.05, and
# prints the counts per pixel. Writes bench/results/visibility_scaling.md. About 10 minutes.
# Usage: bash bench/visibility_scaling.sh [BUILD_DIR] [SIZE]   (build 6)
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/provenance.sh
build=${1:-build}
size=${2:-6}
out=bench/results/visibility_scaling.md
work=$(mktemp -d)
tmp=$(mktemp)
trap 'rm -rf "$work" "$tmp"' EXIT
profile() {  # SCENE SOLUTION VISIBLE_SET_FROM -> the profile's line
  "$build/bench/pixel_profile" "$1" "$2" "$size" 0.05 hemisphere "$3" 2>/dev/null | tail -1
}
{
  echo "# Cost per pixel against the building's size (issue 36, second target)"
  echo
  echo "Produced by \`bash bench/visibility_scaling.sh $build $size\`."
  provenance geometry scene hemisphere vertex radiosity octree localpass bench
  echo
  echo "The building of \`data/building/make_building.py\` with 5 x 5 rooms a storey, solved with"
  echo "\`--element-levels 0 --refine-threshold 0 --max-shots 300 --solver progressive\`; the hemisphere local pass at"
  echo "tolerance 0.05 over $size x $size pixels of the building's camera, one thread"
  echo "(\`bench/pixel_profile\`). \"Polygons it may see\": what the visibility culling keeps per pixel"
  echo "(the roots of the sum and the candidate blockers); without it, every polygon is both. The"
  echo "values are the same with and without it (tests/localpass/visible_set_test.cpp)."
  echo
  echo "| storeys | polygons | culling | ms per pixel | polygons it may see | clusters | faces exact | projected |"
  echo "|---|---|---|---|---|---|---|---|"
  for storeys in 1 3 9; do
    scene="$work/b$storeys.json"
    python3 data/building/make_building.py --storeys "$storeys" -o "$scene" 2>/dev/null
    "$build/cli/radiosity" solve "$scene" --solver progressive --element-levels 0 --refine-threshold 0 --max-shots 300 \
      -o "$work/b$storeys.vtp" >/dev/null 2>&1
    polygons=$("$build/cli/radiosity" info "$scene" 2>/dev/null | awk '$1 == "polygons" {print $2}')
    settings=(on)
    [ "$storeys" -le 3 ] && settings+=(off)  # 9 storeys without it: about 30 s a pixel
    for culling in "${settings[@]}"; do
      from=0
      [ "$culling" = off ] && from=2000000000
      line=$(profile "$scene" "$work/b$storeys.vtp" "$from")
      # "...; N pixels, U us/pixel; per pixel: clusters C, exact E (unoccluded .), gathers .,
      # projected P, polygons it may see V of T"
      echo "$line" | python3 -c "
import re, sys
line = sys.stdin.read()
num = lambda key: re.search(key + r' ([0-9.]+)', line).group(1)
us = float(re.search(r'([0-9.]+) us/pixel', line).group(1))
seen = re.search(r'may see ([0-9.]+)', line)
print('| $storeys | $polygons | $culling | %.1f | %s | %s | %s | %s |' % (us / 1000,
      seen.group(1) if seen and '$culling' == 'on' else 'all', num('clusters'), num('exact'),
      num('projected')))"
    done
  done
} >"$tmp"
mv "$tmp" "$out"
trap 'rm -rf "$work"' EXIT
echo "wrote $out" >&2
