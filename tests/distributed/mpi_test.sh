#!/usr/bin/env bash
# Issue 21: the same commands over mpirun give the same bytes, and faults end the job cleanly.
#
#   mpi_test.sh RADIOSITY SOURCE_DIR
#
# 1. Same answer: render (hemisphere, vertex, montecarlo, pathtrace), probe and sweep, without
#    mpirun, and under mpirun with 1, 2 and 3 processes (--oversubscribe: this machine has 2
#    cores) and 1 or 2 threads each: every image, per-pixel file and probe CSV is byte-identical;
#    the stats JSON too but for the keys that describe the run (seconds, threads, processes)
#    and the per-pixel file's name, and the sweep's results.csv but for its seconds column.
# 2. Faults: a scene the root cannot read; a process that cannot take what the root sent (its
#    $TMPDIR missing); a sweep whose root cannot write between renders; a worker and the root
#    killed midway. Each ends the run within the timeout
#    (never a hang), with exit status non-zero, one line on stderr (`mpirun -q`, as docs/cluster.md
#    says; the scene's warnings aside) naming the problem, and a previous output left as it was.
# Each check can fail: the comparisons are of the files themselves (cmp), and the fault checks
# look for the file's old bytes and the exact line.
set -uo pipefail
RADIOSITY=$1
SOURCE=$2
SCENE=$SOURCE/data/cornell-box/scene.json
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1  # CI runs as root
export OMPI_MCA_rmaps_base_oversubscribe=1
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
cd "$WORK" || exit 1
failures=0
fail() {
  echo "FAILED: $*"
  failures=$((failures + 1))
}
mpi() { timeout 300 mpirun -q --oversubscribe "$@"; }

# A coarse solution: the test is of the distribution, not of the numbers.
"$RADIOSITY" solve "$SCENE" --patch-size 0.2 -o sol.vtp 2>/dev/null || fail "solve"
python3 - <<'EOF' >points.csv
import random
random.seed(21)
print("x,y,z,nx,ny,nz")
for _ in range(200):
    print(f"{random.uniform(0.05, 0.5)},{random.uniform(0.0, 0.5)},{random.uniform(0.05, 0.5)},0,1,0")
EOF

# The runs: a name, and the command's arguments; OUT is replaced by the output's stem.
RUNS=(
  "hemisphere|render $SCENE --solution sol.vtp --width 40 --height 36 --tolerance 0.05 -o OUT.exr"
  "vertex|render $SCENE --method vertex --solution sol.vtp --width 32 --height 32 --tolerance 0.1 -o OUT.exr"
  "montecarlo|render $SCENE --method montecarlo --samples 16 --solution sol.vtp --width 32 --height 32 -o OUT.exr"
  "pathtrace|render $SCENE --method pathtrace --samples 4 --width 33 --height 31 -o OUT.exr"
  "probe|probe $SCENE --points points.csv --solution sol.vtp --tolerance 0.02 -o OUT.csv"
  "sweep|sweep $SCENE --solution sol.vtp --methods hemisphere,montecarlo --width 24 --height 24 --tolerances 0.2,0.05 --samples 4 -o OUT"
)
# The settings: a label, and the launcher.
SETTINGS=("plain|" "n1|mpi -n 1" "n2|mpi -n 2" "n3|mpi -n 3" "n3j1|mpi -n 3" "n2j2|mpi -n 2")
threads_of() { case $1 in *j1) echo "-j 1" ;; *j2) echo "-j 2" ;; *) echo "" ;; esac; }

# What may differ between runs: the stats' run keys and the sweep's seconds column.
normalize() {
  case $1 in
  *.stats.json) grep -v -E '^  "(seconds|threads|processes|pixels_file)":' "$1" ;;
  *results.csv) cut -d, -f4 --complement "$1" ;;
  *) cat "$1" ;;
  esac
}

for run in "${RUNS[@]}"; do
  name=${run%%|*}
  args=${run#*|}
  settings=("${SETTINGS[@]}")
  # The sweep draws charts (seconds of Xvfb and VTK a run): without mpirun and over 3 processes.
  [ "$name" = sweep ] && settings=("plain|" "n3|mpi -n 3")
  for setting in "${settings[@]}"; do
    label=${setting%%|*}
    launcher=${setting#*|}
    out="$name-$label"
    # shellcheck disable=SC2086  # the arguments are words
    if ! $launcher "$RADIOSITY" ${args//OUT/$out} $(threads_of "$label") 2>"$out.err"; then
      fail "$name under '$label' exited with $?: $(tail -1 "$out.err")"
      continue
    fi
  done
  reference="$name-plain"
  for setting in "${settings[@]:1}"; do
    label=${setting%%|*}
    # Every file the plain run wrote, against the same file of this run.
    while IFS= read -r file; do
      other=${file/$reference/$name-$label}
      if ! cmp -s <(normalize "$file") <(normalize "$other"); then
        fail "$name: $other differs from $file"
      fi
    done < <(find . -path "./$reference*" -type f ! -name '*.err' ! -name '*error_vs*' \
      ! -name '*time_vs*' | sort)
  done
done
# The sweep's charts plot seconds; its images and error maps are compared above (.exr).
[ -f sweep-n3/images/hemisphere_T0.05.exr ] || fail "the sweep over 3 processes wrote no images"
grep -q '"processes": 3' hemisphere-n3.stats.json || fail "the stats do not count 3 processes"

# One line on stderr but the scene's warnings (and the sweep's opening line).
error_lines() { grep -v -E '^(warning|sweep): ' "$1"; }
expect_one_line() {  # FILE PATTERN WHAT
  local lines
  lines=$(error_lines "$1")
  if [ "$(printf '%s\n' "$lines" | grep -c .)" != 1 ] || ! grep -q -E "$2" <<<"$lines"; then
    fail "$3: expected one line matching '$2', got: $lines"
  fi
}

# A scene the root cannot read.
echo previous >kept.exr
mpi -n 3 "$RADIOSITY" render missing.json --solution sol.vtp -o kept.exr 2>missing.err
status=$?
[ $status -ne 0 ] || fail "a missing scene exited 0"
expect_one_line missing.err '^radiosity: error: missing.json: cannot open scene file: No such file or directory$' "missing scene"
[ "$(cat kept.exr)" = previous ] || fail "a missing scene touched the output"

# Process 2 cannot take the solution the root sent: its temporary folder does not exist.
mpirun -q --oversubscribe -n 2 "$RADIOSITY" render "$SCENE" --solution sol.vtp --width 16 \
  --height 16 -o kept.exr : -n 1 -x TMPDIR="$WORK/no-such-folder" "$RADIOSITY" render "$SCENE" \
  --solution sol.vtp --width 16 --height 16 -o kept.exr 2>tmpdir.err
status=$?
[ $status -eq 1 ] || fail "a process without a temporary folder: exit $status, not 1"
expect_one_line tmpdir.err '^radiosity: error: process 2: cannot copy sol.vtp to a temporary folder' \
  "a process without a temporary folder"
[ "$(cat kept.exr)" = previous ] || fail "a failed process's run touched the output"

# The root cannot write between the sweep's renders (its folder cannot be made): the others,
# already in the next render, end too.
mpi -n 3 "$RADIOSITY" sweep "$SCENE" --solution sol.vtp --methods hemisphere --width 16 \
  --height 16 --tolerances 0.2 -o /proc/no-such-folder/sweep 2>unwritable.err
status=$?
[ $status -eq 1 ] || fail "a sweep into a folder that cannot be made: exit $status, not 1"
expect_one_line unwritable.err "^radiosity: error: /proc/no-such-folder/sweep/reference.exr: cannot create" \
  "a sweep into a folder that cannot be made"

# A process killed midway (a worker, then the root): the job ends, the old output stays.
# This job's renders alone (other suites may run renders of the same binary meanwhile).
KEPT_RENDERS="^$RADIOSITY render .* -o kept\.exr"
kill_rank_midway() {  # RANK
  local pid rank
  mpi -n 3 "$RADIOSITY" render "$SCENE" --solution sol.vtp --width 160 --height 160 \
    --tolerance 0.002 -o kept.exr 2>"killed$1.err" &
  local launcher=$!
  # Wait until the renders run (their progress is not printed: poll the processes).
  for _ in $(seq 100); do
    [ "$(pgrep -c -f "$KEPT_RENDERS")" = 3 ] && break
    sleep 0.1
  done
  sleep 1
  for pid in $(pgrep -f "$KEPT_RENDERS"); do
    rank=$(tr '\0' '\n' <"/proc/$pid/environ" | sed -n 's/^OMPI_COMM_WORLD_RANK=//p')
    [ "$rank" = "$1" ] && kill -9 "$pid"
  done
  wait $launcher
}
kill_rank_midway 1
status=$?
[ $status -ne 0 ] || fail "a killed worker: the job exited 0"
expect_one_line killed1.err '^radiosity: error: stopped by mpirun \(a process of the job died' \
  "a killed worker"
[ "$(cat kept.exr)" = previous ] || fail "a killed worker: the output changed"
kill_rank_midway 0
status=$?
[ $status -ne 0 ] || fail "a killed root: the job exited 0"
[ "$(cat kept.exr)" = previous ] || fail "a killed root: the output changed"
[ -z "$(pgrep -f "$KEPT_RENDERS")" ] || fail "processes outlived the killed job"

if [ $failures -ne 0 ]; then
  echo "$failures check(s) failed"
  exit 1
fi
echo "mpi_test: every output byte-identical over ${#SETTINGS[@]} settings, and 5 faults ended cleanly"
