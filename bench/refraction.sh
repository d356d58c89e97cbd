#!/usr/bin/env bash
# The refraction heuristic of paper 000 §4 against the path tracer, at each setting of the
# accuracy knob (issue 19): bench/results/refraction.md and the charts
# docs/images/refraction-knob.png (error against --refraction-tolerance) and
# docs/images/refraction-cost.png (error against time). About 10 minutes on 2 cores.
# Usage: bash bench/refraction.sh [BUILD_DIR] [PATHS]
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/provenance.sh
build=${1:-build}
paths=${2:-400000}
out=bench/results
mkdir -p "$out" docs/images
table=$("$build/bench/refraction_bench" docs/images/refraction-knob.png docs/images/refraction-cost.png "$paths")
{
  echo "# The refraction heuristic against the path tracer"
  echo
  echo "Produced by \`bash bench/refraction.sh\` (\`$build/bench/refraction_bench\`): on each scene of"
  echo "\`data/refraction/\` (the lamp of the Cornell box over one transparent object in a black room;"
  echo "\`scripts/refraction_scenes.py\` writes them), at the floor points beside it, the local pass"
  echo "(vertex tracing of the lamp's emission, exact elsewhere) with the refraction heuristic of"
  echo "paper 000 §4 at each setting of \`--refraction-tolerance\` (at most 256 pieces a facet), against"
  echo "two path-traced references of the scene itself: the heuristic's model (what interfaces"
  echo "reflect dropped, \`probe --no-interface-reflections\`, 2 crossings) and the physics (every"
  echo "Fresnel and total internal reflection followed, 8 crossings). Errors: RMS over points and"
  echo "channels of (value - reference) / the reference's mean over the points. Seconds: the gathers"
  echo "at the points on all cores, the median of at least 3 runs (one from 10 s); \"x opaque\" is the ratio to the"
  echo "first row, the same scene with refraction off (its objects opaque, \`\"refraction_depth\": 0\`)."
  echo "The charts:"
  echo "[error against the knob](../../docs/images/refraction-knob.png),"
  echo "[error against time](../../docs/images/refraction-cost.png)."
  provenance geometry scene localpass data/refraction bench/refraction_bench.cpp bench/heuristic_measures.h
  echo
  echo "$table"
} > "$out/refraction.md"
cat "$out/refraction.md"
