#!/usr/bin/python3
"""One frame split into tasks and merged, against one render of the same iterations (docs/farm-rendering.md).

    bench/farm_split.py [--scene scenes/caustics/sphere-point.yaml] [--iterations 64] [--tasks 4]
        [--seeds 3] [--reference-iterations 2048] [--threads 2] [--nimbus build/bin/nimbus]

Renders an independent reference with the light tracer (nimbus.lt, which converges on point-light
caustics), compared over the pixels it covers (bench/error_vs_time.py --covered-only: not those seen
through glass or in mirrors, which a light tracer cannot render), then for each seed: the whole frame in one render, and its N tasks one after another
(`nimbus render --task K --tasks N`, each with all the threads, as an array runs on one node) followed by
`nimbus merge`. Prints per seed and as medians: the relMSE of both against the reference and
their ratio, and the wall time of the single render against the tasks plus the merge (the overhead of the
parts and the merge). Not part of CI.
"""
import argparse
import os
import statistics
import tempfile
import time

from error_vs_time import region_mask, relmse
from nimbus_tools import read_rgb, run


def timed(cmd):
    t0 = time.perf_counter()
    run(cmd, echo=False)
    return time.perf_counter() - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", default="scenes/caustics/sphere-point.yaml")
    ap.add_argument("--iterations", type=int, default=64)
    ap.add_argument("--tasks", type=int, default=4)
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--reference-iterations", type=int, default=2048)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--nimbus", default="build/bin/nimbus")
    args = ap.parse_args()
    nimbus, threads = args.nimbus, ["--threads", str(args.threads), "-q"]
    with tempfile.TemporaryDirectory() as tmp:
        ref = os.path.join(tmp, "reference.exr")
        seconds = timed([nimbus, "render", args.scene, "--integrator", "lt", "--seed", "1000", "--iterations",
                         str(args.reference_iterations), "-o", ref] + threads)
        ref_rgb = read_rgb(ref)
        mask = region_mask(ref_rgb, covered_only=True, crop=None)
        print(f"reference: nimbus.lt, {args.reference_iterations} iterations, {seconds:.0f} s, "
              f"{int(mask.sum())} covered pixels")
        print("seed, relMSE single, relMSE merged, merged/single, seconds single, seconds tasks+merge, ratio")
        rows = []
        for seed in range(1, args.seeds + 1):
            common = ["--seed", str(seed), "--iterations", str(args.iterations)] + threads
            single = os.path.join(tmp, f"single{seed}.exr")
            t_single = timed([nimbus, "render", args.scene, "-o", single] + common)
            parts, t_split = [], 0.0
            for k in range(args.tasks):
                parts.append(os.path.join(tmp, f"s{seed}.part{k}.exr"))
                t_split += timed([nimbus, "render", args.scene, "-o", parts[-1], "--task", str(k), "--tasks",
                                  str(args.tasks)] + common)
            merged = os.path.join(tmp, f"merged{seed}.exr")
            t_split += timed([nimbus, "merge"] + parts + ["-o", merged])
            e_single = relmse(read_rgb(single), ref_rgb, mask)
            e_merged = relmse(read_rgb(merged), ref_rgb, mask)
            rows.append((e_single, e_merged, e_merged / e_single, t_single, t_split, t_split / t_single))
            print(f"{seed}, {e_single:.5f}, {e_merged:.5f}, {rows[-1][2]:.3f}, {t_single:.2f}, {t_split:.2f}, "
                  f"{rows[-1][5]:.3f}", flush=True)
        med = [statistics.median(r[i] for r in rows) for i in range(6)]
        print(f"median, {med[0]:.5f}, {med[1]:.5f}, {med[2]:.3f}, {med[3]:.2f}, {med[4]:.2f}, {med[5]:.3f}")


if __name__ == "__main__":
    main()
