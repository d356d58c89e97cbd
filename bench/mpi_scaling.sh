#!/usr/bin/env bash
# Issue 21: the MPI render's time against processes on this machine, the per-tile costs and the
# messages' costs it measures, and from them the model of 8 to 512 processes
# (bench/mpi_scaling.cpp). Writes bench/results/mpi_scaling.md and docs/images/mpi-scaling.png.
# About 15 minutes on 2 cores. MODEL_ONLY=1 re-runs the model on the last measurements (in
# out/mpi-scaling/).
#
#   bash bench/mpi_scaling.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
RADIOSITY=$BUILD/cli/radiosity
MODEL=$BUILD/bench/mpi_scaling
source bench/provenance.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
OUT=out/mpi-scaling
mkdir -p "$OUT" bench/results docs/images
# The scene: one storey of 2 x 2 rooms of the procedural building, coarsely solved; the local
# pass at tolerance 0.05 over a 48 x 36 image (about 25 ms a pixel: books and windows).
WIDTH=48 HEIGHT=36 TOLERANCE=0.05
if [ "${MODEL_ONLY:-0}" != 1 ]; then
python3 data/building/make_building.py --storeys 1 --rooms-x 2 --rooms-z 2 -o "$OUT/scene.json"
"$RADIOSITY" solve "$OUT/scene.json" --element-levels 0 --refine-threshold 0 --unshot 0.02 \
  -o "$OUT/solution.vtp" 2>/dev/null
INPUT_BYTES=$(($(stat -c %s "$OUT/scene.json") + $(stat -c %s "$OUT/solution.vtp")))

echo "mpi_scaling: per-pixel costs" >&2
"$MODEL" costs "$OUT/scene.json" "$OUT/solution.vtp" $WIDTH $HEIGHT $TOLERANCE "$OUT/costs.csv"
echo "mpi_scaling: the messages' costs" >&2
: >"$OUT/overhead.csv"
for p in 2 3 4; do
  mpirun -q --oversubscribe -n $p "$MODEL" overhead "$INPUT_BYTES" >>"$OUT/overhead.csv"
done

# Measured: the render with 1 to 4 processes of one thread each (3 and 4 oversubscribe the 2
# cores), median of 3 runs; and the setup alone (a 1 x 1 image, one process).
median() { sort -g | awk '{v[NR]=$1} END {print v[int((NR+1)/2)]}'; }
seconds_of() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['seconds'])" "$1"; }
render() {  # PROCESSES WIDTH HEIGHT
  mpirun -q --oversubscribe -n "$1" "$RADIOSITY" render "$OUT/scene.json" --solution "$OUT/solution.vtp" \
    --width "$2" --height "$3" --tolerance $TOLERANCE -j 1 -o "$OUT/render.exr" 2>/dev/null
  seconds_of "$OUT/render.stats.json"
}
setup=$(for _ in 1 2 3; do render 1 1 1; done | median)
: >"$OUT/measured.csv"
for p in 1 2 3 4; do
  echo "mpi_scaling: $p processes" >&2
  t=$(for _ in 1 2 3; do render $p $WIDTH $HEIGHT; done | median)
  echo "$p,$t,$setup" >>"$OUT/measured.csv"
done
echo "$(git rev-parse --short HEAD)$([ -z "$(git status --porcelain -- distributed render cli)" ] || echo ' plus uncommitted changes'), $(date -u +%Y-%m-%d)" >"$OUT/measured_at.txt"
fi
INPUT_BYTES=$(($(stat -c %s "$OUT/scene.json") + $(stat -c %s "$OUT/solution.vtp")))

"$MODEL" model "$OUT/costs.csv" "$OUT/overhead.csv" "$OUT/measured.csv" $WIDTH $HEIGHT "$(nproc)" \
  "$OUT/model.md" docs/images/mpi-scaling.png
{
  echo "# The MPI render: measured on this machine, modelled to 512 processes"
  echo
  echo "Written by \`bash bench/mpi_scaling.sh\` (bench/mpi_scaling.cpp):"
  provenance bench/mpi_scaling.cpp bench/mpi_scaling.sh distributed render data/building
  echo "- measured at: $(cat "$OUT/measured_at.txt" 2>/dev/null || echo unknown) (the runs; the model is re-run by MODEL_ONLY=1)"
  echo "- scene: \`make_building.py --storeys 1 --rooms-x 2 --rooms-z 2\` ($(sed -n 's/^polygons *\([0-9]*\).*/\1/p' <("$RADIOSITY" info "$OUT/scene.json")) polygons), solved with \`--element-levels 0 --refine-threshold 0 --unshot 0.02\`; the local pass (hemisphere) at tolerance $TOLERANCE, $WIDTH x $HEIGHT pixels, one thread a process"
  echo "- the messages (one line per process count: processes, a worker's seconds a block beyond"
  echo "  its work, the root's seconds between two results it served, seconds to broadcast the"
  echo "  inputs' $INPUT_BYTES bytes):"
  echo
  echo '```'
  cat "$OUT/overhead.csv"
  echo '```'
  echo
  cat "$OUT/model.md"
  echo
  echo "![modelled speed-up](../../docs/images/mpi-scaling.png)"
} >bench/results/mpi_scaling.md
echo "mpi_scaling: wrote bench/results/mpi_scaling.md and docs/images/mpi-scaling.png" >&2
