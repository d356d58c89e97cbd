#!/usr/bin/env bash
# The solve at scale: the procedural building (data/building/make_building.py) at 1, 3 and 9
# storeys of 5 x 5 rooms (15k, 46k and 138k polygons: is the time n log n?) and at 9 storeys of
# 10 x 10 rooms (552k polygons, 1.1 million triangles once its quads are split), both solvers
# in the same run, at the building's settings (bench/buildings.sh). The progressive solver
# stops at CAP seconds (a solve that does not finish by then is shown as "> CAP" with the
# unshot share it had reached, from its progress lines). Wall seconds and peak resident memory,
# one run each. The hierarchical solver stops at HCAP seconds (the million-triangle target's
# 30 minutes), shown the same way with the stage it was in. Writes
# bench/results/building_scale.md and docs/images/building-scale.png.
#
#   bash bench/building_scale.sh [BUILD_DIR] [CAP] [HCAP]   (about 70 minutes, 7 GB, 2 cores)
#
# SIZES="S X Z;S X Z" picks other buildings (for trying the script on small ones).
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/provenance.sh
source bench/buildings.sh
build=${1:-build}
cap=${2:-600}
hcap=${3:-1800}
sizes=${SIZES:-"1 5 5;3 5 5;9 5 5;9 10 10"}
out=bench/results
scratch=out/building-scale
mkdir -p "$out" "$scratch" docs/images
IFS=';' read -ra buildings <<<"$sizes"
for size in "${buildings[@]}"; do
  read -r storeys rx rz <<<"$size"
  [ -f "$scratch/building-$storeys-$rx-$rz.json" ] ||
    python3 data/building/make_building.py --storeys "$storeys" --rooms-x "$rx" --rooms-z "$rz" \
      -o "$scratch/building-$storeys-$rx-$rz.json"
done
table=$(python3 - "$build/cli/radiosity" "$scratch" "$building_coarse" "$cap" "$hcap" "$sizes" <<'PY'
import json, math, os, re, subprocess, sys, time

binary, scratch, coarse, cap, hcap, sizes = sys.argv[1:7]
coarse, cap, hcap = coarse.split(), float(cap), float(hcap)
chart = open(os.path.join(scratch, "chart.csv"), "w")
chart.write("series,polygons,seconds\n")

def solve(scene, solver, limit=None):
    """Wall seconds, peak resident MiB, the summary's numbers, or, when the solve ran out of
    time, its last progress line's stage and share."""
    command = ["/usr/bin/time", "-f", "%M", binary, "solve", scene, "-o",
               os.path.join(scratch, solver + ".vtp"), "--solver", solver, *coarse]
    if limit:
        command = ["timeout", "-s", "INT", str(int(limit))] + command
    start = time.monotonic()
    proc = subprocess.run(command, capture_output=True, text=True)
    wall = time.monotonic() - start
    err = proc.stderr.replace("\r", "\n")
    lines = err.strip().splitlines()
    mib = int(lines[-1]) / 1024 if lines and lines[-1].isdigit() else float("nan")
    if proc.returncode != 0:
        stages = [line for line in lines if line.startswith("solve (")]
        if limit and wall >= limit - 1:
            return {"done": False, "wall": wall, "mib": mib, "limit": limit,
                    "stage": stages[-1] if stages else "before its first progress line"}
        sys.exit(f"{binary} solve {scene} --solver {solver} failed: {err.strip()[-2000:]}")
    m = re.search(r"solve: (\d+) patches, (\d+) elements", err)
    links = re.search(r"over (\d+) links", err)
    return {"done": True, "wall": wall, "mib": mib, "patches": int(m.group(1)),
            "links": int(links.group(1)) if links else None}

def counts(scene):
    """Polygons and triangles (a polygon of n corners is n - 2 triangles)."""
    polygons = [p for o in json.load(open(scene))["objects"] for p in o.get("polygons", [])]
    return len(polygons), sum(len(p) - 2 for p in polygons)

def seconds(r):
    """The wall time, or the cap and where the solve was: `solve (shooting): 40%, unshot 3.1%
    (target 2%), ...` reads as "shooting, unshot 3.1%"."""
    if r["done"]:
        return f"{r['wall']:.1f}"
    m = re.match(r"solve \((\w+)\): (\d+)%(?:, (\w+ [\d.e+-]+%))?", r["stage"])
    where = (f"{m.group(1)} {m.group(2)}%" + (f", {m.group(3)}" if m.group(3) else "")
             if m else r["stage"])
    return f"> {r['limit']:.0f} ({where})"

print("| building (storeys x rooms) | polygons | triangles | patches | hierarchical s | "
      "hierarchical MiB | links | progressive s | progressive MiB | ratio |")
print("|---|---|---|---|---|---|---|---|---|---|")
rows = []
for size in sizes.split(";"):
    storeys, rx, rz = size.split()
    scene = os.path.join(scratch, f"building-{storeys}-{rx}-{rz}.json")
    n, triangles = counts(scene)
    h = solve(scene, "hierarchical", hcap)
    p = solve(scene, "progressive", cap)
    print(f"{storeys} x {rx} x {rz}: hierarchical {h['wall']:.1f} s, progressive {seconds(p)}",
          file=sys.stderr)
    for name, r in (("hierarchical", h), ("progressive", p)):
        if r["done"]:
            chart.write(f"{name},{n},{r['wall']}\n")
    if h["done"] and p["done"]:
        ratio = f"**{h['wall'] / p['wall']:.3f}**"
    elif h["done"]:
        ratio = f"< {h['wall'] / cap:.3f}"
    else:
        ratio = "-"
    patches = h.get("patches", p.get("patches", "-"))
    print(f"| {storeys} x {rx} x {rz} | {n} | {triangles} | {patches} | {seconds(h)} | "
          f"{h['mib']:.0f} | {h.get('links', '-')} | {seconds(p)} | {p['mib']:.0f} | {ratio} |")
    if h["done"]:
        rows.append((n, h["wall"]))
chart.close()

# The growth between consecutive sizes: the exponent a of time ~ n^a, and the time n log n
# would predict from the smaller size.
print("\n| from | to | polygons x | hierarchical time x | n log n predicts x | exponent |")
print("|---|---|---|---|---|---|")
for (n0, t0), (n1, t1) in zip(rows, rows[1:]):
    nlogn = n1 * math.log(n1) / (n0 * math.log(n0))
    print(f"| {n0} | {n1} | {n1 / n0:.2f} | {t1 / t0:.2f} | {nlogn:.2f} | "
          f"{math.log(t1 / t0) / math.log(n1 / n0):.2f} |")
PY
)
{
  echo "# The solve at scale: the building up to a million triangles"
  echo
  echo "Produced by \`bash bench/building_scale.sh $build $cap $hcap\`: \`radiosity solve --solver"
  echo "hierarchical\` and \`--solver progressive\` one after the other, in the same run, on all"
  echo "cores, one run each (wall seconds; peak resident memory), on"
  echo "\`data/building/make_building.py --storeys S --rooms-x X --rooms-z Z\` with"
  echo "\`$building_coarse\` (the building's default accuracy, as in"
  echo "bench/results/building_solve.md). The progressive solver is stopped at $cap s and the"
  echo "hierarchical at $hcap s (shown as \"> cap\" with the stage and share each had reached);"
  echo "the ratio is hierarchical / progressive. The second table is the hierarchical solver's"
  echo "growth between consecutive sizes it finished (exponent a in time ~ n^a)."
  provenance geometry scene radiosity cli data/building
  echo
  echo "$table"
  echo
  echo "![solve time against polygons, both solvers](../../docs/images/building-scale.png)"
} > "$out/building_scale.md"
"$build/bench/line_chart" docs/images/building-scale.png "$scratch/chart.csv" \
  "radiosity solve on the procedural building up to 1.1 million triangles" "polygons" \
  "seconds" log
cat "$out/building_scale.md"
