#!/usr/bin/env bash
# Instructions executed per iteration, nimbus.pt against nimbus.caustics, counted by valgrind's callgrind:
# a figure free of the machine's timing noise, for the zero-cost rule on scenes without caustics.
#   bash bench/instructions.sh [SCENE.yaml ...]     (default: the two caustic-free scenes; ~3 min each)
# Per iteration = (count at 3 iterations - count at 1 iteration) / 2, so scene loading and the solver's
# first-iteration probe are excluded; the probe's cost is printed separately.
set -euo pipefail
cd "$(dirname "$0")/.."
nimbus=${NIMBUS:-build/bin/nimbus}
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(scenes/caustics/diffuse-room.yaml scenes/caustics/interior.yaml)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
count() {  # scene integrator iterations -> instructions
  valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.out" "$nimbus" render "$1" --integrator "$2" \
    --iterations "$3" --seed 1 -o "$tmp/out.exr" -q 2>&1 | awk '/Collected/ {print $4}'
}
for scene in "${scenes[@]}"; do
  pt1=$(count "$scene" pt 1) pt3=$(count "$scene" pt 3) c1=$(count "$scene" caustics 1) c3=$(count "$scene" caustics 3)
  /usr/bin/python3 - "$scene" "$pt1" "$pt3" "$c1" "$c3" <<'PY'
import sys
scene, pt1, pt3, c1, c3 = sys.argv[1], *map(int, sys.argv[2:])
pt, c = (pt3 - pt1) / 2, (c3 - c1) / 2
print(f"{scene}: instructions per iteration pt {pt / 1e6:,.1f} M, caustics {c / 1e6:,.1f} M, "
      f"difference {100 * (c / pt - 1):+.2f} %; first iteration (probe) {(c1 - pt1) / 1e6:+,.0f} M "
      f"({100 * (c1 / pt1 - 1):+.1f} %)")
PY
done
