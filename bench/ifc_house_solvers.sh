#!/usr/bin/env bash
# The two solvers on the IFC house (the scene bench/ifc_house.sh makes from Debian's
# assimp-testmodels), one after the other in the same run, at coarse settings (one element a
# patch, no refinement, --unshot 0.02) and at default settings: wall seconds, peak memory,
# links and the ledger's escaped share. Writes bench/results/ifc_house_solvers.md. About 8
# minutes on 2 cores.
# Needs: apt-get install assimp-utils assimp-testmodels.
# Usage: bash bench/ifc_house_solvers.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/provenance.sh
build=${1:-build}
model=/usr/share/assimp/models/IFC/AC14-FZK-Haus.ifc
if ! command -v assimp >/dev/null || [ ! -f "$model" ]; then
  echo "ifc_house_solvers: needs Assimp's command line and test models: apt-get install assimp-utils assimp-testmodels" >&2
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
assimp export "$model" "$work/model.obj" -tri -jiv -fd >/dev/null
python3 scripts/ifc_house.py "$work/model.obj" "$work/house" >/dev/null
coarse="--element-levels 0 --refine-threshold 0 --unshot 0.02"
rows=""
for settings in coarse default; do
  options=()
  [ "$settings" = coarse ] && read -r -a options <<<"$coarse"
  for solver in progressive hierarchical; do
    /usr/bin/time -f "%e %M" -o "$work/time.txt" "$build/cli/radiosity" solve \
      "$work/house/scene.json" --solver "$solver" "${options[@]}" -o "$work/$solver.vtp" \
      2>"$work/$solver.log" >/dev/null
    read -r seconds kb <"$work/time.txt"
    echo "ifc house, $settings, $solver: $seconds s" >&2
    rows+=$(python3 - "$settings" "$solver" "$seconds" "$kb" "$work/$solver.log" <<'PY'
import re, sys
settings, solver = sys.argv[1], sys.argv[2]
seconds, kb, log = float(sys.argv[3]), float(sys.argv[4]), open(sys.argv[5]).read()
m = re.search(r"solve: (\d+) patches", log)
links = re.search(r"over (\d+) links", log)
e = re.search(r"energy: emitted \(([^)]*)\) = absorbed \(([^)]*)\) \+ escaped \(([^)]*)\)", log)
emitted, escaped = (sum(float(v) for v in e.group(i).split(",")) for i in (1, 3))
pairs = re.search(r"visibility: (\d+) point-patch pairs", log)
elements = re.search(r"patches, (\d+) elements", log)
steps = re.search(r"time: linking ([\d.e+-]+) s, opening the sources the light reached "
                  r"([\d.e+-]+) s, refining ([\d.e+-]+) s, sweeps ([\d.e+-]+) s", log)
steps = " / ".join(f"{float(v):.1f}" for v in steps.groups()) if steps else "-"
print(f"| {settings} | {solver} | {elements.group(1)} | {seconds:.1f} | {kb / 1024:.0f} | "
      f"{links.group(1) if links else '-'} | {pairs.group(1)} | {100 * escaped / emitted:.2f}% | "
      f"{steps} |")
PY
)$'\n'
  done
done
ratios=$(python3 -c "import sys; r = sys.argv[1].splitlines(); s = [float(l.split('|')[4]) for l in r]; print(f'{s[1] / s[0]:.2f} coarse, {s[3] / s[2]:.2f} at default settings')" "$rows")
{
  echo "# The two solvers on the IFC house"
  echo
  echo "Produced by \`bash bench/ifc_house_solvers.sh $build\`: \`radiosity solve --solver"
  echo "progressive\` and \`--solver hierarchical\` one after the other on the IFC house of"
  echo "bench/ifc_house.sh (AC14-FZK-Haus.ifc through Assimp and scripts/ifc_house.py), with"
  echo "\`$coarse\` (coarse) and at default settings, on all cores, one run each (wall"
  echo "seconds, peak resident memory)."
  echo "The hierarchical solver's steps: the seconds of its linking, its opening rounds (the"
  echo "sources the light has reached since linking), its refinement passes and its sweeps, as"
  echo "\`solve\` prints them. What they spend their time on: docs/algorithms.md, \"The"
  echo "hierarchical solver\"."
  provenance radiosity scene scripts/ifc_house.py
  echo
  echo "| settings | solver | leaves | s | MiB | links | point-patch pairs | escaped | steps: linking / opening / refining / sweeps s |"
  echo "|---|---|---|---|---|---|---|---|---|"
  printf "%s" "$rows"
  echo
  echo "Hierarchical / progressive time: **$ratios**. The target for the house: at most"
  echo "120 s at default settings."
} >bench/results/ifc_house_solvers.md
echo "ifc_house_solvers: wrote bench/results/ifc_house_solvers.md" >&2
