#!/usr/bin/env bash
# Issue 21's large scene through the usual commands: data/building/make_building.py writes the
# default building (3 storeys of 5 x 5 rooms, tens of thousands of polygons), which `info` loads
# and validates and `render --method facing` draws; then a small building (one storey of
# 2 x 1 rooms, the same generator) is solved and rendered by the local pass over 3 processes,
# byte-identical to the render without mpirun. The default building's solve and local pass
# take hours on 2 cores (docs/cluster.md): CI runs them on the small one.
#
#   building_test.sh RADIOSITY SOURCE_DIR
set -euo pipefail
RADIOSITY=$1
SOURCE=$2
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1  # CI runs as root
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cd "$WORK"
GENERATE=$SOURCE/data/building/make_building.py

python3 "$GENERATE" -o building.json 2>generate.err
polygons=$("$RADIOSITY" info building.json | sed -n 's/^polygons *\([0-9]*\).*/\1/p')
echo "default building: $polygons polygons"
[ "$polygons" -ge 20000 ] || { echo "FAILED: only $polygons polygons"; exit 1; }
"$RADIOSITY" render building.json --method facing --width 96 --height 72 -o facing.exr
# The same arguments write the same bytes.
python3 "$GENERATE" -o again.json 2>/dev/null
cmp building.json again.json

python3 "$GENERATE" --storeys 1 --rooms-x 2 --rooms-z 1 -o small.json
"$RADIOSITY" solve small.json --element-levels 0 --refine-threshold 0 --unshot 0.05 -o small.vtp
args=(render small.json --solution small.vtp --width 32 --height 24 --tolerance 0.2)
"$RADIOSITY" "${args[@]}" -o plain.exr
timeout 600 mpirun -q --oversubscribe -n 3 "$RADIOSITY" "${args[@]}" -o mpi.exr
cmp plain.exr mpi.exr
cmp plain.pixels.exr mpi.pixels.exr
echo "building_test: generated, loaded, solved and rendered; the same image over 3 processes"
