#!/usr/bin/env bash
# The stability report: bench/stability_bench over the degenerate scene families, with the
# machine and command, to bench/results/stability.md. Usage: bash bench/stability.sh [BUILD_DIR]
# (or: make stability; make bench runs it too).
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/provenance.sh
build=${1:-build}
out=bench/results/stability.md
{
  echo "# Stability: the degenerate scene families through both exact gatherers and Monte Carlo"
  echo
  echo "Produced by \`make stability\` (\`$build/bench/stability_bench\`), one thread."
  provenance geometry scene hemisphere vertex localpass bench/stability_bench.cpp tests/random_scenes.h
  echo
  echo "Direct light: every polygon occludes from both sides, the lamps emit. Seeded scenes (seed"
  echo "100000 x family + scene); each row gathers at every site of every scene with the hemisphere"
  echo "gatherer, vertex tracing and Monte Carlo (4096 cosine-weighted rays, seeded). Differences are"
  echo "max_c |a - b| / max_c |b| against the hemisphere gatherer. For the filter families (000 §2.2)"
  echo "the hemisphere column is the identity of independent removals, a sum of opaque hemisphere"
  echo "gathers (tests/filter_identity.h), against vertex tracing; for the mirror families (000 §3)"
  echo "both exact methods run through the local pass at tolerance 0, which unfolds the mirrors, and"
  echo "Monte Carlo's rays reflect off them."
  echo
  "$build/bench/stability_bench"
} > "$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out" >&2
