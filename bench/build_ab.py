#!/usr/bin/python3
"""Seconds of two whole builds (host and plugins) rendering the same scenes, measured side by side.

    bench/build_ab.py --a OLD/build/bin/nimbus --b build/bin/nimbus scenes/default.yaml ... \
        [--integrator caustics] [--iterations 16] [--runs 3] [--instructions]

Each run renders every scene with build A, then with build B (same integrator, iterations and seed),
and the script prints per scene the median over runs of each build's seconds and of the per-run ratio
B / A, and whether the two builds' images were bit-identical in every run. Only ratios taken within one
run are compared: the machine's speed drifts by +-10 % within minutes.

With --instructions, the figure is instead the instructions each build executes per iteration, counted
by callgrind (Debian's valgrind): repeatable to 0.01 % (the progress display and checkpoints follow the
clock), so one run decides changes of a percent that times cannot. Each build renders every scene for N
and 2N iterations (N = --iterations), one thread; the difference over N cancels start-up, loading and
writing. Slow (callgrind runs ~50 times slower):
use a few iterations. Not part of CI.
"""
import argparse
import os
import statistics
import tempfile

from exr_compare import compare_images
from nimbus_tools import callgrind_instructions
from overhead import render


def compare_instructions(args):
    """Per scene: each build's instructions per iteration (M), B / A, and whether the images match."""
    print("scene, A M instructions/iteration, B M instructions/iteration, B/A, images identical")
    n = args.iterations
    with tempfile.TemporaryDirectory() as tmp:
        outs = {side: os.path.join(tmp, side + ".exr") for side in ("a", "b")}
        for scene in args.scenes:
            per_iteration = {}
            for side, nimbus in (("a", args.a), ("b", args.b)):
                counts = [callgrind_instructions([nimbus, "render", scene, "-o", outs[side], "--integrator",
                                                  args.integrator, "--iterations", str(k), "--seed", "1",
                                                  "--threads", "1", "-q"])[0] for k in (2 * n, n)]
                per_iteration[side] = (counts[0] - counts[1]) / n  # the N-iteration image stays for the check
            a, b = per_iteration["a"], per_iteration["b"]
            same = compare_images(outs["a"], outs["b"])[0]
            print("%s, %.3f, %.3f, %.4f, %s" % (os.path.basename(scene), a / 1e6, b / 1e6, b / a,
                                                "yes" if same else "no"))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--a", required=True, help="the nimbus executable of build A")
    ap.add_argument("--b", required=True, help="the nimbus executable of build B")
    ap.add_argument("--integrator", default="caustics")
    ap.add_argument("--iterations", type=int, default=16)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--instructions", action="store_true",
                    help="compare instructions per iteration (callgrind) instead of seconds")
    args = ap.parse_args()
    if args.instructions:
        compare_instructions(args)
        return
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
