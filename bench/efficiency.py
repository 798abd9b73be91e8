#!/usr/bin/python3
"""Efficiency at equal iterations: variance of one render times its seconds (lower is better).

    bench/efficiency.py scenes/caustics/*.yaml [--integrator caustics] [--iterations 32] [--seeds 11,12]
                        [--env NAME=VALUE ...]

Per scene, renders the two seeds, estimates the variance of one render from their difference (as
bench/variance_split.py, relMSE units, no reference needed) and multiplies it by the mean of the two
renders' `nimbus:seconds`. For an unbiased estimator relMSE at equal time is about variance x seconds /
budget, so the ratio of this product between two configurations is their ratio of error at equal time
(bias aside: the merge radius, hence the kernel bias, does not depend on the photon count). `--env`
sets environment variables for the renders (to compare configurations of an experimental build).
Timing carries the machine's noise (±10-15 % here); the variance does not. Not part of CI.
"""
import argparse
import os
import statistics
import tempfile

from nimbus_tools import exr_metadata, run
from variance_split import read_rgb, relative_variance


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--integrator", default="caustics")
    ap.add_argument("--iterations", type=int, default=32)
    ap.add_argument("--seeds", default="11,12")
    ap.add_argument("--env", action="append", default=[])
    ap.add_argument("--nimbus", default="build/bin/nimbus")
    args = ap.parse_args()
    seeds = [int(s) for s in args.seeds.split(",")]
    assert len(seeds) == 2, "two seeds"
    env = dict(os.environ, **dict(kv.split("=", 1) for kv in args.env))
    with tempfile.TemporaryDirectory() as tmp:
        for scene in args.scenes:
            images, secs, photons = [], [], []
            for seed in seeds:
                out = os.path.join(tmp, f"{seed}.exr")
                run([args.nimbus, "render", scene, "-o", out, "--integrator", args.integrator, "--iterations",
                     str(args.iterations), "--seed", str(seed), "-q"], echo=False, env=env)
                meta = exr_metadata(out)
                secs.append(float(meta["nimbus:seconds"]))
                photons.append(float(meta.get("nimbus:stat:caustics_photons", 0)))
                images.append(read_rgb(out, "beauty", tmp))
            var = relative_variance(images[0], images[1], (images[0] + images[1]) / 2)
            sec = statistics.mean(secs)
            print(f"{os.path.basename(scene):20s} {' '.join(args.env) or '-':24s} variance {var:.4g}  seconds "
                  f"{sec:.2f}  variance x seconds {var * sec:.4g}  photons {statistics.mean(photons):.0f}",
                  flush=True)


if __name__ == "__main__":
    main()
