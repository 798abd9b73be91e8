#!/usr/bin/python3
"""Per-iteration cost of nimbus.caustics over nimbus.pt at equal iterations, measured side by side.

    bench/overhead.py scenes/caustics/*.yaml [--iterations 64] [--runs 3] [--out docs/overhead-64.csv]

For each scene and run, renders the scene with pt and with caustics (alternating, same seed per run),
reads the render's own timing and the solver's statistics from the EXR metadata, and prints per scene the
median seconds of each, the overhead (caustics / pt - 1), photon paths per pass, photons stored, bytes per
photon and the share of time spent tracing photons. Not part of CI: timings need a quiet machine.
"""
import argparse
import csv
import os
import statistics
import tempfile

from nimbus_tools import exr_metadata, run


def render(nimbus, scene, integrator, iterations, seed, out):
    run([nimbus, "render", scene, "-o", out, "--integrator", integrator, "--iterations", str(iterations),
         "--seed", str(seed), "-q"], echo=False)
    return exr_metadata(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--iterations", type=int, default=64)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--out", default="docs/overhead-64.csv")
    ap.add_argument("--nimbus", default="build/bin/nimbus")
    args = ap.parse_args()

    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "img.exr")
        for scene in args.scenes:
            secs = {"pt": [], "caustics": []}
            stats = []
            for i in range(args.runs):
                for integrator in ("pt", "caustics"):
                    meta = render(args.nimbus, scene, integrator, args.iterations, i + 1, out)
                    secs[integrator].append(float(meta["nimbus:seconds"]))
                    if integrator == "caustics":
                        stats.append(meta)
            pt, ca = statistics.median(secs["pt"]), statistics.median(secs["caustics"])
            last = stats[-1]
            stat = lambda k: float(last.get("nimbus:stat:" + k, 0))
            passes = stat("caustics_photon_passes")
            row = {
                "scene": os.path.basename(scene),
                "iterations": args.iterations,
                "pt_seconds_median": round(pt, 3),
                "caustics_seconds_median": round(ca, 3),
                "overhead_percent": round(100 * (ca / pt - 1), 1),
                "photon_passes": int(passes),
                "photon_paths": int(stat("caustics_photon_paths")),
                "photon_paths_per_pass": int(stat("caustics_photon_paths") / passes) if passes else 0,
                "photons_stored": int(stat("caustics_photons")),
                "bytes_per_photon": round(stat("caustics_bytes_per_photon"), 1),
                "photon_seconds": round(stat("caustics_photon_seconds"), 3),
                "pt_runs": " ".join(f"{s:.3f}" for s in secs["pt"]),
                "caustics_runs": " ".join(f"{s:.3f}" for s in secs["caustics"]),
            }
            rows.append(row)
            print(f"{row['scene']:20s} pt {pt:7.3f}s caustics {ca:7.3f}s overhead {row['overhead_percent']:6.1f}% "
                  f"photon paths {row['photon_paths']} in {row['photon_passes']} passes, "
                  f"{row['photons_stored']} photons, {row['bytes_per_photon']} B/photon", flush=True)
    os.makedirs(os.path.dirname(args.out) or ".", exist_ok=True)
    with open(args.out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
