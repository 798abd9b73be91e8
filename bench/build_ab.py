#!/usr/bin/python3
"""Seconds of two whole builds (host and plugins) rendering the same scenes, measured side by side.

    bench/build_ab.py --a OLD/build/bin/nimbus --b build/bin/nimbus scenes/default.yaml ... \
        [--integrator caustics] [--iterations 16] [--runs 3]

Each run renders every scene with build A, then with build B (same integrator, iterations and seed),
and the script prints per scene the median over runs of each build's seconds and of the per-run ratio
B / A, and whether the two builds' images were bit-identical in every run. Only ratios taken within one
run are compared: the machine's speed drifts by +-10 % within minutes. Not part of CI.
"""
import argparse
import os
import statistics
import tempfile

from exr_compare import compare_images
from overhead import render


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--a", required=True, help="the nimbus executable of build A")
    ap.add_argument("--b", required=True, help="the nimbus executable of build B")
    ap.add_argument("--integrator", default="caustics")
    ap.add_argument("--iterations", type=int, default=16)
    ap.add_argument("--runs", type=int, default=3)
    args = ap.parse_args()
    print("scene, A seconds, B seconds, B/A (medians over %d runs), images identical" % args.runs)
    with tempfile.TemporaryDirectory() as tmp:
        out_a, out_b = os.path.join(tmp, "a.exr"), os.path.join(tmp, "b.exr")
        for scene in args.scenes:
            a, b, ratio, same = [], [], [], True
            for run in range(args.runs):
                ma = render(args.a, scene, args.integrator, args.iterations, 1, out_a)
                mb = render(args.b, scene, args.integrator, args.iterations, 1, out_b)
                a.append(float(ma["nimbus:seconds"]))
                b.append(float(mb["nimbus:seconds"]))
                ratio.append(b[-1] / a[-1])
                same = same and compare_images(out_a, out_b)[0]
            print("%s, %.3f, %.3f, %.3f, %s" % (os.path.basename(scene), statistics.median(a), statistics.median(b),
                                                statistics.median(ratio), "yes" if same else "no"))


if __name__ == "__main__":
    main()
