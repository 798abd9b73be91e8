#!/usr/bin/python3
"""How much of a render's error is variance, and which part of the light carries it.

    bench/variance_split.py A.exr B.exr [--reference REF.exr] [--crop X0,Y0,X1,Y1]

A and B: the same scene, integrator and budget, two seeds, rendered with the `caustics` element
(without it, as from nimbus.pt, beauty only). Per
pixel and channel the variance of one render is estimated without a reference as (a - b)^2 / 2, and
expressed in relMSE units as `nimbus compare` does: mean of (a - b)^2 / 2 / (r^2 + 0.01), r from REF (or
(a + b) / 2 without one). Printed for beauty, for the regular light (beauty - caustics: paths without an
eligible merge technique, which nimbus.caustics renders exactly as nimbus.pt does) and for the
caustics element. With REF, also each render's relMSE and the mean of their bias estimate
((a + b) / 2 - r)^2 - var / 2, so relMSE ~ variance + bias^2. Images are read through oiiotool
(Debian's openimageio-tools) as FITS; --crop limits every figure to the pixels [X0, X1) x [Y0, Y1) (a
caustic's region). Not part of CI.
"""
import argparse
import os
import subprocess
import tempfile

import numpy as np


CROP = None  # (x0, y0, x1, y1) or None: the whole image


def read_channel(path, channel, tmp):
    """One channel as a float array, through a single-plane float FITS file (no PFM writer in Debian 12's
    OIIO): 2880-byte header blocks of 80-character cards up to END, then big-endian float32 data."""
    out = os.path.join(tmp, "channel.fits")
    cut = []
    if CROP:
        x0, y0, x1, y1 = CROP
        cut = ["--cut", f"{x1 - x0}x{y1 - y0}+{x0}+{y0}"]
    subprocess.run(["oiiotool", path, "--ch", channel] + cut + ["-d", "float", "-o", out], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(out, "rb") as f:
        raw = f.read()
    pos, dims = 0, {}
    while True:
        block = raw[pos:pos + 2880]
        pos += 2880
        cards = [block[i:i + 80].decode("ascii") for i in range(0, 2880, 80)]
        for c in cards:
            if c.startswith("NAXIS1") or c.startswith("NAXIS2"):
                dims[c[:6]] = int(c.split("=")[1].split("/")[0])
        if any(c.startswith("END") for c in cards):
            break
    n = dims["NAXIS1"] * dims["NAXIS2"]
    return np.frombuffer(raw, dtype=">f4", count=n, offset=pos).astype(np.float64)


def read_rgb(path, layer, tmp):
    """Channels layer.R, layer.G, layer.B (R, G, B for beauty), shape (pixels, 3)."""
    prefix = "" if layer == "beauty" else layer + "."
    return np.stack([read_channel(path, prefix + c, tmp) for c in "RGB"], axis=-1)


def relative_variance(x, y, ref):
    """Variance of one render from two renders x, y of different seeds, in relMSE units against ref."""
    ok = np.isfinite(x).all(-1) & np.isfinite(y).all(-1) & np.isfinite(ref).all(-1)
    return float(np.mean((x[ok] - y[ok]) ** 2 / 2 / (ref[ok] ** 2 + 0.01)))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--reference")
    ap.add_argument("--crop", help="X0,Y0,X1,Y1: pixels [X0, X1) x [Y0, Y1) only")
    args = ap.parse_args()
    global CROP
    CROP = tuple(int(v) for v in args.crop.split(",")) if args.crop else None
    with tempfile.TemporaryDirectory() as tmp:
        a, b = read_rgb(args.a, "beauty", tmp), read_rgb(args.b, "beauty", tmp)
        try:
            ca, cb = read_rgb(args.a, "caustics", tmp), read_rgb(args.b, "caustics", tmp)
        except subprocess.CalledProcessError:  # no caustics element (nimbus.pt): beauty only
            ca = cb = None
        ref = read_rgb(args.reference, "beauty", tmp) if args.reference else (a + b) / 2
    ok = np.isfinite(a).all(-1) & np.isfinite(b).all(-1) & np.isfinite(ref).all(-1)
    den = ref[ok] ** 2 + 0.01

    def rel_var(x, y):
        return relative_variance(x, y, ref)

    parts = {"beauty": (a, b)}
    if ca is not None:
        parts.update({"regular": (a - ca, b - cb), "caustics": (ca, cb)})
    for name, (x, y) in parts.items():
        print(f"variance of one render, {name:9s}: {rel_var(x, y):.4g}")
    if args.reference:
        for name, x in (("A", a), ("B", b)):
            print(f"relMSE {name}: {float(np.mean((x[ok] - ref[ok]) ** 2 / den)):.4g}")
        mean = (a + b) / 2
        bias2 = float(np.mean(((mean[ok] - ref[ok]) ** 2 - (a[ok] - b[ok]) ** 2 / 4) / den))
        print(f"bias^2 (against the reference, its own error included): {bias2:.4g}")


if __name__ == "__main__":
    main()
