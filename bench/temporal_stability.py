#!/usr/bin/python3
"""Temporal stability: renders a scene N times with different seeds (frames of a still animation) per
side at equal time, and reports the spatial autocorrelation of the frame-to-frame differences at pixel
lags 1, 2, 4 and 8 (mean over the N-1 consecutive pairs of the normalised correlation of each difference
image with itself shifted horizontally and vertically). Independent per-pixel noise gives ~0 at every lag;
structure that flickers from frame to frame (clumps, blotches) shows as correlation at lags up to its size.

    bench/temporal_stability.py scenes/caustics/pool.yaml --sides pt,caustics,guided=caustics@GUIDED \
        --time 5 --frames 10

A side is INTEGRATOR or LABEL=INTEGRATOR@NIMBUS (another binary or a wrapper adding flags). The sides
alternate frame by frame. Not part of CI."""
import argparse
import os
import tempfile

import numpy as np

from nimbus_tools import read_rgb, run

LAGS = (1, 2, 4, 8)


def autocorrelation(d, lag):
    """Normalised correlation of difference image d (luminance) with itself shifted by lag pixels,
    horizontally and vertically, averaged."""
    d = d - d.mean()
    var = (d * d).mean()
    if var <= 0:
        return 0.0
    h = (d[:, lag:] * d[:, :-lag]).mean() / var
    v = (d[lag:, :] * d[:-lag, :]).mean() / var
    return 0.5 * (h + v)


def luminance(rgb):
    return rgb @ np.array([0.2126, 0.7152, 0.0722])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene")
    ap.add_argument("--sides", default="pt,caustics")
    ap.add_argument("--time", type=float, default=5)
    ap.add_argument("--frames", type=int, default=10)
    ap.add_argument("--nimbus", default="build/bin/nimbus")
    a = ap.parse_args()
    sides = []
    for s in a.sides.split(","):
        label, _, rest = s.partition("=") if "=" in s else (s, "", s)
        integrator, _, binary = rest.partition("@")
        sides.append((label, integrator, binary or a.nimbus))
    frames = {label: [] for label, _, _ in sides}
    with tempfile.TemporaryDirectory() as tmp:
        for f in range(a.frames):
            for label, integrator, binary in sides:
                out = os.path.join(tmp, f"{label}-{f}.exr")
                run([binary, "render", a.scene, "-o", out, "--integrator", integrator, "--time", str(a.time),
                     "--seed", str(100 + f), "-q"])
                frames[label].append(luminance(read_rgb(out)))
    print(f"{'side':12s}" + "".join(f"   lag {lag:<3d}" for lag in LAGS) + "   rms diff / mean")
    for label, _, _ in sides:
        imgs = frames[label]
        diffs = [imgs[i + 1] - imgs[i] for i in range(len(imgs) - 1)]
        acs = [np.mean([autocorrelation(d, lag) for d in diffs]) for lag in LAGS]
        rms = np.sqrt(np.mean([(d * d).mean() for d in diffs])) / np.mean([i.mean() for i in imgs])
        print(f"{label:12s}" + "".join(f"   {c:8.4f}" for c in acs) + f"   {rms:.4f}")


if __name__ == "__main__":
    main()
