#!/usr/bin/env bash
# Specular transfer in the global solution (issue 37), before and after, against the scene's
# path tracer at 40 points of the ceiling, the back wall, the floor and the side walls
# (scripts/specular_solution.py writes the points and two of the scenes):
# - glass: the solver carries refracting objects as filters, unbent
#   (SolverSettings::glass_as_filters), where it had them opaque and black (`--opaque-glass`),
#   on the Cornell box with a glass block and a prism (data/cornell-glass-prism/) and with a
#   glass pane under its lamp;
# - a point light seen in a mirror: the Cornell box lit by a point light, a mirror on its back
#   wall; the local pass, the solver and the path tracer now carry the light's image. Before:
#   the binary of commit BASE (default d17c760, the main issue 37 was filed against; built
#   once by bench/earlier_binary.sh).
# - glossy: the light a glossy ring reflects from the lit floor (not carried: the beams start
#   at point sources), measured on the ring's white floor against a black one.
# Writes bench/results/specular_solution.md. About 15 minutes on 2 cores (plus building BASE).
# Usage: bash bench/specular_solution.sh [BUILD_DIR] [PATHS] [BASE]   (build 400000 d17c760)
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/provenance.sh
source bench/earlier_binary.sh
build=${1:-build}
paths=${2:-400000}
base=${3:-d17c760}
radiosity="$build/cli/radiosity"
before=$(earlier_radiosity "$base")
out=bench/results/specular_solution.md
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 scripts/specular_solution.py scenes "$work"
points="$work/points.csv"
table() { python3 scripts/specular_solution.py table "$@"; }

# the seconds of solve's summary line: "solve: ..., 31.2 s"
seconds() { grep '^solve:' "$1" | grep -o '[0-9.]\+ s$' | cut -d' ' -f1; }

# solve_and_probe BINARY SCENE NAME [SOLVE FLAGS...]: NAME.csv, the local pass over the
# solution (vertex, tolerance 0.01; refraction by the knob at 0.05, so that the solution's
# error, not the heuristic's, shows), and NAME.log, the solve's summary.
solve_and_probe() {
  local binary=$1 scene=$2 name=$3
  shift 3
  "$binary" solve "$scene" "$@" -o "$work/$name.vtp" 2>"$work/$name.log" >/dev/null
  local knob=()
  grep -q '"ior"' "$scene" && knob=(--refraction-tolerance 0.05)
  "$binary" probe "$scene" -s "$work/$name.vtp" -p "$points" -m vertex -t 0.01 "${knob[@]}" \
    -o "$work/$name.csv" 2>/dev/null
}

reference() {  # reference SCENE NAME [FLAGS...]: the path tracer's NAME.csv
  local scene=$1 name=$2
  shift 2
  "$radiosity" probe "$scene" -p "$points" -m pathtrace --samples "$paths" "$@" \
    -o "$work/$name.csv" 2>/dev/null
}

{
  echo "# Specular transfer in the global solution, before and after"
  echo
  echo "Produced by \`bash bench/specular_solution.sh\`: the local pass (\`probe --method vertex"
  echo "--tolerance 0.01\`, E plus the refraction heuristic's \`refracted\` light, the knob at"
  echo "\`--refraction-tolerance 0.05\` so that the solution's error shows, not the heuristic's) over"
  echo "each solution (\`solve\` at the default settings) at 40 points of the ceiling, the back wall,"
  echo "the floor away from the objects and both side walls (\`scripts/specular_solution.py\`), against"
  echo "the scene's path tracer at $paths paths a point. Errors: RMS over the points and channels of"
  echo "(value - reference) / the reference's mean over them, in %."
  provenance radiosity localpass scene scripts/specular_solution.py bench/specular_solution.sh
  echo
  echo "## Glass: opaque and black to the solver (before), carried as filters, unbent (after)"
  echo
  echo "The references: the physics (every Fresnel and total internal reflection) and the"
  echo "heuristic's model (\`--no-interface-reflections\`)."
  for scene in data/cornell-glass-prism/scene.json "$work/cornell-glass-pane.json"; do
    name=cornell-glass-prism
    [[ $scene == "$work"/* ]] && name=cornell-glass-pane
    reference "$scene" physics
    reference "$scene" model --no-interface-reflections
    solve_and_probe "$radiosity" "$scene" opaque --opaque-glass
    solve_and_probe "$radiosity" "$scene" filters
    echo
    echo "### $name"
    echo
    table "$work/physics.csv" "$work/model.csv" \
      "glass opaque (solve $(seconds "$work/opaque.log") s)=$work/opaque.csv" \
      "glass as filters (solve $(seconds "$work/filters.log") s)=$work/filters.csv"
  done
  echo
  echo "## A point light seen in a mirror: before ($base) and after"
  echo
  echo "The Cornell box lit by a point light, a mirror on its back wall (specular 0.9). The"
  echo "reference: this commit's path tracer, whose next-event light includes the light's image"
  echo "(tested against the closed form); before, the path tracer lacked it too (its row)."
  scene="$work/cornell-mirror-light.json"
  reference "$scene" physics
  "$before" probe "$scene" -p "$points" -m pathtrace --samples "$paths" \
    -o "$work/path-before.csv" 2>/dev/null
  solve_and_probe "$before" "$scene" before
  solve_and_probe "$radiosity" "$scene" after
  echo
  table "$work/physics.csv" - \
    "before: the local pass over its solution (solve $(seconds "$work/before.log") s)=$work/before.csv" \
    "before: the path tracer=$work/path-before.csv" \
    "after: the local pass over its solution (solve $(seconds "$work/after.log") s)=$work/after.csv"
  echo
  echo "## Glossy: the light of the solution's patches reflected by a glossy ring (not carried)"
  echo
  echo "The ring of \`data/glossy-ring/\` (gloss 0.08) under its point light, at its 33 floor points"
  echo "(\`ring-points.csv\`), E plus the beams' \`glossy\` light. The beams start at point sources"
  echo "(paper 003): what the floor's own light sends off the ring back to the floor is missing."
  echo "On a black floor that light is 0, and the error is the beams' own; on the white floor the"
  echo "difference is the missing light. Reference: the path tracer (it samples the lobes)."
  for floor in black white; do
    scene="$work/glossy-ring-$floor.json"
    "$radiosity" probe "$scene" -p data/glossy-ring/ring-points.csv -m pathtrace \
      --samples "$paths" -o "$work/ring-reference-$floor.csv" 2>/dev/null
    "$radiosity" solve "$scene" -o "$work/ring-$floor.vtp" 2>/dev/null >/dev/null
    "$radiosity" probe "$scene" -s "$work/ring-$floor.vtp" -p data/glossy-ring/ring-points.csv \
      -m vertex -t 0.01 -o "$work/ring-$floor.csv" 2>/dev/null
  done
  echo
  echo "| floor | the local pass's RMS error (%) |"
  echo "|---|---|"
  for floor in black white; do
    e=$(table "$work/ring-reference-$floor.csv" - "x=$work/ring-$floor.csv" | awk -F'|' '$2 == " x " {print $3}')
    echo "| $floor |$e|"
  done
} >"$out"
cat "$out"
