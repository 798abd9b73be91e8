#!/usr/bin/python3
"""Error against time: renders scenes with several integrators at several time budgets (three seeds each),
compares every image with a reference, and writes a CSV and a log-log plot of relMSE against seconds.

    bench/error_vs_time.py scenes/caustics/sphere-area.yaml --integrators pt,caustics \
        --times 5,10,20,40,80 [--reference REF.exr] [--reference-integrator pt --reference-time 1200] \
        [--covered-only] [--crop X0,Y0,X1,Y1] [--brighter-than F] [--exclude-render MASK.yaml] \
        [--seeds 3] [--out docs/error-vs-time] \
        [--nimbus build/bin/nimbus]

Without --reference, the reference is rendered first, as two independent halves (seeds 1000 and 1001),
each with --reference-integrator for --reference-time seconds, and kept next to the CSV with the commands
that made them. The reference is their mean; half the squared difference of the halves estimates the
reference's own variance, which every relMSE against it contains, and the corrected relMSE (relMSE minus
that variance, an unbiased estimate of the error against the exact image) is reported beside it; the
efficiency ratios use the corrected figure. The integrators alternate at every
(time, seed), so machine load falls on both sides alike. relMSE is nimbus compare's: mean over the
channels of the pixels finite in both of (t - r)^2 / (r^2 + 0.01), over the whole image, the --crop
rectangle, or with --covered-only the pixels the reference covers (non-zero, with every pixel within 2
of them non-zero, so that silhouettes of glass and mirrors are left out): a light tracer (nimbus.lt)
renders every pixel whose camera ray first meets a non-specular surface and leaves those behind glass or
in mirrors black, so it is an independent reference for those pixels in scenes that path tracing cannot
converge (delta lights behind specular surfaces). It prints, per integrator and time, the median relMSE
over seeds, efficiency = 1 / (relMSE x seconds), and the ratio of each integrator's efficiency to the path
tracer's measured in the same run. --exclude-render MASK.yaml leaves out the pixels that a 64-iteration
nimbus.pt render of MASK.yaml shows non-zero, and those within 2 of them (bench/masks/ holds such scenes:
the pixels a moving glass object covers during the shutter, whose light no independent integrator
renders). An entry of --integrators may name another build as
LABEL=INTEGRATOR@NIMBUS (e.g. old=caustics@/path/to/old/build/bin/nimbus), to compare two versions. Uses Debian's python3 and matplotlib; not part of
CI (machines are shared and noisy: read the ratios, not the absolute figures).
"""
import argparse
import csv
import os
import statistics
import subprocess
import time

import numpy as np

from nimbus_tools import read_rgb, remove_render_outputs, run


def render(nimbus, scene, integrator, seconds, seed, out):
    cmd = [nimbus, "render", scene, "-o", out, "--integrator", integrator, "--time", str(seconds),
           "--seed", str(seed), "-q"]
    t0 = time.monotonic()
    run(cmd)
    return time.monotonic() - t0, cmd


def relmse(test, ref, mask, scale=None):
    """nimbus compare's relMSE over the pixels of `mask` finite in both images, each squared difference
    divided by scale^2 + 0.01 (scale: `ref` unless given)."""
    scale = ref if scale is None else scale
    keep = mask & np.isfinite(test).all(axis=-1) & np.isfinite(ref).all(axis=-1)
    return float(((test[keep] - ref[keep]) ** 2 / (scale[keep] ** 2 + 0.01)).mean())


def within_2(pixels, outside=False):
    """Whether every pixel within 2 (a 5 x 5 square) of each pixel is set in `pixels` (pixels outside the
    image: `outside`)."""
    out = np.ones(pixels.shape, dtype=bool)
    padded = np.pad(pixels, 2, constant_values=outside)
    h, w = pixels.shape
    for dy in range(5):
        for dx in range(5):
            out &= padded[dy:dy + h, dx:dx + w]
    return out


def excluded_pixels(mask_exr, shape, scene):
    """The pixels a mask render shows non-zero (rows x columns, True: left out); it must match the
    scene's resolution, `shape`."""
    excluded = (read_rgb(mask_exr) > 0).any(axis=-1)
    if excluded.shape != shape:
        raise SystemExit(f"{mask_exr}: {excluded.shape[1]}x{excluded.shape[0]} pixels, "
                         f"{scene} {shape[1]}x{shape[0]}")
    return excluded


def region_mask(ref, covered_only, crop, brighter_than=None, excluded=None):
    """The pixels compared: all, or those --covered-only and --crop keep, less `excluded` (rows x
    columns, True: left out, with the pixels within 2 of them); with brighter_than F, only those of them
    whose reference luminance exceeds F times the region's median (a caustic's own pixels)."""
    mask = np.ones(ref.shape[:2], dtype=bool)
    if covered_only:
        # A pixel counts when its whole neighbourhood is covered: a pixel on a glass or mirror silhouette
        # is partly light the light tracer cannot render, so its reference is too dark there.
        mask &= within_2((ref > 0).any(axis=-1))
    if excluded is not None:
        mask &= within_2(~excluded, outside=True)
    if crop:
        x0, y0, x1, y1 = crop
        box = np.zeros_like(mask)
        box[y0:y1, x0:x1] = True
        mask &= box
    if brighter_than:
        lum = ref @ np.array([0.2126, 0.7152, 0.0722])
        mask &= lum > brighter_than * np.median(lum[mask])
    return mask


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--integrators", default="pt,caustics")
    ap.add_argument("--times", default="5,10,20,40,80")
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--reference")
    ap.add_argument("--reference2", help="a second, independent reference render (another seed)")
    ap.add_argument("--reference-integrator", default="pt")
    ap.add_argument("--reference-time", type=float, default=1200)
    ap.add_argument("--covered-only", action="store_true", help="only the pixels the reference covers")
    ap.add_argument("--crop", help="X0,Y0,X1,Y1: only this pixel rectangle")
    ap.add_argument("--also-crop", action="append", default=[], metavar="NAME:X0,Y0,X1,Y1",
                    help="also report this rectangle, from the same renders (repeatable)")
    ap.add_argument("--brighter-than", type=float,
                    help="F: only the pixels whose reference luminance exceeds F x the region's median")
    ap.add_argument("--exclude-render", metavar="MASK.yaml",
                    help="leave out the pixels a nimbus.pt render of MASK.yaml shows non-zero")
    ap.add_argument("--out", default="docs/error-vs-time")
    ap.add_argument("--nimbus", default="build/bin/nimbus")
    args = ap.parse_args()

    integrators = [s.strip() for s in args.integrators.split(",") if s.strip()]
    # LABEL=INTEGRATOR@NIMBUS, or INTEGRATOR alone (labelled by itself, rendered by --nimbus).
    how = {}
    for entry in integrators:
        label, _, spec = entry.rpartition("=") if "=" in entry else (entry, "", entry)
        integ, _, binary = spec.partition("@")
        how[label or integ] = (integ, binary or args.nimbus)
    integrators = list(how)
    times = [float(t) for t in args.times.split(",")]
    crop = [int(v) for v in args.crop.split(",")] if args.crop else None
    os.makedirs(args.out, exist_ok=True)
    rows = []
    for scene in args.scenes:
        name = os.path.splitext(os.path.basename(scene))[0]
        refs = [r for r in (args.reference, args.reference2) if r]
        if not refs:
            for k, seed in enumerate((1000, 1001)):
                ref = os.path.join(args.out, f"{name}-reference{'' if k == 0 else '-2'}.exr")
                refs.append(ref)
                if os.path.exists(ref):
                    continue
                secs, cmd = render(args.nimbus, scene, args.reference_integrator, args.reference_time, seed, ref)
                commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                                        text=True).stdout.strip() or "unknown"
                with open(ref + ".txt", "w") as f:
                    f.write(f"command: {' '.join(cmd)}\nwall seconds: {secs:.1f}\n"
                            f"commit: {commit}; used by error-vs-time.csv\n")
        halves = [read_rgb(r) for r in refs]
        ref_image = sum(halves) / len(halves)
        excluded = None
        if args.exclude_render:
            mask_exr = os.path.join(args.out, f"{name}-excluded.exr")
            run([args.nimbus, "render", args.exclude_render, "-o", mask_exr, "--integrator", "pt",
                 "--iterations", "64", "--seed", "1", "-q"])
            excluded = excluded_pixels(mask_exr, ref_image.shape[:2], scene)
        regions = {"image": crop}
        for entry in args.also_crop:
            label, _, rect = entry.partition(":")
            regions[label] = [int(v) for v in rect.split(",")]
        masks, ref_vars = {}, {}
        for region, rect in regions.items():
            masks[region] = region_mask(ref_image, args.covered_only, rect, args.brighter_than, excluded)
            ref_vars[region] = 0.0
            if len(halves) == 2:
                ref_vars[region] = relmse(halves[0], halves[1], masks[region], scale=ref_image) / 4
        errs = {(region, integ, t): [] for region in regions for integ in integrators for t in times}
        for t in times:
            for s in range(args.seeds):
                for integ in integrators:
                    out = os.path.join(args.out, f"{name}-{integ}-{t:g}s-seed{s + 1}.exr")
                    render(how[integ][1], scene, how[integ][0], t, s + 1, out)
                    image = read_rgb(out)
                    for region in regions:
                        errs[(region, integ, t)].append(relmse(image, ref_image, masks[region]))
                    remove_render_outputs(out)
        for region, integ, t in errs:
            e = errs[(region, integ, t)]
            ref_var = ref_vars[region]
            med = statistics.median(e)
            corrected = statistics.median([x - ref_var for x in e])
            rows.append({"scene": name if region == "image" else f"{name}/{region}", "integrator": integ,
                         "seconds": t, "relmse_median": med,
                         "relmse_runs": " ".join(f"{x:.6g}" for x in e), "reference_variance": ref_var,
                         "relmse_corrected": corrected,
                         "efficiency": 1.0 / (corrected * t) if corrected > 0 else float("inf"),
                         "pixels_compared": float(masks[region].mean())})

    csv_path = os.path.join(args.out, "error-vs-time.csv")
    with open(csv_path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    print(f"\nwrote {csv_path}\n")
    print(f"{'scene':<16} {'integrator':<12} {'seconds':>8} {'relMSE':>10} {'ref var':>10} {'corrected':>10} "
          f"{'efficiency':>12} {'vs pt':>7}")
    for r in rows:
        base = [x for x in rows if x["scene"] == r["scene"] and x["integrator"] == "pt" and x["seconds"] == r["seconds"]]
        ratio = r["efficiency"] / base[0]["efficiency"] if base else float("nan")
        print(f"{r['scene']:<16} {r['integrator']:<12} {r['seconds']:>8g} {r['relmse_median']:>10.4g} "
              f"{r['reference_variance']:>10.4g} {r['relmse_corrected']:>10.4g} {r['efficiency']:>12.4g} {ratio:>7.2f}")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    for scene in sorted({r["scene"] for r in rows}):
        fig, ax = plt.subplots(figsize=(6, 4.5))
        for integ in integrators:
            pts = [(r["seconds"], r["relmse_median"], r["relmse_corrected"]) for r in rows
                   if r["scene"] == scene and r["integrator"] == integ]
            line, = ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", label=integ)
            if pts[0][1] != pts[0][2]:
                ax.loglog([p[0] for p in pts], [max(p[2], 1e-9) for p in pts], "s--", color=line.get_color(),
                          label=f"{integ}, reference variance removed")
        ax.set_xlabel("seconds")
        ax.set_ylabel("relMSE against the reference (median of seeds)")
        ax.set_title(scene)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
        png = os.path.join(args.out, f"{scene.replace('/', '-')}-error-vs-time.png")
        fig.savefig(png, dpi=110, bbox_inches="tight")
        print(f"wrote {png}")


if __name__ == "__main__":
    main()
