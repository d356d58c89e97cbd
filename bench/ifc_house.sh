#!/usr/bin/env bash
# Issue 36's fourth target: a real model nobody here wrote. Debian's assimp-testmodels holds an
# IFC house (AC14-FZK-Haus.ifc, Karlsruhe Institute of Technology); Assimp's command line
# exports it as OBJ+MTL, scripts/ifc_house.py makes it a scene (one mesh per material, a sky of
# emitting quads, a ground, a camera at 512 x 384). The scene is solved at the solver's default
# accuracy, shown from the solution (`render --method patches`, 512 x 384) and by the exact
# local pass (hemisphere, default tolerance) at EXACT_WIDTH x 3/4 of it; bench/pixel_profile
# gives the local pass's counts per pixel on 4 x 4 pixels. Writes bench/results/ifc_house.md and
# docs/images/ifc-house-*.png. About 30 minutes on 2 cores (the solve 15, the exact pass 12).
# Needs: apt-get install assimp-utils assimp-testmodels.
# Usage: bash bench/ifc_house.sh [BUILD_DIR] [EXACT_WIDTH]   (build 48)
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/provenance.sh
build=${1:-build}
exact_width=${2:-48}
exact_height=$((exact_width * 3 / 4))
model=/usr/share/assimp/models/IFC/AC14-FZK-Haus.ifc
if ! command -v assimp >/dev/null || [ ! -f "$model" ]; then
  echo "ifc_house: needs Assimp's command line and test models: apt-get install assimp-utils assimp-testmodels" >&2
  exit 1
fi
out=bench/results/ifc_house.md
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
radiosity="$build/cli/radiosity"

assimp export "$model" "$work/model.obj" -tri -jiv -fd >/dev/null
python3 scripts/ifc_house.py "$work/model.obj" "$work/house" >"$work/convert.log"
scene="$work/house/scene.json"
polygons=$("$radiosity" info "$scene" 2>/dev/null | awk '$1 == "polygons" {print $2}')

# seconds of a command's own summary line: "solve: ..., 916 s" / "render: ... in 1.3 s; ..."
"$radiosity" solve "$scene" -o "$work/coarse.vtp" --element-levels 0 --refine-threshold 0 \
  --unshot 0.02 2>"$work/coarse.log" >/dev/null
"$radiosity" solve "$scene" -o "$work/solution.vtp" 2>"$work/solve.log" >/dev/null
# (render prints its summary on stderr)
"$radiosity" render "$scene" --method patches --solution "$work/solution.vtp" \
  -o "$work/patches.exr" --preview docs/images/ifc-house-patches.png 2>"$work/patches.log"
"$radiosity" render "$scene" --method hemisphere --solution "$work/solution.vtp" \
  --width "$exact_width" --height "$exact_height" -o "$work/exact.exr" \
  --preview docs/images/ifc-house-exact.png 2>"$work/exact.log"
profile=$("$build/bench/pixel_profile" "$scene" "$work/solution.vtp" 4 0.1 2>/dev/null | tail -1)

summary() { grep -m1 "^$1:" "$2"; }
solve_seconds() { summary solve "$1" | sed -E 's/.*, ([0-9.]+) s$/\1/'; }
render_seconds() { summary render "$1" | sed -E 's/.* in ([0-9.]+) s;.*/\1/'; }
exact_s=$(render_seconds "$work/exact.log")
per_pixel=$(awk -v s="$exact_s" -v n=$((exact_width * exact_height)) 'BEGIN {printf "%.3f", s / n}')
full_hours=$(awk -v p="$per_pixel" 'BEGIN {printf "%.1f", p * 512 * 384 / 3600}')
{
  echo "# A real model: the IFC house of Debian's assimp-testmodels (issue 36, fourth target)"
  echo
  echo "Produced by \`bash bench/ifc_house.sh $build $exact_width\`."
  provenance geometry scene hemisphere radiosity octree localpass render cli scripts/ifc_house.py
  echo
  echo "AC14-FZK-Haus.ifc through \`assimp export MODEL.ifc model.obj -tri -jiv -fd\` and"
  echo "\`scripts/ifc_house.py\` (Lambertian materials from the MTL's \`Kd\`, glass opaque and dark, a"
  echo "sky of emitting quads, a ground): $polygons polygons. Seconds are each command's own, all cores."
  echo
  echo "| step | settings | result | seconds |"
  echo "|---|---|---|---|"
  echo "| solve, coarse | \`--element-levels 0 --refine-threshold 0 --unshot 0.02\` | $(summary solve "$work/coarse.log" | sed -E 's/^solve: //; s/, [0-9.]+ s$//') | $(solve_seconds "$work/coarse.log") |"
  echo "| solve, default accuracy | defaults | $(summary solve "$work/solve.log" | sed -E 's/^solve: //; s/, [0-9.]+ s$//') | $(solve_seconds "$work/solve.log") |"
  echo "| the solution shown | \`render --method patches\`, 512 x 384 | ![](../../docs/images/ifc-house-patches.png) | $(render_seconds "$work/patches.log") |"
  echo "| the exact local pass | \`render --method hemisphere\` (tolerance 0.1), $exact_width x $exact_height | ![](../../docs/images/ifc-house-exact.png) | $exact_s |"
  echo
  echo "The exact pass took $per_pixel s a pixel on all cores: 512 x 384 would take about $full_hours hours."
  echo "Per pixel (bench/pixel_profile, 4 x 4 pixels, one thread, tolerance 0.1):"
  echo
  echo "    $profile"
} >"$out"
cat "$out"
