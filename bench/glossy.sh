#!/usr/bin/env bash
# Glossy transfer by backward beams (paper 003) against the path tracer, and its cost against
# the number of scatterer triangles (issue 20): bench/results/glossy.md and the charts
# docs/images/glossy-sigma.png (error against sigma, per --glossy-split) and
# docs/images/glossy-cost.png (time per receiver against triangles). About 5 minutes on 2 cores.
# Usage: bash bench/glossy.sh [BUILD_DIR] [PATHS]
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/provenance.sh
build=${1:-build}
paths=${2:-400000}
out=bench/results
mkdir -p "$out" docs/images
table=$("$build/bench/glossy_bench" docs/images/glossy-sigma.png docs/images/glossy-cost.png "$paths")
{
  echo "# Glossy beams against the path tracer"
  echo
  echo "Produced by \`bash bench/glossy.sh\` (\`$build/bench/glossy_bench\`). Accuracy: the ring of"
  echo "\`data/glossy-ring/\` (40 segments, smooth) with a black floor, so that what reaches the floor"
  echo "points of \`ring-points.csv\` is the light straight and by way of the ring; the local pass"
  echo "(the light's direct light exactly, plus paper 003's beams at each \`--glossy-split\`) against"
  echo "the path tracer of the scene itself, which samples the lobes (every glossy bounce, where"
  echo "the beams follow one). Errors: RMS over points and channels of (value - reference) / the"
  echo "reference's mean over the points. Cost: the glossy gather alone at 121 points on a grid"
  echo "over the floor (as a picture's pixels), the median of at least 3 runs, with the cone hierarchy (cut at 5 sigma) and over every beam."
  echo "The charts: [error against sigma](../../docs/images/glossy-sigma.png),"
  echo "[time against triangles](../../docs/images/glossy-cost.png)."
  provenance geometry scene localpass data/glossy-ring bench/glossy_bench.cpp bench/heuristic_measures.h
  echo
  echo "$table"
} > "$out/glossy.md"
cat "$out/glossy.md"
