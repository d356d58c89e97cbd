#!/usr/bin/env bash
# The cost of paper 000's filters and mirrors against the opaque Cornell box: the same box with
# the stained-glass pane, with the mirror, and with both (data/cornell-glass-mirror), each
# solved at the default settings and rendered by the exact local pass (vertex tracing, the one
# method that takes filters) at 96 x 96 and tolerance 0.1, with and without the culling beams.
# Writes bench/results/filters_mirrors.md. Usage: bash bench/filters_mirrors.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/provenance.sh
build=${1:-build}
radiosity="$build/cli/radiosity"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 - "$work" <<'PY'
import json, sys
work = sys.argv[1]
full = json.load(open("data/cornell-glass-mirror/scene.json"))
full["objects"] = [dict(o, mesh="../../" + o["mesh"]) if "mesh" in o else o for o in full["objects"]]
variants = {
    "opaque": lambda o: o["name"] != "wall mirror" and not o["name"].startswith("pane"),
    "glass": lambda o: o["name"] != "wall mirror",
    "mirror": lambda o: not o["name"].startswith("pane"),
    "glass-and-mirror": lambda o: True,
}
for name, keep in variants.items():
    scene = dict(full, objects=[o for o in full["objects"] if keep(o)])
    json.dump(scene, open(f"{work}/{name}.json", "w"))
PY
seconds() { grep -o 'in [0-9.e+-]* s' "$1" | head -1 | awk '{print $2}'; }
{
  echo "# Filters and mirrors against the opaque Cornell box"
  echo
  echo "Produced by \`bash bench/filters_mirrors.sh\`: each variant of \`data/cornell-glass-mirror\`"
  echo "solved at the default settings, then \`render --method vertex --width 96 --height 96\` (tolerance 0.1),"
  echo "with and without \`--no-mirror-culling\`. One run each (the ratios are what to read)."
  provenance . ':!bench/results'
  echo
  echo "| scene | elements | solve s | render s | render / opaque | faces gathered exactly per pixel | render s, no culling beams |"
  echo "|---|---|---|---|---|---|---|"
  opaque_render=""
  for name in opaque glass mirror glass-and-mirror; do
    "$radiosity" solve "$work/$name.json" -o "$work/$name.vtp" 2> "$work/$name.solve.log" >/dev/null
    elements=$(grep -o '[0-9]* elements' "$work/$name.solve.log" | head -1 | awk '{print $1}')
    solve_s=$(grep -o ', [0-9.]* s$' "$work/$name.solve.log" | head -1 | awk '{print $2}')
    "$radiosity" render "$work/$name.json" --solution "$work/$name.vtp" --method vertex --width 96 --height 96 \
      -o "$work/$name.exr" --no-preview 2> "$work/$name.render.log" >/dev/null
    render_s=$(seconds "$work/$name.render.log")
    gathered=$(grep -o 'mean [0-9.]*' "$work/$name.render.log" | head -1 | awk '{print $2}')
    "$radiosity" render "$work/$name.json" --solution "$work/$name.vtp" --method vertex --width 96 --height 96 \
      --no-mirror-culling -o "$work/$name.nocull.exr" --no-preview 2> "$work/$name.nocull.log" >/dev/null
    nocull_s=$(seconds "$work/$name.nocull.log")
    [ -n "$opaque_render" ] || opaque_render=$render_s
    ratio=$(python3 -c "print(f'{$render_s / $opaque_render:.1f}')")
    echo "| $name | $elements | $solve_s | $render_s | $ratio | $gathered | $nocull_s |"
  done
} > bench/results/filters_mirrors.md
cat bench/results/filters_mirrors.md
