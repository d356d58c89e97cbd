#!/usr/bin/env bash
# Solving the procedural building (data/building/make_building.py) as it grows, this commit's
# `radiosity solve` against an earlier commit's (by default 8587d0f: before a shot's receivers
# were put in order without a sort and picked in parallel, the shooter's pair counts kept per
# thread, and a pair one polygon hides whole left without shadow rays: radiosity/shooter.h,
# radiosity/receiver_culling.h). Writes bench/results/building_solve.md.
#
# Each size runs the two binaries back to back, PAIRS times, and checks that their solutions
# are the same bytes. The default building (46,005 polygons) runs with this commit's binary
# only: the earlier one's rate is measured over its first SHOTS shots instead (it would take
# long). About 15 minutes on 2 cores (5 more to build the earlier commit's CLI, once).
#
#   bash bench/building_solve.sh [BUILD_DIR] [BASE_COMMIT] [PAIRS] [SHOTS]
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/provenance.sh
source bench/buildings.sh
source bench/earlier_binary.sh
build=${1:-build}
base=${2:-8587d0f}
pairs=${3:-3}
shots=${4:-300}
out=bench/results
scratch=out/building-solve
mkdir -p "$out" "$scratch"
earlier=$(earlier_radiosity "$base")
coarse=$building_coarse
write_buildings "$scratch"
table=$(python3 - "$earlier" "$build/cli/radiosity" "$pairs" "$shots" \
  "$scratch" "$coarse" "$base" <<'PY'
import filecmp, json, os, re, statistics, subprocess, sys, time

base, new, pairs, shots, scratch, coarse, base_commit = sys.argv[1:8]
pairs, shots, coarse = int(pairs), int(shots), coarse.split()
points = open(os.path.join(scratch, "chart.csv"), "w")
points.write("series,polygons,seconds\n")

def solve(binary, scene, output, extra=()):
    """Wall seconds and the summary line's numbers of one solve."""
    start = time.monotonic()
    # This commit's progressive solver by name (the one whose shots the table counts); the
    # earlier commit had no other.
    solver = ["--solver", "progressive"] if binary == new else []
    proc = subprocess.run([binary, "solve", scene, "-o", output, *coarse, *solver, *extra],
                          capture_output=True, text=True)
    wall = time.monotonic() - start
    if proc.returncode != 0:
        sys.exit(f"{binary} solve {scene} failed: {proc.stderr.strip()}")
    m = re.search(r"solve: (\d+) patches, \d+ elements .*?, (\d+) shots, unshot ([\d.e+-]+)%",
                  proc.stderr)
    return wall, int(m.group(1)), int(m.group(2)), float(m.group(3))

def polygons(scene):
    data = json.load(open(scene))
    return sum(len(o.get("polygons", [])) for o in data["objects"])

med = statistics.median
print("| building (storeys x rooms) | polygons | patches | shots | earlier s | this s | "
      "ratio (median) | same bytes |")
print("|---|---|---|---|---|---|---|---|")
for name in ["1-2-2", "1-3-3", "1-5-5"]:
    scene = os.path.join(scratch, f"building-{name}.json")
    a, b = os.path.join(scratch, "base.vtp"), os.path.join(scratch, "new.vtp")
    rows = []
    for i in range(pairs):
        rb = solve(base, scene, a)
        rn = solve(new, scene, b)
        same = filecmp.cmp(a, b, shallow=False)
        rows.append((rb, rn, same))
        print(f"{name} pair {i + 1}: {rb[0]:.1f} s -> {rn[0]:.1f} s, same bytes: {same}",
              file=sys.stderr)
    _, patches, n_shots, _ = rows[0][1]
    points.write(f"earlier ({base_commit}),{polygons(scene)},{med(r[0][0] for r in rows)}\n")
    points.write(f"this commit,{polygons(scene)},{med(r[1][0] for r in rows)}\n")
    print(f"| {name.replace('-', ' x ', 1).replace('-', ' x ')} | {polygons(scene)} | {patches} | "
          f"{n_shots} | {med(r[0][0] for r in rows):.1f} | {med(r[1][0] for r in rows):.1f} | "
          f"**{med(r[1][0] / r[0][0] for r in rows):.3f}** | "
          f"{'yes' if all(r[2] for r in rows) else 'NO'} |")
# The default building: the first `shots` shots with both (same bytes), then the whole solve
# with this commit's binary.
scene = os.path.join(scratch, "building-3-5-5.json")
a, b = os.path.join(scratch, "base.vtp"), os.path.join(scratch, "new.vtp")
limit = ["--max-shots", str(shots)]
rb = solve(base, scene, a, limit)
rn = solve(new, scene, b, limit)
same = filecmp.cmp(a, b, shallow=False)
print(f"default, {shots} shots: {rb[0]:.1f} s -> {rn[0]:.1f} s, same bytes: {same}", file=sys.stderr)
print(f"| 3 x 5 x 5, first {shots} shots | {polygons(scene)} | {rn[1]} | {shots} | {rb[0]:.1f} | "
      f"{rn[0]:.1f} | **{rn[0] / rb[0]:.3f}** | {'yes' if same else 'NO'} |")
full = solve(new, scene, b)
print(f"default, whole: {full[0]:.1f} s, {full[2]} shots", file=sys.stderr)
points.write(f"this commit,{polygons(scene)},{full[0]}\n")
points.close()
print(f"| 3 x 5 x 5, whole solve | {polygons(scene)} | {full[1]} | {full[2]} | | "
      f"{full[0]:.1f} | | |")
print()
print(f"The whole default solve stopped at {full[3]:.3g}% unshot after {full[2]} shots.")
PY
)
{
  echo "# Solving the procedural building"
  echo
  echo "Produced by \`bash bench/building_solve.sh $build $base $pairs $shots\`: \`radiosity solve\`"
  echo "on buildings of \`data/building/make_building.py --storeys S --rooms-x X --rooms-z Z\`"
  echo "with \`$coarse\`, on all cores; the earlier commit's binary (\`$base\`) and"
  echo "this one's back to back, $pairs pairs per size (seconds are medians, the ratio is the median"
  echo "of the pairs' new / earlier). \"Same bytes\": the two solution files are identical."
  provenance geometry scene radiosity cli data/building
  echo
  echo "$table"
  echo
  echo "![solve time against polygons](../../docs/images/building-solve.png)"
} > "$out/building_solve.md"
"$build/bench/line_chart" docs/images/building-solve.png "$scratch/chart.csv" \
  "radiosity solve on the procedural building (coarse settings)" "polygons" "seconds" log
cat "$out/building_solve.md"
