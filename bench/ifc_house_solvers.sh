#!/usr/bin/env bash
# The two solvers on the IFC house (the scene bench/ifc_house.sh makes from Debian's
# assimp-testmodels), one after the other in the same run, at coarse settings (one element a
# patch, no refinement, --unshot 0.02): wall seconds, peak memory, links and the ledger's
# escaped share. Writes bench/results/ifc_house_solvers.md. About 2 minutes on 2 cores.
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
coarse=(--element-levels 0 --refine-threshold 0 --unshot 0.02)
rows=""
for solver in progressive hierarchical; do
  /usr/bin/time -f "%e %M" -o "$work/time.txt" "$build/cli/radiosity" solve \
    "$work/house/scene.json" --solver "$solver" "${coarse[@]}" -o "$work/$solver.vtp" \
    2>"$work/$solver.log" >/dev/null
  read -r seconds kb <"$work/time.txt"
  echo "ifc house, $solver: $seconds s" >&2
  rows+=$(python3 - "$solver" "$seconds" "$kb" "$work/$solver.log" <<'PY'
import re, sys
solver, seconds, kb, log = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), open(sys.argv[4]).read()
m = re.search(r"solve: (\d+) patches", log)
links = re.search(r"over (\d+) links", log)
e = re.search(r"energy: emitted \(([^)]*)\) = absorbed \(([^)]*)\) \+ escaped \(([^)]*)\)", log)
emitted, escaped = (sum(float(v) for v in e.group(i).split(",")) for i in (1, 3))
pairs = re.search(r"visibility: (\d+) point-patch pairs", log)
print(f"| {solver} | {m.group(1)} | {seconds:.1f} | {kb / 1024:.0f} | "
      f"{links.group(1) if links else '-'} | {pairs.group(1)} | {100 * escaped / emitted:.2f}% |")
PY
)$'\n'
done
ratio=$(python3 -c "import sys; r = sys.argv[1].splitlines(); s = [float(l.split('|')[3]) for l in r]; print(f'{s[1] / s[0]:.2f}')" "$rows")
{
  echo "# The two solvers on the IFC house"
  echo
  echo "Produced by \`bash bench/ifc_house_solvers.sh $build\`: \`radiosity solve --solver"
  echo "progressive\` and \`--solver hierarchical\` one after the other on the IFC house of"
  echo "bench/ifc_house.sh (AC14-FZK-Haus.ifc through Assimp and scripts/ifc_house.py), with"
  echo "\`${coarse[*]}\`, on all cores, one run each (wall seconds, peak resident memory)."
  echo "What the hierarchical solver spends its time on there: docs/algorithms.md, \"The"
  echo "hierarchical solver\"."
  provenance radiosity scene scripts/ifc_house.py
  echo
  echo "| solver | patches | s | MiB | links | point-patch pairs | escaped |"
  echo "|---|---|---|---|---|---|---|"
  printf "%s" "$rows"
  echo
  echo "Hierarchical / progressive time: **$ratio**. The issue's target for the house: at most 120 s"
  echo "at default accuracy."
} >bench/results/ifc_house_solvers.md
echo "ifc_house_solvers: wrote bench/results/ifc_house_solvers.md" >&2
