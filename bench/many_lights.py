#!/usr/bin/python3
"""Many-light benchmark (issue: light-sampler plugins). Measures, in one run on this machine:
  1. per-sample cost of scenes/many-lights.yaml (10,000 emitters + sun + sky, tree sampler) against
     scenes/one-light.yaml (same geometry, one area light): ratio of seconds per camera sample;
  2. relMSE at equal time of nimbus.lights.tree against nimbus.lights.power, against a long reference
     (tree sampler), medians over seeds.

    bench/many_lights.py [--seconds 30] [--reference-seconds 900] [--seeds 3] [--out docs/many-lights]
"""
import argparse
import json
import os
import statistics

from nimbus_tools import exr_metadata, run


def meta(exr):
    """Iterations and seconds from the EXR header."""
    m = exr_metadata(exr)
    return float(m["nimbus:iterations"]), float(m["nimbus:seconds"])


def render(nimbus, scene, out, seconds, seed, sampler):
    run([nimbus, "render", scene, "-o", out, "--time", str(seconds), "--seed", str(seed), "--light-sampler", sampler,
         "-q"])
    return meta(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seconds", type=float, default=30)
    ap.add_argument("--reference-seconds", type=float, default=900)
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--out", default="docs/many-lights")
    ap.add_argument("--nimbus", default="build/bin/nimbus")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    many, one = "scenes/many-lights.yaml", "scenes/one-light.yaml"
    if not os.path.exists(many):
        run(["/usr/bin/python3", "scenes/generate_many_lights.py"])

    cost = {}
    for name, scene, sampler in (("one-light", one, "nimbus.lights.power"), ("many-lights", many, "nimbus.lights.tree")):
        per = []
        for s in range(a.seeds):
            it, sec = render(a.nimbus, scene, os.path.join(a.out, f"cost-{name}.exr"), a.seconds, s + 1, sampler)
            per.append(sec / it)
        cost[name] = statistics.median(per)
    ratio = cost["many-lights"] / cost["one-light"]

    ref = os.path.join(a.out, "many-lights-reference.exr")
    if not os.path.exists(ref):
        render(a.nimbus, many, ref, a.reference_seconds, 1000, "nimbus.lights.tree")
    err = {}
    for sampler in ("nimbus.lights.power", "nimbus.lights.tree"):
        e = []
        for s in range(a.seeds):
            out = os.path.join(a.out, f"equal-time-{sampler}-{s + 1}.exr")
            render(a.nimbus, many, out, a.seconds, s + 1, sampler)
            e.append(json.loads(run([a.nimbus, "compare", out, ref, "--json"]))["relmse"])
        err[sampler] = statistics.median(e)

    print("\nper-iteration cost: one-light %.4g s, many-lights (tree) %.4g s, ratio %.2f (goal <= 1.5)"
          % (cost["one-light"], cost["many-lights"], ratio))
    print("equal-time relMSE (%g s, median of %d seeds): power %.4g, tree %.4g, power/tree %.2f (goal > 1)"
          % (a.seconds, a.seeds, err["nimbus.lights.power"], err["nimbus.lights.tree"],
             err["nimbus.lights.power"] / err["nimbus.lights.tree"]))


if __name__ == "__main__":
    main()
