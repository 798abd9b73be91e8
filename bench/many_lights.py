#!/usr/bin/python3
"""Many-light benchmark (issue: light-sampler plugins). Measures, in one run on this machine:
  1. per-sample cost of scenes/many-lights.yaml (10,000 emitters + sun + sky, tree sampler) against
     scenes/one-light.yaml (same geometry, one area light): ratio of seconds per camera sample;
  2. relMSE at equal time of nimbus.lights.tree against nimbus.lights.power, against a long reference
     (tree sampler), medians over seeds.

    bench/many_lights.py [--seconds 30] [--reference-iterations 1024] [--seeds 3] [--out docs/many-lights]

The reference is rendered once (kept in --out; delete it after changing the scene) for a fixed number of
iterations, so that its quality does not depend on how busy the machine was.
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


def render(nimbus, scene, out, stop, seed, sampler):
    """stop: the stopping rule, e.g. ["--time", "10"] or ["--iterations", "1024"]."""
    run([nimbus, "render", scene, "-o", out, *stop, "--seed", str(seed), "--light-sampler", sampler, "-q"])
    return meta(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seconds", type=float, default=30)
    ap.add_argument("--reference-iterations", type=int, default=1024)
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--out", default="docs/many-lights")
    ap.add_argument("--nimbus", default="build/bin/nimbus")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    many, one = "scenes/many-lights.yaml", "scenes/one-light.yaml"
    if not os.path.exists(many):
        run(["/usr/bin/python3", "scenes/generate_many_lights.py"])

    # The two scenes alternate, so that a slow moment of the machine weighs on both.
    per = {"one-light": [], "many-lights": []}
    for s in range(a.seeds):
        for name, scene, sampler in (("one-light", one, "nimbus.lights.power"),
                                     ("many-lights", many, "nimbus.lights.tree")):
            it, sec = render(a.nimbus, scene, os.path.join(a.out, f"cost-{name}.exr"), ["--time", str(a.seconds)], s + 1,
                             sampler)
            per[name].append(sec / it)
            print(f"{name} seed {s + 1}: {sec / it:.4g} s per iteration", flush=True)
    cost = {name: statistics.median(v) for name, v in per.items()}
    ratio = cost["many-lights"] / cost["one-light"]

    ref = os.path.join(a.out, "many-lights-reference.exr")
    if not os.path.exists(ref):
        render(a.nimbus, many, ref, ["--iterations", str(a.reference_iterations)], 1000, "nimbus.lights.tree")
    err = {}
    for sampler in ("nimbus.lights.power", "nimbus.lights.tree"):
        e = []
        for s in range(a.seeds):
            out = os.path.join(a.out, f"equal-time-{sampler}-{s + 1}.exr")
            render(a.nimbus, many, out, ["--time", str(a.seconds)], s + 1, sampler)
            e.append(json.loads(run([a.nimbus, "compare", out, ref, "--json"]))["relmse"])
        err[sampler] = statistics.median(e)

    print("\nper-iteration cost: one-light %.4g s, many-lights (tree) %.4g s, ratio %.2f (goal <= 1.5)"
          % (cost["one-light"], cost["many-lights"], ratio))
    print("equal-time relMSE (%g s, median of %d seeds): power %.4g, tree %.4g, power/tree %.2f (goal > 1)"
          % (a.seconds, a.seeds, err["nimbus.lights.power"], err["nimbus.lights.tree"],
             err["nimbus.lights.power"] / err["nimbus.lights.tree"]))


if __name__ == "__main__":
    main()
