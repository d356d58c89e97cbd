# Sourced by the benchmark scripts that compare against an earlier commit:
# `earlier_radiosity COMMIT` builds that commit's `radiosity` once, in a worktree under $TMPDIR
# (reused by later runs), and prints the binary's path.
earlier_radiosity() {
  local base=$1
  local base_dir
  base_dir="${TMPDIR:-/tmp}/rad-base-$(git rev-parse --short "$base")"
  if [ ! -x "$base_dir/build/cli/radiosity" ]; then
    echo "building $base's radiosity in $base_dir" >&2
    rm -rf "$base_dir"
    git worktree prune
    git worktree add --detach "$base_dir" "$base" >/dev/null
    cmake -S "$base_dir" -B "$base_dir/build" -DCMAKE_BUILD_TYPE=Release -DRAD_BUILD_TESTS=OFF \
      -DRAD_BUILD_BENCH=OFF >/dev/null
    cmake --build "$base_dir/build" --target radiosity -j2 >/dev/null
  fi
  echo "$base_dir/build/cli/radiosity"
}
