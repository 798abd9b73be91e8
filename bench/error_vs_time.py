#!/usr/bin/python3
"""Error against time: renders scenes with several integrators at several time budgets (three seeds each),
compares every image with a reference, and writes a CSV and a log-log plot of relMSE against seconds.

    bench/error_vs_time.py scenes/caustics/sphere-area.yaml --integrators pt,caustics \
        --times 5,10,20,40,80 [--reference REF.exr] [--reference-integrator pt --reference-time 1200] \
        [--seeds 3] [--out docs/error-vs-time] [--nimbus build/bin/nimbus]

Without --reference, a reference is rendered first with --reference-integrator for --reference-time
seconds (and kept next to the CSV, with the command that made it). It prints, per integrator and time,
the median relMSE over seeds, efficiency = 1 / (relMSE x seconds), and the ratio of each integrator's
efficiency to the path tracer's measured in the same run. Uses Debian's python3 and matplotlib; not part of
CI (machines are shared and noisy: read the ratios, not the absolute figures).
"""
import argparse
import csv
import json
import os
import statistics
import subprocess
import time

from nimbus_tools import remove_render_outputs, run


def render(nimbus, scene, integrator, seconds, seed, out):
    cmd = [nimbus, "render", scene, "-o", out, "--integrator", integrator, "--time", str(seconds),
           "--seed", str(seed), "-q"]
    t0 = time.monotonic()
    run(cmd)
    return time.monotonic() - t0, cmd


def compare(nimbus, test, ref):
    return json.loads(run([nimbus, "compare", test, ref, "--json"]))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--integrators", default="pt,caustics")
    ap.add_argument("--times", default="5,10,20,40,80")
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--reference")
    ap.add_argument("--reference-integrator", default="pt")
    ap.add_argument("--reference-time", type=float, default=1200)
    ap.add_argument("--out", default="docs/error-vs-time")
    ap.add_argument("--nimbus", default="build/bin/nimbus")
    args = ap.parse_args()

    integrators = [s.strip() for s in args.integrators.split(",") if s.strip()]
    times = [float(t) for t in args.times.split(",")]
    os.makedirs(args.out, exist_ok=True)
    rows = []
    for scene in args.scenes:
        name = os.path.splitext(os.path.basename(scene))[0]
        ref = args.reference
        if not ref:
            ref = os.path.join(args.out, f"{name}-reference.exr")
            if not os.path.exists(ref):
                secs, cmd = render(args.nimbus, scene, args.reference_integrator, args.reference_time, 1000, ref)
                commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                                        text=True).stdout.strip() or "unknown"
                with open(ref + ".txt", "w") as f:
                    f.write(f"command: {' '.join(cmd)}\nwall seconds: {secs:.1f}\n"
                            f"commit: {commit}; used by error-vs-time.csv\n")
        for integ in integrators:
            for t in times:
                errs = []
                for s in range(args.seeds):
                    out = os.path.join(args.out, f"{name}-{integ}-{t:g}s-seed{s + 1}.exr")
                    render(args.nimbus, scene, integ, t, s + 1, out)
                    errs.append(compare(args.nimbus, out, ref)["relmse"])
                    remove_render_outputs(out)
                med = statistics.median(errs)
                rows.append({"scene": name, "integrator": integ, "seconds": t, "relmse_median": med,
                             "relmse_runs": " ".join(f"{e:.6g}" for e in errs),
                             "efficiency": 1.0 / (med * t) if med > 0 else float("inf")})

    csv_path = os.path.join(args.out, "error-vs-time.csv")
    with open(csv_path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    print(f"\nwrote {csv_path}\n")
    print(f"{'scene':<16} {'integrator':<12} {'seconds':>8} {'relMSE':>10} {'efficiency':>12} {'vs pt':>7}")
    for r in rows:
        base = [x for x in rows if x["scene"] == r["scene"] and x["integrator"] == "pt" and x["seconds"] == r["seconds"]]
        ratio = r["efficiency"] / base[0]["efficiency"] if base else float("nan")
        print(f"{r['scene']:<16} {r['integrator']:<12} {r['seconds']:>8g} {r['relmse_median']:>10.4g} "
              f"{r['efficiency']:>12.4g} {ratio:>7.2f}")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    for scene in sorted({r["scene"] for r in rows}):
        fig, ax = plt.subplots(figsize=(6, 4.5))
        for integ in integrators:
            pts = [(r["seconds"], r["relmse_median"]) for r in rows if r["scene"] == scene and r["integrator"] == integ]
            ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", label=integ)
        ax.set_xlabel("seconds")
        ax.set_ylabel("relMSE (median of seeds)")
        ax.set_title(scene)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
        png = os.path.join(args.out, f"{scene}-error-vs-time.png")
        fig.savefig(png, dpi=110, bbox_inches="tight")
        print(f"wrote {png}")


if __name__ == "__main__":
    main()
