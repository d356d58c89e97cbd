#!/usr/bin/env bash
# The README's two commands on a fresh Debian 12 machine (issue 39): each run is a new minimal
# Debian (debootstrap --variant=minbase bookworm) in a chroot, with only `make` added (the
# README asks for it), a clone of the repository at a commit, and `make demo` or `make test`
# timed from there: installing packages, configuring, building, running. Writes
# bench/results/fresh_machine.md and the README's line between its "fresh machine" markers.
# Usage (as root, about an hour): bash bench/fresh_machine.sh [BASE_COMMIT]
#   BASE_COMMIT (default 1043789, before make demo built the executable alone): its make demo
#   is timed too, for the ratio.
# Downloads the packages each run (a fresh machine has none); the machine is shared and noisy,
# so ratios are of runs made one after the other here.
set -euo pipefail
cd "$(dirname "$0")/.."
base=${1:-1043789}
head=$(git rev-parse --short HEAD)
work=${FRESH_WORK:-/var/tmp/rad-fresh}
out=bench/results/fresh_machine.md
[ "$(id -u)" -eq 0 ] || { echo "fresh_machine: needs root (debootstrap, chroot)" >&2; exit 1; }
command -v debootstrap >/dev/null || apt-get install -y -qq debootstrap >/dev/null

mkdir -p "$work"
if [ ! -d "$work/pristine" ]; then
  debootstrap --variant=minbase bookworm "$work/pristine.tmp" http://deb.debian.org/debian >/dev/null
  mv "$work/pristine.tmp" "$work/pristine"
fi

root=$work/machine
unmount() {
  for m in dev/pts dev/shm dev sys proc; do umount "$root/$m" 2>/dev/null || true; done
}
trap unmount EXIT

# run COMMIT TARGET: prints "TOTAL INSTALL CONFIGURE BUILD RUN" seconds for make TARGET.
run() {
  local commit=$1 target=$2 log=$work/$1-$2.log
  unmount
  rm -rf "$root"
  cp -a "$work/pristine" "$root"
  git clone -q . "$root/root/repo"
  git -C "$root/root/repo" checkout -q "$commit"
  cp /etc/resolv.conf "$root/etc/"
  mount -t proc proc "$root/proc"
  mount -t sysfs sysfs "$root/sys"  # hwloc (under mpirun) reads the CPU topology there
  mount --bind /dev "$root/dev"
  mount --bind /dev/pts "$root/dev/pts"
  mount -t tmpfs tmpfs "$root/dev/shm"
  chroot "$root" bash -c 'apt-get update -qq && apt-get install -y -qq make >/dev/null 2>&1'
  # Each line of the run with the seconds since its start.
  chroot "$root" bash -c "cd /root/repo && start=\$(date +%s);
    make $target 2>&1 | while IFS= read -r line; do echo \"\$(( \$(date +%s) - start )) \$line\"; done;
    echo \"\$(( \$(date +%s) - start )) exit \${PIPESTATUS[0]}\"" >"$log"
  if ! tail -1 "$log" | grep -q " exit 0$"; then
    # A failed build is no measurement; a test that failed is said beside the times.
    grep -q "tests passed, .* failed" "$log" || {
      echo "fresh_machine: make $target at $commit failed: $log" >&2
      return 1
    }
    echo "fresh_machine: make $target at $commit: $(grep -o '[0-9]* tests failed.*' "$log")" >&2
  fi
  # Phases: packages installed, then the build folder configured, then built, then run.
  awk '
    /install-deps: (done|all)/ && !i { i = $1 }
    /Build files have been written/ && !c { c = $1 }
    /Built target radiosity$|Linking CXX executable .*radiosity$/ { b = $1 }
    /ctest|Test project|build\/cli\/radiosity info/ && !r { r = $1 }
    /tests passed, / { sub(/^[0-9]+ /, ""); result = $0; gsub(/ /, "_", result) }
    END { total = $1; if (!r) r = b; print total, i, c - i, r - c, total - r, result }' "$log"
}

# Each run once per commit (its times kept in the work folder): a run that failed is redone.
timed() {
  [ -s "$work/$1-$2.times" ] || run "$1" "$2" >"$work/$1-$2.times"
  cat "$work/$1-$2.times"
}
timed "$head" demo >/dev/null
read -r demo_total demo_install demo_configure demo_build demo_run _ < <(timed "$head" demo)
timed "$base" demo >/dev/null
read -r base_total base_install base_configure base_build base_run _ < <(timed "$base" demo)
timed "$head" test >/dev/null
read -r test_total test_install test_configure test_build test_run test_result < <(timed "$head" test)

ratio=$(python3 -c "print(f'{$demo_total / $base_total:.2f}')")
minutes() { python3 -c "print(f'{$1 / 60:.0f}')"; }
{
  echo "# The README's commands on a fresh machine"
  echo
  echo "\`bash bench/fresh_machine.sh $base\` (issue 39): each row a new minimal Debian 12 in a chroot"
  echo "(debootstrap minbase, plus \`make\`), a clone at the commit, the command timed from there;"
  echo "packages downloaded from deb.debian.org each time. Seconds."
  echo
  echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
  echo "date: $(date -u +%Y-%m-%d)"
  echo
  echo "| commit | command | total | installing packages | configuring | building | running |"
  echo "|---|---|---|---|---|---|---|"
  echo "| $base | make demo | $base_total | $base_install | $base_configure | $base_build | $base_run |"
  echo "| $head | make demo | $demo_total | $demo_install | $demo_configure | $demo_build | $demo_run |"
  echo "| $head | make test | $test_total | $test_install | $test_configure | $test_build | $test_run |"
  echo
  echo "make test: ${test_result//_/ }."
  echo
  echo "make demo at $head takes $ratio of the time at $base: it installs the packages the"
  echo "executable needs (not GoogleTest, Google Benchmark, clang, clang-format or the test models)"
  echo "and builds the executable alone, with Ninja and unity builds of the modules."
} >"$out"

python3 - "$(minutes "$demo_total")" "$(minutes "$test_total")" "${test_result//_/ }" <<'PY'
import re, sys
demo, test, result = sys.argv[1], sys.argv[2], sys.argv[3]
text = open("README.md").read()
found = re.search(r"(\d+) tests failed out of (\d+)", result)
failed = f", with {found[1]} of its {found[2]} tests failing there" if found and found[1] != "0" else ""
line = (f"On a fresh machine `make demo` took {demo} minutes and `make test` {test}{failed} "
        "([bench/results/fresh_machine.md](bench/results/fresh_machine.md)).")
text = re.sub(r"(<!-- fresh machine: begin -->\n).*?(\n<!-- fresh machine: end -->)",
              lambda m: m.group(1) + line + m.group(2), text, flags=re.S)
open("README.md", "w").write(text)
PY
cat "$out"
