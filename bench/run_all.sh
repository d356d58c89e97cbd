#!/usr/bin/env bash
# Runs every benchmark and writes its table to bench/results/, with the machine and command.
# Usage: bash bench/run_all.sh [BUILD_DIR]   (or: make bench)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
out=bench/results
mkdir -p "$out"

source bench/provenance.sh
machine() {
  provenance geometry scene hemisphere vertex radiosity octree localpass formats render experiments \
    viz cli "bench/*.cpp"
}

# Ray casting (Cornell box, 20 polygons)
json=$(mktemp)
"$build/bench/ray_casting_bench" --benchmark_repetitions=3 --benchmark_report_aggregates_only=true \
  --benchmark_out="$json" --benchmark_out_format=json >/dev/null
{
  echo "# Ray casting on the Cornell box"
  echo
  echo "Produced by \`bash bench/run_all.sh\` (\`$build/bench/ray_casting_bench --benchmark_repetitions=3\`)."
  machine
  echo
  echo "| benchmark | threads | median time | items per second |"
  echo "|---|---|---|---|"
  python3 - "$json" <<'PY'
import json, sys
data = json.load(open(sys.argv[1]))
for b in data["benchmarks"]:
    if b.get("aggregate_name") != "median":
        continue
    name = b["run_name"]
    threads = "all (TBB)" if "render" in name else "1"
    print(f"| {name} | {threads} | {b['real_time']:.3g} {b['time_unit']} | {b['items_per_second']:.3g} |")
PY
} > "$out/ray_casting.md"
rm -f "$json"
echo "wrote $out/ray_casting.md" >&2

# Progressive radiosity (Cornell box at three patch sizes, default settings otherwise)
table=$("$build/bench/solve_bench")
{
  echo "# Progressive radiosity on the Cornell box"
  echo
  echo "Produced by \`bash bench/run_all.sh\` (\`$build/bench/solve_bench\`): \`radiosity solve\` with default"
  echo "settings (unshot 1e-3, 2 x 2 initial elements per patch, refinement threshold 0.05, 3 neighbour"
  echo "passes, 16 shadow rays) but the patch size; all cores."
  machine
  echo
  echo "$table"
} > "$out/solve.md"
echo "wrote $out/solve.md" >&2

# The two exact gatherers (Cornell box meshed into ~1k, 3k, 10k patches, all emitting; and the
# 1000-thin-triangle stress scene of paper 001 Fig. 7b)
table=$("$build/bench/hemisphere_bench" 40)
{
  echo "# The exact gatherers: hemisphere projection and vertex tracing"
  echo
  echo "Produced by \`bash bench/run_all.sh\` (\`$build/bench/hemisphere_bench 40\`): irradiance at 40 seeded"
  echo "points on the floor, back wall, right wall and ceiling, with the box's polygons cut into patches"
  echo "(as \`radiosity solve\` cuts them), every patch a face of its polygon emitting 1 and every polygon"
  echo "occluding; both methods see the same faces. Then 10 floor points under 1000 thin triangles and a"
  echo "crescent-shaped source (direct light only)."
  machine
  echo
  echo "$table"
} > "$out/hemisphere.md"
echo "wrote $out/hemisphere.md" >&2

# The error-bounded local pass against tolerance 0, the naive exact gather and the Monte Carlo
# baseline: local_pass.md at LOCAL_PASS_SIZE (default 64) with the naive rows. The large images
# are bench/local_pass_targets.sh's (about 40 min on 2 cores).
local_pass_table() {
  local size=$1 naive=$2 file=$3
  local table
  table=$("$build/bench/local_pass_bench" "$size" 0.07 "$naive")
  {
    echo "# The error-bounded local pass on the Cornell box"
    echo
    echo "Produced by \`bash bench/run_all.sh\` (\`$build/bench/local_pass_bench $size 0.07 $naive\`): per method"
    echo "and tolerance, the image from the scene camera against the same method at tolerance 0; relative"
    echo "errors on each pixel's brightest channel; \"elements gathered\" counts the elements gathered"
    echo "exactly, most of them by Lambert's formula alone (nothing can hide them); \"clusters\" the"
    echo "cluster intervals computed; \"projected\" the faces and blocking polygons sent to the visibility"
    echo "structure; \"error / bound\" is the actual error over the certified bound (1 is tight); the last"
    echo "column is what the Monte Carlo gather (second table) needs for the same RMS error, interpolated"
    echo "(or extrapolated by its samples^-1/2 law). \"no culling\" rows: the naive exact gather (every"
    echo "element that can light the point, every element occluding), against the culled image. All cores."
    machine
    echo
    echo "$table"
  } > "$out/$file"
  echo "wrote $out/$file" >&2
}
local_pass_table "${LOCAL_PASS_SIZE:-64}" 1 local_pass.md
bash bench/stability.sh "$build"
