#!/usr/bin/env bash
# Solving a finely tessellated floor under one lamp (data/floor-grid/make_floor_grid.py): this
# commit's `radiosity solve` against an earlier commit's, back to back in pairs, at the default
# settings; wall seconds and peak memory (GNU time), and whether the two solution files are the
# same bytes. Writes bench/results/floor_grid_solve.md. About 5 minutes on 2 cores at the
# defaults (5 more to build the earlier commit's CLI, once).
#
#   bash bench/floor_grid_solve.sh [BUILD_DIR] [BASE_COMMIT] [PAIRS] [CELLS...]
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/provenance.sh
source bench/earlier_binary.sh
build=${1:-build}
base=${2:-89600a6}
pairs=${3:-2}
shift $(($# < 3 ? $# : 3))
cells=(50 100)
[ $# -eq 0 ] || cells=("$@")
scratch=out/floor-grid-solve
mkdir -p bench/results "$scratch"
earlier=$(earlier_radiosity "$base")
run() {  # binary scene output -> "seconds kB"
  /usr/bin/time -f "%e %M" -o "$scratch/time.txt" "$1" solve "$2" -o "$3" >/dev/null 2>&1
  cat "$scratch/time.txt"
}
rows=""
echo "series,triangles,seconds" > "$scratch/chart.csv"
for n in "${cells[@]}"; do
  scene="$scratch/floor-$n.json"
  python3 data/floor-grid/make_floor_grid.py --cells "$n" -o "$scene"
  t_old=() t_new=() m_old=() m_new=() same=yes
  for ((i = 0; i < pairs; ++i)); do
    read -r s m < <(run "$earlier" "$scene" "$scratch/base.vtp"); t_old+=("$s"); m_old+=("$m")
    read -r s m < <(run "$build/cli/radiosity" "$scene" "$scratch/new.vtp"); t_new+=("$s"); m_new+=("$m")
    # Identical, or how many bytes differ (the files are the same size when only sums moved).
    if ! cmp -s "$scratch/base.vtp" "$scratch/new.vtp"; then
      same="no ($( (cmp -l "$scratch/base.vtp" "$scratch/new.vtp" || true) | wc -l) bytes)"
    fi
    echo "floor $n x $n, pair $((i + 1)): ${t_old[-1]} s -> ${t_new[-1]} s" >&2
  done
  rows+=$(python3 - "$n" "${t_old[*]}" "${t_new[*]}" "${m_old[*]}" "${m_new[*]}" "$same" <<'PY'
import statistics, sys
n, old, new, mold, mnew, same = sys.argv[1:]
old, new = [float(x) for x in old.split()], [float(x) for x in new.split()]
mold, mnew = [float(x) / 1024 for x in mold.split()], [float(x) / 1024 for x in mnew.split()]
med = statistics.median
ratio = med(b / a for a, b in zip(old, new))
print(f"| {n} x {n} | {2 * int(n) ** 2} | {med(old):.1f} | {med(new):.1f} | **{ratio:.3f}** | "
      f"{max(mold):.0f} | {max(mnew):.0f} | {same} |")
PY
)$'\n'
  python3 - "$n" "${t_old[*]}" "${t_new[*]}" >> "$scratch/chart.csv" <<'PY'
import statistics, sys
n, old, new = sys.argv[1:]
triangles = 2 * int(n) ** 2
print(f"earlier,{triangles},{statistics.median(float(x) for x in old.split())}")
print(f"this,{triangles},{statistics.median(float(x) for x in new.split())}")
PY
done
# One series after the other, as line_chart joins each series' points in file order.
(head -1 "$scratch/chart.csv"; tail -n +2 "$scratch/chart.csv" | sort -t, -k1,1 -s) \
  > "$scratch/chart-sorted.csv"
"$build/bench/line_chart" docs/images/floor-grid-solve.png "$scratch/chart-sorted.csv" \
  "Solving a tessellated floor under one lamp" "triangles" "seconds (median)" log
{
  echo "# Solving a tessellated floor"
  echo
  echo "Produced by \`bash bench/floor_grid_solve.sh $build $base $pairs ${cells[*]}\`: \`radiosity solve\` at"
  echo "the default settings on \`data/floor-grid/make_floor_grid.py --cells N\` (a 10 m floor of N x N"
  echo "squares, two triangles each, under a 1 m lamp), on all cores; the earlier commit's binary"
  echo "(\`$base\`) and this one's back to back, $pairs pairs per size. Seconds are medians, the ratio"
  echo "is the median of the pairs' new / earlier, memory the largest peak resident set. \"Same"
  echo "bytes\": the two solution files are identical (where not, how many bytes differ: the"
  echo "ledger's sums, added over other blocks of receivers). The issue's target for the 100 x 100"
  echo "floor: at most 20 s and 1 GB."
  provenance geometry scene radiosity cli data/floor-grid
  echo
  echo "| floor | triangles | earlier s | this s | ratio (median) | earlier MiB | this MiB | same bytes |"
  echo "|---|---|---|---|---|---|---|---|"
  printf '%s' "$rows"
  echo
  echo "![solve time against triangles](../../docs/images/floor-grid-solve.png)"
} > bench/results/floor_grid_solve.md
cat bench/results/floor_grid_solve.md
