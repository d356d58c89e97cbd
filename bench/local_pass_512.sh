#!/usr/bin/env bash
# The local pass at the camera's size on the demo's solution (issue 15's targets): wall seconds
# of `radiosity render` for each method and tolerance, and the ratio to Monte Carlo 1024 in the
# same run. Writes bench/results/local_pass_512.md.
# Usage: bash bench/local_pass_512.sh [BUILD_DIR] [SIZE] [EXACT_SIZE]   (defaults: build 512 256)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
size=${2:-512}
exact_size=${3:-256}
exe=$build/cli/radiosity
scene=data/cornell-box/scene.json
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
solution=$work/solution.vtp
"$exe" solve "$scene" -o "$solution" >"$work/solve.log" 2>&1
run() {  # label, size, render arguments...
  local label=$1 n=$2
  shift 2
  local start end
  start=$(date +%s.%N)
  "$exe" render "$scene" --solution "$solution" --width "$n" --height "$n" "$@" -o "$work/$label.exr" >/dev/null
  end=$(date +%s.%N)
  python3 -c "print(f'{$end - $start:.1f}')"
}
mc=$(run mc "$size" --method montecarlo --samples 1024)
{
  echo "# Local pass at ${size} x ${size} on the demo's solution"
  echo
  echo "- command: bash bench/local_pass_512.sh $build $size $exact_size"
  echo "- machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
  echo "- date: $(date -u +%Y-%m-%d)"
  echo "- commit: $(git rev-parse --short HEAD)"
  echo "- solution: $(grep -o '[0-9]* elements' "$work/solve.log" | head -1) (default solve)"
  echo
  echo "Wall seconds of \`radiosity render\` (scene load and ray casting included), all cores, one run."
  echo
  echo "| method | tolerance | size | seconds | / Monte Carlo 1024 | faces gathered exactly per pixel (mean) | largest relative bound |"
  echo "|---|---|---|---|---|---|---|"
  echo "| montecarlo (1024 samples) | - | $size | $mc | 1 | - | - |"
  for method in hemisphere vertex; do
    for t in 0.01 0.05 0.1 0.2; do
      s=$(run "$method-$t" "$size" --method "$method" --tolerance "$t")
      read -r gathered bound < <(python3 -c "import json; d=json.load(open('$work/$method-$t.stats.json')); print(round(d['emitting_per_pixel']['mean'],1), round(d['bound']['relative_max'],4))")
      echo "| $method | $t | $size | $s | $(python3 -c "print(f'{$s / $mc:.2f}')") | $gathered | $bound |"
    done
  done
  s=$(run exact "$exact_size" --method hemisphere --tolerance 0)
  echo "| hemisphere | 0 | $exact_size | $s | - | - | 0 |"
} >"$work/table.md"
mkdir -p bench/results
mv "$work/table.md" bench/results/local_pass_512.md
cat bench/results/local_pass_512.md
