#!/usr/bin/env bash
# The long fuzz campaign (issue 16): every target until FUZZ_RUNS executions (default 1,000,000)
# or FUZZ_SECONDS (default 3600, the issue's "one million executions or one hour"), FUZZ_JOBS
# targets at a time (default 2), each after replaying its regression set. Writes
# fuzz/results/campaign.md: the machine and one row per target with the commit it ran. Each
# target's row is kept in fuzz/results/rows/<target>.md; with FUZZ_TARGETS (space-separated;
# empty: none, only the table is assembled) only those run, and the table takes the other rows
# from there or, failing that, from the last table (a target rerun after a fix). Exits 1 when a
# row has a finding (kept under BUILD/fuzz-findings/).
# Usage: bash fuzz/campaign.sh [FUZZ_BUILD_DIR] [RADIOSITY]   (make fuzz-campaign)
set -uo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-fuzz}
radiosity=${2:-build/cli/radiosity}
runs=${FUZZ_RUNS:-1000000}
seconds=${FUZZ_SECONDS:-3600}
jobs=${FUZZ_JOBS:-2}
# The slowest first, so that the parallel runs end together.
all="fuzz_exr fuzz_solution fuzz_scene fuzz_mesh_obj fuzz_mesh_ply fuzz_mesh_off fuzz_mesh_stl \
fuzz_mtl fuzz_points"
targets=${FUZZ_TARGETS-$all}
rows=$(mktemp -d)
trap 'rm -rf "$rows"' EXIT
commit=$(git rev-parse --short HEAD)$(git diff --quiet HEAD -- . ':!fuzz/results' || echo "-dirty")
out=fuzz/results/campaign.md
kept=fuzz/results/rows
mkdir -p "$kept"

# run.sh runs them FUZZ_JOBS at a time and prints one row per target.
if [ -n "$(echo $targets)" ]; then
  FUZZ_TARGETS="$(echo $targets)" FUZZ_JOBS=$jobs FUZZ_RUNS=$runs FUZZ_NO_HEADER=1 \
    bash fuzz/run.sh "$build" "$seconds" "$radiosity" >"$rows/all.md"
fi
for t in $targets; do
  grep "^| $t |" "$rows/all.md" | sed "s/ |\$/ | $commit, $(date -u +%Y-%m-%d) |/" >"$kept/$t.md"
done
# Rows of targets not run now: kept ones, or the last table's.
for t in $all; do
  if [ -s "$kept/$t.md" ]; then
    cp "$kept/$t.md" "$rows/$t.md"
  elif [ -f "$out" ]; then
    grep "^| $t |" "$out" >"$rows/$t.md"
  fi
done

mkdir -p fuzz/results
{
  echo "# Fuzz campaign"
  echo
  echo "*Written by \`make fuzz-campaign\` (\`fuzz/campaign.sh\`); do not edit.*"
  echo
  echo "- command: \`make fuzz-campaign\` (FUZZ_RUNS=$runs, FUZZ_SECONDS=$seconds, FUZZ_JOBS=$jobs;"
  echo "  FUZZ_TARGETS=\"...\" reruns some targets and keeps the other rows)"
  echo "- machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
  echo "- build: $(clang --version | head -1), -fsanitize=fuzzer,address,undefined, leak detection on"
  echo
  echo "Each target runs until $runs executions or $seconds seconds, whichever comes first, on the"
  echo "corpus of earlier runs (seeded from \`tests/data/\` and \`data/\`), after its regression set."
  echo
  echo "| target | seconds | executions | corpus files | result | commit, date |"
  echo "|---|---|---|---|---|---|"
  for t in $all; do cat "$rows/$t.md" 2>/dev/null; done
} >"$out.tmp"
mv "$out.tmp" "$out"
cat "$out"
! grep -q "FINDING\|FAILED" "$out"
