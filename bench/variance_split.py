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
((a + b) / 2 - r)^2 - var / 2, so relMSE ~ variance + bias^2. Images are read by nimbus_tools.read_rgb;
--crop limits every figure to the pixels [X0, X1) x [Y0, Y1) (a
caustic's region), and --covered-only (with REF) to the pixels a light-traced reference covers, as
bench/error_vs_time.py's option of that name does; --excluded MASK.exr leaves out a mask render's pixels
as error_vs_time.py's --exclude-render does. Not part of CI.
"""
import argparse

import numpy as np

import nimbus_tools
from error_vs_time import excluded_pixels, region_mask


PIXELS = None  # boolean rows x columns mask of the pixels compared, or None: the whole image


def read_rgb(path, layer):
    """The element's R, G, B at the PIXELS compared, shape (pixels, 3)."""
    rgb = nimbus_tools.read_rgb(path, layer)
    return rgb.reshape(-1, 3) if PIXELS is None else rgb[PIXELS]


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
    ap.add_argument("--covered-only", action="store_true", help="only the pixels the reference covers")
    ap.add_argument("--excluded", metavar="MASK.exr",
                    help="leave out the pixels this image shows non-zero, and those within 2 of them "
                         "(error_vs_time.py --exclude-render keeps its mask render as SCENE-excluded.exr)")
    args = ap.parse_args()
    if args.covered_only and not args.reference:
        ap.error("--covered-only needs --reference")
    crop = tuple(int(v) for v in args.crop.split(",")) if args.crop else None
    if crop or args.covered_only or args.excluded:
        global PIXELS
        frame = nimbus_tools.read_rgb(args.reference or args.a, "beauty")
        excluded = excluded_pixels(args.excluded, frame.shape[:2], args.a) if args.excluded else None
        PIXELS = region_mask(frame, args.covered_only, crop, excluded=excluded)
    a, b = read_rgb(args.a, "beauty"), read_rgb(args.b, "beauty")
    try:
        ca, cb = read_rgb(args.a, "caustics"), read_rgb(args.b, "caustics")
    except (KeyError, StopIteration):  # no caustics element (nimbus.pt): beauty only
        ca = cb = None
    ref = read_rgb(args.reference, "beauty") if args.reference else (a + b) / 2
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
