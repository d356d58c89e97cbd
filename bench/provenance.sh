# Sourced by the benchmark scripts: `provenance PATH...` prints where a table was made, the
# machine (cores, CPU), the date and the commit, marked "plus uncommitted changes" when any of
# the given paths (the code and data the table depends on) differs from it.
provenance() {
  echo "- machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')"
  echo "- date: $(date -u +%Y-%m-%d)"
  local dirty=""
  [ -z "$(git status --porcelain -- "$@" 2>/dev/null)" ] || dirty=" plus uncommitted changes"
  echo "- commit: $(git rev-parse --short HEAD 2>/dev/null || echo unknown)$dirty"
}
