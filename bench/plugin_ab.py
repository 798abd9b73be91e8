#!/usr/bin/python3
"""Render seconds of two builds of one plugin, measured side by side in one run.

    bench/plugin_ab.py --plugin libnimbus_pathtracer.so --integrator pt --a OLD.so --b NEW.so \\
        scenes/caustics/pool.yaml [--iterations 64] [--runs 5]

Each run renders every scene with build A and build B of the plugin (copied into the build's plugin
directory before each render and restored at the end), same iterations and seed, alternating which goes
first. Prints per scene the median seconds of both builds and the median of the per-run ratio B / A.
Use bench/overhead_ab.py to compare caustics builds by their overhead over nimbus.pt. Not part of CI.
"""
import argparse
import os
import statistics
import tempfile

from nimbus_tools import PluginSwap, add_ab_arguments
from overhead import render


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_ab_arguments(ap, "plugin library")
    ap.add_argument("--plugin", required=True, help="library file name in the plugin directory")
    ap.add_argument("--integrator", required=True, help="integrator to render with, e.g. pt")
    args = ap.parse_args()

    with tempfile.TemporaryDirectory() as tmp, \
            PluginSwap(args.nimbus, args.plugin, {"A": args.a, "B": args.b}) as swap:
        out = os.path.join(tmp, "img.exr")
        for scene in args.scenes:
            t = {"A": [], "B": []}
            for i in range(args.runs):
                for build in ("A", "B") if i % 2 == 0 else ("B", "A"):
                    swap.use(build)
                    meta = render(args.nimbus, scene, args.integrator, args.iterations, i + 1, out)
                    t[build].append(float(meta["nimbus:seconds"]))
            ratio = [b / a for a, b in zip(t["A"], t["B"])]
            print(f"{os.path.basename(scene):20s} A {statistics.median(t['A']):7.3f} s  "
                  f"B {statistics.median(t['B']):7.3f} s  time B/A {statistics.median(ratio):.3f}  "
                  f"(runs B/A: {' '.join(f'{r:.3f}' for r in ratio)})", flush=True)


if __name__ == "__main__":
    main()
