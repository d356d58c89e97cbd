#!/usr/bin/env bash
# Replays each fuzz target's regression set (fuzz/regressions/<target>/: every input must be
# read or refused cleanly) and then fuzzes it for SECONDS (default 60) on a corpus seeded from
# the repository's own files. Prints a table of executions per target. Exits 1 when a
# regression input fails; a new finding of the exploration is kept under BUILD/fuzz-findings/
# and reported, and fails the run only with FUZZ_STRICT=1 (CI replays the regressions strictly
# but does not let a new, unrelated finding in a third-party reader block every change).
# Usage: bash fuzz/run.sh [FUZZ_BUILD_DIR] [SECONDS] [RADIOSITY]   (a build configured with
# -DRAD_FUZZ=ON; RADIOSITY, the executable that makes the seed solution and image, default
# build/cli/radiosity). FUZZ_TARGETS (space-separated) runs only those targets; FUZZ_JOBS runs
# that many at a time (default 1; make fuzz runs two, one per core); FUZZ_RUNS stops
# each target after that many executions too (whichever comes first); FUZZ_NO_HEADER=1 leaves
# out the table's header (fuzz/campaign.sh joins the rows of parallel runs).
set -uo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-fuzz}
seconds=${2:-60}
radiosity=${3:-build/cli/radiosity}
corpus=$build/fuzz-corpus
findings=$build/fuzz-findings
mkdir -p "$corpus" "$findings"

seed() {  # target, files...
  local target=$1
  shift
  mkdir -p "$corpus/$target"
  for f in "$@"; do [ -f "$f" ] && cp -n "$f" "$corpus/$target/" 2>/dev/null; done
  return 0
}
seed fuzz_scene data/*/scene.json tests/data/bad/*.json tests/data/meshes/*.json
for format in obj ply off stl; do
  seed "fuzz_mesh_$format" tests/data/meshes/*."$format" tests/data/bad/*."$format"
done
seed fuzz_mtl tests/data/obj-room/*.mtl /usr/share/assimp/models/OBJ/*.mtl
seed fuzz_points tests/data/points/*.csv
# A small solution and a small image, made by the (sanitized) executable itself.
if [ ! -f "$corpus/fuzz_solution/cube.vtp" ]; then
  mkdir -p "$corpus/fuzz_solution" "$corpus/fuzz_exr"
  "$radiosity" solve data/closed-cube/scene.json --patch-size 0.5 \
    -o "$corpus/fuzz_solution/cube.vtp" >/dev/null 2>&1
  "$radiosity" render data/cornell-box/scene.json --method albedo --width 8 --height 8 \
    --no-preview -o "$corpus/fuzz_exr/albedo.exr" >/dev/null 2>&1
fi

status=0
if [ "${FUZZ_NO_HEADER:-0}" != 1 ]; then
  echo "| target | seconds | executions | corpus files | result |"
  echo "|---|---|---|---|---|"
fi
targets=${FUZZ_TARGETS:-fuzz_scene fuzz_mesh_obj fuzz_mesh_ply fuzz_mesh_off fuzz_mesh_stl \
fuzz_mtl fuzz_points fuzz_solution fuzz_exr}
# FUZZ_JOBS > 1: that many targets at a time, each a run of this script on one target (the
# corpus is seeded above, once); the rows are printed in the targets' order.
jobs=${FUZZ_JOBS:-1}
if [ "$jobs" -gt 1 ]; then
  rows=$(mktemp -d)
  trap 'rm -rf "$rows"' EXIT
  export build seconds radiosity rows
  printf '%s\n' $targets | xargs -P "$jobs" -I{} bash -c \
    'FUZZ_JOBS=1 FUZZ_TARGETS={} FUZZ_NO_HEADER=1 bash fuzz/run.sh "$build" "$seconds" "$radiosity" \
       >"$rows/{}.md"; echo $? >"$rows/{}.status"'
  for target in $targets; do
    cat "$rows/$target.md"
    [ "$(cat "$rows/$target.status")" = 0 ] || status=1
  done
  exit $status
fi
runs=()
[ -n "${FUZZ_RUNS:-}" ] && runs=(-runs="$FUZZ_RUNS")
for target in $targets; do
  exe=$build/fuzz/$target
  dict=()
  [ "$target" = fuzz_scene ] && dict=(-dict=fuzz/scene.dict)
  log=$findings/$target.log
  # The regression set first: each file once.
  if [ -d "fuzz/regressions/$target" ] && [ -n "$(ls -A "fuzz/regressions/$target")" ]; then
    if ! LSAN_OPTIONS=suppressions=$PWD/fuzz/lsan.supp:print_suppressions=0 "$exe" -runs=1 "fuzz/regressions/$target"/* >"$log.regressions" 2>&1; then
      echo "| $target | - | - | - | regression FAILED (see $log.regressions) |"
      status=1
      continue
    fi
  fi
  started=$(date +%s)
  ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=$PWD/fuzz/lsan.supp:print_suppressions=0 "$exe" "${dict[@]}" "${runs[@]}" -max_total_time="$seconds" -timeout=10 \
    -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$findings/$target-" \
    "$corpus/$target" >"$log" 2>&1
  result=$?
  elapsed=$(($(date +%s) - started))
  executed=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1)
  files=$(ls "$corpus/$target" | wc -l)
  if [ $result -eq 0 ]; then
    echo "| $target | $elapsed | ${executed:-?} | $files | clean |"
  else
    echo "| $target | $elapsed | ${executed:-?} | $files | FINDING (see $log and $findings/) |"
    [ "${FUZZ_STRICT:-0}" = 1 ] && status=1
  fi
done
exit $status
