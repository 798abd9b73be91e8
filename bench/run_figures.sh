#!/bin/bash
# The figures docs/performance.md takes from one serial run (a quiet machine: nothing else running):
# §1 throughput, §2 many lights, §4 overhead table, §5 error table, §8 emission strategies. Long: about
# three and a quarter hours on 2 cores (the error stage alone about 100 minutes with its references, the
# guiding stage about 40).
# Writes the files the document cites:
#   docs/bench-pt.txt
#   docs/overhead-64.csv
#   docs/error-vs-time/<scene>/error-vs-time.csv, <scene>-error-vs-time.png, <scene>-reference.exr.txt
# and, not committed, the images in docs/many-lights/ and the references docs/error-vs-time/<scene>/*.exr
# (delete a reference to have it rendered again, e.g. after changing its scene).
#   [STAGES="bench overhead lights error guiding"] bash bench/run_figures.sh [REFERENCE_SECONDS=200] [TIMES=5,20]
set -euo pipefail
cd "$(dirname "$0")/.."
REF_SECONDS=${1:-200}
TIMES=${2:-5,20}
STAGES=${STAGES:-bench overhead lights error guiding}
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
# Every scene in scenes/, solver against nimbus.pt at equal time, each against an independent reference
# (one the solver did not render): nimbus.pt where path tracing converges (area lights, no caustics);
# nimbus.lt where a delta light's caustics sit behind glass or a mirror, compared over the pixels the light
# tracer covers (every pixel whose camera ray first meets a non-specular surface; --covered-only). The
# pool (the sun's caustics seen through water) has neither: its reference is the solver's own long
# render, and says so. Each reference is two renders of REFERENCE_SECONDS (error_vs_time.py). On
# cornell-point the solver's error falls as 1/time and path tracing's does not, so it also runs 60 s.
for spec in default:pt:all one-light:pt:all many-lights:pt:all caustics/diffuse-room:pt:all \
    caustics/sphere-area:pt:all caustics/glasses:lt:covered caustics/sphere-point:lt:covered \
    caustics/cornell-point:lt:covered caustics/ring:lt:covered caustics/interior:lt:covered \
    caustics/envmap:pt:all caustics/pool:caustics:all; do
  IFS=: read -r path ref mode <<<"$spec"
  scene=$(basename "$path")
  extra=() times=$TIMES
  [[ $mode == covered ]] && extra=(--covered-only)
  [[ $scene == cornell-point ]] && times=$TIMES,60
  $PY bench/error_vs_time.py scenes/$path.yaml --integrators pt,caustics --times "$times" --seeds 3 \
    --reference-integrator "$ref" --reference-time "$REF_SECONDS" "${extra[@]}" --out docs/error-vs-time/$scene
done
# The moving box: the pixels its glass sphere sweeps are left out (the light tracer does not see the box
# through it).
$PY bench/error_vs_time.py scenes/caustics/cornell-moving.yaml --integrators pt,caustics --times "$TIMES" \
  --seeds 3 --reference-integrator lt --reference-time "$REF_SECONDS" --covered-only \
  --exclude-render bench/masks/cornell-moving-sphere.yaml --out docs/error-vs-time/cornell-moving
fi
if stage guiding; then
# §8: the photon emission strategies at equal time (relMSE between independent renders: all are
# unbiased), every LightMix group's caustic on many-lights against light-traced references of its
# lamps, and the render region against the error stage's pool reference.
echo "== photon emission strategies"
$PY bench/emission_strategies.py scenes/caustics/{stadium,apartment,envmap}.yaml \
  --strategies uniform,adaptive-map,guided --time 8
$PY bench/emission_strategies.py scenes/caustics/{pool,sphere-point,sphere-area,ring,glasses,interior}.yaml \
  scenes/caustics/{cornell-point,many-lights,diffuse-room}.yaml scenes/default.yaml \
  --strategies uniform,adaptive-map --time 8
$PY bench/lightmix_caustics.py --time 30 --reference-time 60 --seeds 3
for emission in uniform adaptive-map; do
  $PY bench/render_region.py scenes/caustics/pool.yaml --region 224,80,416,208 --iterations 32 \
    --reference docs/error-vs-time/pool/pool-reference.exr --flags "--photon_emission $emission"
done
fi
echo "== done"
