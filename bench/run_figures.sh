#!/bin/bash
# The figures docs/performance.md takes from one serial run (a quiet machine: nothing else running):
# §1 throughput, §2 many lights, §4 overhead table, §5 error table. Long: about an hour on 2 cores, plus
# sphere-point's 8,000-iteration reference when it is missing (~25 minutes).
# Writes the files the document cites:
#   docs/bench-pt.txt
#   docs/overhead-64.csv
#   docs/error-vs-time/<scene>/error-vs-time.csv, <scene>-error-vs-time.png, <scene>-reference.exr.txt
# and, not committed, the images in docs/many-lights/ and the references docs/error-vs-time/<scene>/*.exr
# (delete a reference to have it rendered again, e.g. after changing its scene).
#   [STAGES="bench overhead lights error"] bash bench/run_figures.sh [REFERENCE_SECONDS=240] [TIMES=6,24]
set -euo pipefail
cd "$(dirname "$0")/.."
REF_SECONDS=${1:-240}
TIMES=${2:-6,24}
STAGES=${STAGES:-bench overhead lights error}
stage() { [[ " $STAGES " == *" $1 "* ]]; }
PY=/usr/bin/python3
NIMBUS=build/bin/nimbus
echo "== commit $(git rev-parse --short HEAD), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
if stage bench; then
echo "== nimbus.pt vs Embree rays/s"
build/bin/nimbus_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true | tee docs/bench-pt.txt
fi
if stage overhead; then
# 64 iterations: photon passes grow with the useful-pixel ratio, which accumulates, so short renders
# understate the steady state. The last two scenes have no caustics (the zero-cost rule).
echo "== caustics overhead per iteration"
$PY bench/overhead.py scenes/caustics/{sphere-point,sphere-area,ring,pool,glasses,diffuse-room,interior}.yaml \
  --iterations 64 --runs 3 --out docs/overhead-64.csv
fi
if stage lights; then
echo "== many lights"
$PY bench/many_lights.py --seconds 10 --reference-iterations 1024 --seeds 5 --out docs/many-lights
fi
if stage error; then
echo "== error vs time"
# References: nimbus.pt where path tracing converges (a small area light, directly visible caustic); the
# solver itself, run long, where it alone converges (point, spot and sun light: pt cannot sample them,
# light tracing cannot see caustics through glass or water). It is consistent and agrees with pt and lt
# where they converge (tests/caustics).
for spec in sphere-area:pt sphere-point:caustics ring:caustics pool:caustics glasses:caustics; do
  scene=${spec%%:*} ref=${spec##*:} dir=docs/error-vs-time/${spec%%:*}
  times=$TIMES
  refargs=(--reference-integrator "$ref" --reference-time "$REF_SECONDS")
  if [[ $scene == sphere-point ]]; then
    # Path tracing's error here is a fixed bias (the point light's caustic it cannot render) and the
    # solver's falls as 1/time, so the ratio is also measured at 96 s. A 240 s reference would be noisier
    # than the solver's 96 s renders: the reference is a fixed 8,000 iterations of the solver.
    times=$TIMES,96
    refexr=$dir/$scene-reference.exr
    if [[ ! -f $refexr ]]; then
      mkdir -p "$dir"
      cmd=("$NIMBUS" render scenes/caustics/$scene.yaml -o "$refexr" --integrator caustics --iterations 8000
           --seed 1000 -q)
      start=$SECONDS
      "${cmd[@]}"
      printf 'command: %s\nwall seconds: %d\ncommit: %s; used by error-vs-time.csv\n' "${cmd[*]}" \
        $((SECONDS - start)) "$(git rev-parse --short HEAD)" >"$refexr.txt"
    fi
    refargs=(--reference "$refexr")
  fi
  $PY bench/error_vs_time.py scenes/caustics/$scene.yaml --integrators pt,caustics --times "$times" --seeds 3 \
    "${refargs[@]}" --out "$dir"
done
fi
echo "== done"
