#!/usr/bin/env bash
# The hierarchical solver against the progressive one, in the same run: solve time, memory and
# the energy ledger on the procedural building (coarse settings, as bench/building_solve.sh),
# and on the Cornell box at default settings with the exact local pass's error at its 36
# accuracy points against the path-traced reference (data/cornell-box/accuracy-reference.csv);
# and the smallest building at default settings, where refinement is most of the work.
# Writes bench/results/hierarchical_solve.md and docs/images/hierarchical-solve.png.
# Usage: bash bench/hierarchical_solve.sh [BUILD_DIR]   (about 30 minutes and 8 GB on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/provenance.sh
source bench/buildings.sh
build=${1:-build}
out=bench/results
scratch=out/hierarchical-solve
mkdir -p "$out" "$scratch" docs/images
coarse=$building_coarse
write_buildings "$scratch"
table=$(python3 - "$build/cli/radiosity" "$scratch" "$coarse" <<'PY'
import json, math, os, re, subprocess, sys, time

binary, scratch, coarse = sys.argv[1], sys.argv[2], sys.argv[3].split()
chart = open(os.path.join(scratch, "chart.csv"), "w")
chart.write("series,polygons,seconds\n")

def solve(scene, output, solver, extra):
    """Wall seconds, peak resident MiB and the summary's numbers of one solve."""
    start = time.monotonic()
    proc = subprocess.run(["/usr/bin/time", "-f", "%M", binary, "solve", scene, "-o", output,
                           "--solver", solver, *extra], capture_output=True, text=True)
    wall = time.monotonic() - start
    if proc.returncode != 0:
        sys.exit(f"{binary} solve {scene} --solver {solver} failed: {proc.stderr.strip()}")
    err = proc.stderr
    mib = int(err.strip().splitlines()[-1]) / 1024
    m = re.search(r"solve: (\d+) patches, (\d+) elements", err)
    e = re.search(r"energy: emitted \(([^)]*)\) = absorbed \(([^)]*)\) \+ escaped \(([^)]*)\)", err)
    emitted, escaped = (sum(float(v) for v in e.group(i).split(",")) for i in (1, 3))
    links = re.search(r"over (\d+) links", err)
    return {"wall": wall, "mib": mib, "patches": int(m.group(1)), "elements": int(m.group(2)),
            "escaped": 100 * escaped / emitted, "links": int(links.group(1)) if links else None}

def polygons(scene):
    return sum(len(o.get("polygons", [])) for o in json.load(open(scene))["objects"])

def accuracy(solution):
    """RMS, largest and mean relative error of the local pass at the Cornell box's points."""
    probed = os.path.join(scratch, "probed.csv")
    subprocess.run([binary, "probe", "data/cornell-box/scene.json", "-p",
                    "data/cornell-box/accuracy-points.csv", "-s", solution, "-o", probed],
                   check=True, capture_output=True)
    def rows(path):
        return [[float(v) if v else 0.0 for v in line.strip().split(",")]
                for line in open(path) if not line.startswith(("#", "x,"))]
    errors = [g[6 + c] / r[6 + c] - 1
              for r, g in zip(rows("data/cornell-box/accuracy-reference.csv"), rows(probed))
              for c in range(3)]
    return (math.sqrt(sum(x * x for x in errors) / len(errors)), max(abs(x) for x in errors),
            sum(errors) / len(errors))

print("## The procedural building (coarse settings)\n")
print("| building (storeys x rooms) | polygons | patches | progressive s | hierarchical s | "
      "ratio | progressive MiB | hierarchical MiB | links | escaped: progressive | "
      "escaped: hierarchical |")
print("|---|---|---|---|---|---|---|---|---|---|---|")
for name in ["1-2-2", "1-3-3", "1-5-5", "3-5-5"]:
    scene = os.path.join(scratch, f"building-{name}.json")
    p = solve(scene, os.path.join(scratch, "p.vtp"), "progressive", coarse)
    h = solve(scene, os.path.join(scratch, "h.vtp"), "hierarchical", coarse)
    n = polygons(scene)
    print(f"{name}: progressive {p['wall']:.1f} s, hierarchical {h['wall']:.1f} s", file=sys.stderr)
    chart.write(f"progressive,{n},{p['wall']}\nhierarchical,{n},{h['wall']}\n")
    print(f"| {name.replace('-', ' x ')} | {n} | {p['patches']} | {p['wall']:.1f} | "
          f"{h['wall']:.1f} | **{h['wall'] / p['wall']:.3f}** | {p['mib']:.0f} | {h['mib']:.0f} | "
          f"{h['links']} | {p['escaped']:.2f}% | {h['escaped']:.2f}% |")
chart.close()

print("\n## The smallest building at default settings\n")
print("| building (storeys x rooms) | polygons | solver | elements | s | MiB | links | escaped |")
print("|---|---|---|---|---|---|---|---|")
scene = os.path.join(scratch, "building-1-2-2.json")
for solver in ["progressive", "hierarchical"]:
    r = solve(scene, os.path.join(scratch, "d.vtp"), solver, [])
    print(f"1-2-2 at default settings: {solver} {r['wall']:.1f} s", file=sys.stderr)
    links = r["links"] if r["links"] is not None else "-"
    print(f"| 1 x 2 x 2 | {polygons(scene)} | {solver} | {r['elements']} | {r['wall']:.1f} | "
          f"{r['mib']:.0f} | {links} | {r['escaped']:.2f}% |")

print("\n## The Cornell box (default settings)\n")
print("| solver | elements | solve s | RMS error | largest error | mean error | escaped |")
print("|---|---|---|---|---|---|---|")
for solver in ["progressive", "hierarchical"]:
    solution = os.path.join(scratch, f"cornell-{solver}.vtp")
    r = solve("data/cornell-box/scene.json", solution, solver, [])
    rms, largest, mean = accuracy(solution)
    print(f"| {solver} | {r['elements']} | {r['wall']:.1f} | {100 * rms:.2f}% | "
          f"{100 * largest:.2f}% | {100 * mean:+.2f}% | {r['escaped']:.2f}% |")
PY
)
{
  echo "# The hierarchical solver against the progressive solver"
  echo
  echo "Produced by \`bash bench/hierarchical_solve.sh $build\`: \`radiosity solve --solver"
  echo "progressive\` and \`--solver hierarchical\` one after the other, in the same run, on all"
  echo "cores, one run each (wall seconds; peak resident memory). The buildings are"
  echo "\`data/building/make_building.py --storeys S --rooms-x X --rooms-z Z\` solved with"
  echo "\`$coarse\`; the ratio is hierarchical / progressive. \"Escaped\" is the"
  echo "ledger's share of the emitted power that no element took in: the building is closed, so"
  echo "it is what each solver's approximations lose. The Cornell box's errors are the exact local"
  echo "pass's (\`radiosity probe\`, tolerance 0) at its 36 accuracy points, per point and"
  echo "channel, against the path-traced reference (what limits the hierarchical solver there:"
  echo "docs/algorithms.md, \"The hierarchical solver\")."
  provenance geometry scene radiosity cli data/building data/cornell-box
  echo
  echo "$table"
  echo
  echo "![solve time against polygons, both solvers](../../docs/images/hierarchical-solve.png)"
} > "$out/hierarchical_solve.md"
"$build/bench/line_chart" docs/images/hierarchical-solve.png "$scratch/chart.csv" \
  "radiosity solve on the procedural building, both solvers (coarse settings)" "polygons" \
  "seconds" log
cat "$out/hierarchical_solve.md"
