#!/usr/bin/python3
"""Overhead over nimbus.pt of two builds of the caustics plugin, measured side by side in one run.

    bench/overhead_ab.py --a OLD.so --b NEW.so scenes/caustics/*.yaml [--iterations 16] [--runs 5]

Each run renders every scene with pt, with build A and with build B (the plugin library is copied into
the build's plugin directory before each render, and restored at the end), same iterations and seed.
Per run and build the overhead is caustics seconds / pt seconds - 1 against that run's pt render; the
script prints per scene the median over runs for both builds and the median of the per-run ratio
B / A of caustics seconds, and of the photon passes' seconds (stat `caustics_photon_seconds`, which
moves less with the machine than the whole render). The machine's speed drifts by ±10 % within
minutes, so only ratios taken within one run are compared. Not part of CI.
"""
import argparse
import os
import statistics
import tempfile

from nimbus_tools import PluginSwap, add_ab_arguments
from overhead import render


def seconds(nimbus, scene, integrator, iterations, seed, out):
    """The render's seconds and its photon passes' seconds (0 for nimbus.pt)."""
    meta = render(nimbus, scene, integrator, iterations, seed, out)
    return float(meta["nimbus:seconds"]), float(meta.get("nimbus:stat:caustics_photon_seconds", 0))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_ab_arguments(ap, "caustics plugin library")
    args = ap.parse_args()

    with tempfile.TemporaryDirectory() as tmp, \
            PluginSwap(args.nimbus, "libnimbus_caustics.so", {"A": args.a, "B": args.b}) as swap:
        out = os.path.join(tmp, "img.exr")
        for scene in args.scenes:
            over = {"A": [], "B": []}
            ratio, photon_ratio = [], []
            for i in range(args.runs):
                pt = seconds(args.nimbus, scene, "pt", args.iterations, i + 1, out)[0]
                t, photons = {}, {}
                for build in ("A", "B") if i % 2 == 0 else ("B", "A"):
                    swap.use(build)
                    t[build], photons[build] = seconds(args.nimbus, scene, "caustics", args.iterations, i + 1,
                                                       out)
                    over[build].append(100 * (t[build] / pt - 1))
                ratio.append(t["B"] / t["A"])
                if photons["A"] > 0:
                    photon_ratio.append(photons["B"] / photons["A"])
            print(f"{os.path.basename(scene):20s} overhead A {statistics.median(over['A']):6.1f} %  "
                  f"B {statistics.median(over['B']):6.1f} %  time B/A {statistics.median(ratio):.3f}  "
                  f"photon passes B/A {statistics.median(photon_ratio) if photon_ratio else float('nan'):.3f}  "
                  f"(runs A: {' '.join(f'{o:.0f}' for o in over['A'])}; B: {' '.join(f'{o:.0f}' for o in over['B'])})",
                  flush=True)


if __name__ == "__main__":
    main()
