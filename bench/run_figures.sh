#!/bin/bash
# Every timing figure of docs/performance.md, in one serial run (a quiet machine: nothing else running).
# Long: about an hour on 2 cores. Outputs: docs/bench-pt.txt, docs/overhead-64.csv, docs/many-lights/,
# docs/error-vs-time/<scene>/ (CSV, plot; reference and test EXRs are not committed).
#   [STAGES="bench overhead lights error"] bash bench/run_figures.sh [REFERENCE_SECONDS=240] [TIMES=8,32]
set -euo pipefail
cd "$(dirname "$0")/.."
REF_SECONDS=${1:-240}
TIMES=${2:-8,32}
STAGES=${STAGES:-bench overhead lights error}
stage() { [[ " $STAGES " == *" $1 "* ]]; }
PY=/usr/bin/python3
echo "== commit $(git rev-parse --short HEAD), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2)"
if stage bench; then
echo "== nimbus.pt vs Embree rays/s"
build/bin/nimbus_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true | tee docs/bench-pt.txt
fi
if stage overhead; then
# 64 iterations: photon passes grow with the useful-pixel ratio, which accumulates, so short renders
# understate the steady state.
echo "== caustics overhead per iteration"
$PY bench/overhead.py scenes/caustics/*.yaml --iterations 64 --runs 3 --out docs/overhead-64.csv
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
  scene=${spec%%:*} ref=${spec##*:}
  $PY bench/error_vs_time.py scenes/caustics/$scene.yaml --integrators pt,caustics --times "$TIMES" --seeds 3 \
    --reference-integrator "$ref" --reference-time "$REF_SECONDS" --out docs/error-vs-time/$scene
done
fi
echo "== done"
