#!/usr/bin/env bash
# Where the hierarchical solver's time goes as the building grows: `perf record` on
# `radiosity solve --solver hierarchical` at the building's default accuracy
# (bench/buildings.sh) at 1 and 3 storeys of 5 x 5 rooms, each function's CPU seconds (its own
# samples, not its callees') at both sizes and their ratio, beside the solve's counts (links,
# point-patch pairs measured, the share one polygon hid whole). The functions that grow faster
# than the polygons are what stands between the solver and n log n (bench/building_scale.sh).
# Writes bench/results/building_profile.md.
# Usage: bash bench/building_profile.sh [BUILD_DIR]   (about 4 minutes on 2 cores; needs perf)
# SIZES="S X Z;S X Z" picks other buildings (two of them).
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/provenance.sh
source bench/buildings.sh
build=${1:-build}
sizes=${SIZES:-"1 5 5;3 5 5"}
command -v perf >/dev/null || { echo "building_profile: perf is not installed" >&2; exit 1; }
scratch=out/building-profile
mkdir -p "$scratch" bench/results
IFS=';' read -ra buildings <<<"$sizes"
for size in "${buildings[@]}"; do
  read -r storeys rx rz <<<"$size"
  scene="$scratch/building-$storeys-$rx-$rz.json"
  [ -f "$scene" ] ||
    python3 data/building/make_building.py --storeys "$storeys" --rooms-x "$rx" --rooms-z "$rz" \
      -o "$scene"
  # shellcheck disable=SC2086  # the settings are words
  perf record -q -F 499 -o "$scratch/perf-$storeys-$rx-$rz.data" -- \
    "$build/cli/radiosity" solve "$scene" -o "$scratch/solution.vtp" --solver hierarchical \
    $building_coarse 2>"$scratch/solve-$storeys-$rx-$rz.log" >/dev/null
  perf report -q -i "$scratch/perf-$storeys-$rx-$rz.data" --no-children --stdio -n \
    --sort dso,symbol 2>/dev/null >"$scratch/report-$storeys-$rx-$rz.txt"
done

table=$(python3 - "$scratch" "$sizes" <<'PY'
import json, os, re, sys

scratch, sizes = sys.argv[1:3]
FREQUENCY = 499  # perf record -F: samples per CPU second
runs = []
for size in sizes.split(";"):
    storeys, rx, rz = size.split()
    tag = f"{storeys}-{rx}-{rz}"
    scene = json.load(open(os.path.join(scratch, f"building-{tag}.json")))
    polygons = sum(len(o.get("polygons", [])) for o in scene["objects"])
    samples = {}
    for line in open(os.path.join(scratch, f"report-{tag}.txt")):
        m = re.match(r"\s*[\d.]+%\s+(\d+)\s+(\S+)\s+\[[.k]\]\s+(.+?)\s*$", line)
        if m:
            if m.group(2) == "radiosity":
                name = m.group(3).split("  ")[0]  # (perf pads the name, then other columns)
                name = re.sub(r"\(.*", "", name).replace("rad::", "")
            else:  # a library's functions together (Embree's have no symbols)
                name = re.sub(r"\.so.*", "", m.group(2)) + " (all of it)"
            samples[name] = samples.get(name, 0) + int(m.group(1))
    log = open(os.path.join(scratch, f"solve-{tag}.log")).read().replace("\r", "\n")
    solve = re.search(r"solve: (\d+) patches.*over (\d+) links.*?([\d.]+) s\n", log)
    pairs = re.search(r"visibility: (\d+) point-patch pairs.*?([\d.]+)% hidden whole", log)
    if not (solve and pairs):
        sys.exit(f"building_profile: no summary in {scratch}/solve-{tag}.log")
    runs.append({"label": f"{storeys} x {rx} x {rz}", "polygons": polygons,
                 "patches": int(solve.group(1)), "links": int(solve.group(2)),
                 "seconds": float(solve.group(3)), "pairs": int(pairs.group(1)),
                 "hidden": float(pairs.group(2)), "samples": samples})
small, large = runs
print(f"| building | polygons | patches | solve s | links | point-patch pairs | "
      f"pairs per patch | hidden whole by one polygon |")
print("|---|---|---|---|---|---|---|---|")
for r in runs:
    print(f"| {r['label']} | {r['polygons']} | {r['patches']} | {r['seconds']:.1f} | "
          f"{r['links']} | {r['pairs']} | {r['pairs'] / r['patches']:.0f} | {r['hidden']:.1f}% |")
grows = large["polygons"] / small["polygons"]
print()
print(f"| function (own samples) | CPU s at {small['label']} | CPU s at {large['label']} | "
      f"x (polygons x {grows:.2f}) | share at {large['label']} |")
print("|---|---|---|---|---|")
total_large = sum(large["samples"].values())
top = sorted(large["samples"], key=lambda k: -large["samples"][k])[:15]
for name in top:
    a = small["samples"].get(name, 0) / FREQUENCY
    b = large["samples"][name] / FREQUENCY
    ratio = f"{b / a:.1f}" if a > 0 else "-"
    print(f"| `{name}` | {a:.1f} | {b:.1f} | {ratio} | {100 * large['samples'][name] / total_large:.1f}% |")
rest_a = (sum(small["samples"].values()) - sum(small["samples"].get(n, 0) for n in top)) / FREQUENCY
rest_b = (total_large - sum(large["samples"][n] for n in top)) / FREQUENCY
print(f"| the rest | {rest_a:.1f} | {rest_b:.1f} | {rest_b / rest_a:.1f} | "
      f"{100 * rest_b * FREQUENCY / total_large:.1f}% |")
a, b = sum(small["samples"].values()) / FREQUENCY, total_large / FREQUENCY
print(f"| **all** | {a:.1f} | {b:.1f} | {b / a:.1f} | 100% |")
PY
)

{
  echo "# Where the hierarchical solver's time goes as the building grows"
  echo
  echo "Produced by \`bash bench/building_profile.sh $build\`: \`perf record -F 499\` on"
  echo "\`radiosity solve --solver hierarchical $building_coarse\` (the building's default"
  echo "accuracy) at each size, one run each, on all cores. CPU seconds are a function's own"
  echo "samples (not its callees') over 499 per second, summed over the threads."
  provenance radiosity scene data/building bench/building_profile.sh
  echo
  echo "$table"
} >bench/results/building_profile.md
echo "wrote bench/results/building_profile.md"
