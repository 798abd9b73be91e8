#!/usr/bin/python3
"""A render region against the same pixels of a full-frame render, at equal iterations (paper 3.3: a small
region must still get the photon batches it needs). For each seed, renders the scene whole and with
--region, compares the region's pixels of both with a reference, and prints the medians over seeds and
their ratio (region / full; 1 means the region converges like the full frame).

    bench/render_region.py scenes/caustics/pool.yaml --region 224,96,416,224 --iterations 32 \
        --reference docs/error-vs-time/pool/pool-reference.exr [--seeds 3] [--flags "--photon_emission uniform"]

Not part of CI (renders for minutes)."""
import argparse
import os
import statistics
import tempfile

import numpy as np

from error_vs_time import relmse
from nimbus_tools import read_rgb, run


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene")
    ap.add_argument("--region", required=True, help="x0,y0,x1,y1 in pixels")
    ap.add_argument("--iterations", type=int, default=32)
    ap.add_argument("--reference", required=True)
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--flags", default="", help="extra render flags for both sides")
    ap.add_argument("--nimbus", default="build/bin/nimbus")
    a = ap.parse_args()
    x0, y0, x1, y1 = (int(v) for v in a.region.split(","))
    ref = read_rgb(a.reference)
    mask = np.zeros(ref.shape[:2], dtype=bool)
    mask[y0:y1, x0:x1] = True
    errors = {"full": [], "region": []}
    with tempfile.TemporaryDirectory() as tmp:
        for seed in range(1, a.seeds + 1):
            for side in ("full", "region"):
                out = os.path.join(tmp, f"{side}-{seed}.exr")
                cmd = [a.nimbus, "render", a.scene, "-o", out, "--iterations", str(a.iterations), "--seed",
                       str(seed), "-q"] + a.flags.split()
                if side == "region":
                    cmd += ["--region", a.region]
                run(cmd)
                errors[side].append(relmse(read_rgb(out), ref, mask))
                print(f"seed {seed} {side}: relMSE {errors[side][-1]:.5g}", flush=True)
    full, region = statistics.median(errors["full"]), statistics.median(errors["region"])
    print(f"median relMSE over the region's {mask.sum()} pixels: full frame {full:.5g}, region {region:.5g}, "
          f"ratio {region / full:.3f}")


if __name__ == "__main__":
    main()
