# Sourced by the building benchmarks (bench/building_solve.sh, bench/hierarchical_solve.sh):
# the scenes they solve and the settings a scene of their size needs.
# The solver's settings for a scene of this size: one element per patch, no adaptive
# refinement, stop at 2% unshot (the local pass computes the exact irradiance from it).
building_coarse="--element-levels 0 --refine-threshold 0 --unshot 0.02"
# `write_buildings DIR` writes DIR/building-S-X-Z.json for 1 x 2 x 2, 1 x 3 x 3, 1 x 5 x 5 and
# 3 x 5 x 5 (storeys x rooms; data/building/make_building.py, the same bytes every time).
write_buildings() {
  local size storeys rx rz
  for size in "1 2 2" "1 3 3" "1 5 5" "3 5 5"; do
    read -r storeys rx rz <<<"$size"
    python3 data/building/make_building.py --storeys "$storeys" --rooms-x "$rx" --rooms-z "$rz" \
      -o "$1/building-$storeys-$rx-$rz.json"
  done
}
