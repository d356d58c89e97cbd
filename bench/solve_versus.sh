#!/usr/bin/env bash
# The default solve of the Cornell box against an earlier commit's, in interleaved pairs
# (issue 18's speed target: no slower than the solve when the issue was filed, ee5828c):
# bench/results/solve_versus.md. The machine is shared and noisy, so each pair runs the two
# binaries back to back and the table gives each pair's ratio and the medians.
# About 10 minutes on 2 cores (5 to build the earlier commit's CLI, once; then the pairs).
# Usage: bash bench/solve_versus.sh [BUILD_DIR] [BASE_COMMIT] [PAIRS]
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/provenance.sh
source bench/earlier_binary.sh
build=${1:-build}
base=${2:-ee5828c}
pairs=${3:-8}
scene=data/cornell-box/scene.json
out=bench/results
mkdir -p "$out"
earlier=$(earlier_radiosity "$base")
table=$(python3 - "$earlier" "$build/cli/radiosity" "$pairs" "$scene" <<'PY'
import os, statistics, subprocess, sys, tempfile, time

base, new, pairs, scene = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]

def run(binary, output):
    """Wall and CPU (user + system) seconds of one default solve."""
    start = time.monotonic()
    proc = subprocess.Popen([binary, "solve", scene, "-o", output],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.monotonic() - start
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"{binary} solve failed")
    return wall, usage.ru_utime + usage.ru_stime

rows = []
with tempfile.TemporaryDirectory() as scratch:
    for i in range(pairs):
        b = run(base, os.path.join(scratch, "base.vtp"))
        n = run(new, os.path.join(scratch, "new.vtp"))
        rows.append((b, n))
        print(f"pair {i + 1}: {b[0]:.1f} s -> {n[0]:.1f} s", file=sys.stderr)

med = statistics.median
print("| pair | base wall s | new wall s | wall ratio | base CPU s | new CPU s | CPU ratio | "
      "base cores busy | new cores busy |")
print("|---|---|---|---|---|---|---|---|---|")
for i, (b, n) in enumerate(rows):
    print(f"| {i + 1} | {b[0]:.1f} | {n[0]:.1f} | {n[0] / b[0]:.3f} | {b[1]:.1f} | {n[1]:.1f} | "
          f"{n[1] / b[1]:.3f} | {b[1] / b[0]:.2f} | {n[1] / n[0]:.2f} |")
print(f"| **median** | {med(b[0] for b, _ in rows):.1f} | {med(n[0] for _, n in rows):.1f} | "
      f"**{med(n[0] / b[0] for b, n in rows):.3f}** | {med(b[1] for b, _ in rows):.1f} | "
      f"{med(n[1] for _, n in rows):.1f} | **{med(n[1] / b[1] for b, n in rows):.3f}** | "
      f"{med(b[1] / b[0] for b, _ in rows):.2f} | {med(n[1] / n[0] for _, n in rows):.2f} |")
PY
)
{
  echo "# The default solve against an earlier commit's"
  echo
  echo "Produced by \`bash bench/solve_versus.sh $build $base $pairs\`: \`radiosity solve $scene\`"
  echo "at default settings on all cores, the earlier commit's binary (\`$base\`) and this one's run"
  echo "back to back in each pair. Ratios are new / base (below 1: faster); CPU is user + system."
  provenance geometry scene radiosity cli
  echo
  echo "$table"
} > "$out/solve_versus.md"
cat "$out/solve_versus.md"
