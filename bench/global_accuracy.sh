#!/usr/bin/env bash
# The global solution against the converged path-traced reference on the Cornell box and the
# room with a window (issue 18): bench/results/global_accuracy.md and its chart
# docs/images/global-accuracy.png. About 4 minutes on 2 cores.
# Usage: bash bench/global_accuracy.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
source bench/provenance.sh
build=${1:-build}
out=bench/results
mkdir -p "$out" docs/images
table=$("$build/bench/global_accuracy" docs/images/global-accuracy.png)
{
  echo "# The global solution against a converged reference"
  echo
  echo "Produced by \`bash bench/global_accuracy.sh\` (\`$build/bench/global_accuracy\`): \`radiosity solve\` at"
  echo "each patch size, default settings otherwise, then the exact local pass (hemisphere, tolerance"
  echo "0) at each scene's accuracy points, against their path-traced irradiance"
  echo "(\`data/<scene>/accuracy-reference.csv\`, see the scenes' READMEs). Errors are relative, per"
  echo "point and channel (value / reference - 1); RMS, largest and mean run over all of them. Solve"
  echo "seconds on all cores, one run (the default: the median of three). The chart:"
  echo "[docs/images/global-accuracy.png](../../docs/images/global-accuracy.png)."
  provenance geometry scene hemisphere vertex radiosity octree localpass formats render experiments viz cli "bench/*.cpp"
  echo "$table"
} > "$out/global_accuracy.md"
cat "$out/global_accuracy.md"
