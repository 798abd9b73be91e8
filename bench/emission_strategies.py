#!/usr/bin/python3
"""Photon emission strategies of the caustics solver at equal time, without a reference: every strategy is
unbiased, so the relMSE between two independent renders is twice a render's variance. For each scene,
renders seeds 1..S of every strategy (alternating their order from seed to seed), and prints per strategy
the median over the S seed pairs (s, s + 1 mod S) of that relMSE, for the beauty and for the `caustics`
element (both scaled by the pair's mean beauty), the iterations each render reached, and the share of
traced photon paths a lookup used.

With --bound, also renders nimbus.pt for the same time per seed and prints what no photon strategy can
beat: photons carry only the `caustics` element's paths, the rest of the image (beauty - caustics) is
path traced by the same camera-path layer as nimbus.pt's, so its variance falls as 1/iterations and an
image whose caustics had no error, rendered as fast as nimbus.pt, would still have the relMSE of that
part scaled by (solver iterations / nimbus.pt iterations). Its ratio to a strategy's beauty relMSE is
the largest gain any emission strategy could give at equal time.

    bench/emission_strategies.py scenes/caustics/stadium.yaml scenes/caustics/envmap.yaml \
        --strategies uniform,adaptive-map,guided --time 8 [--seeds 3] [--bound]

Not part of CI (renders for minutes)."""
import argparse
import os
import statistics
import tempfile

from error_vs_time import relmse
from nimbus_tools import exr_metadata, read_rgb, run


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--strategies", default="uniform,adaptive-map,guided",
                    help="values of the solver's photon_emission option")
    ap.add_argument("--time", type=float, default=8)
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--nimbus", default="build/bin/nimbus")
    ap.add_argument("--bound", action="store_true", help="also render nimbus.pt: the largest possible gain")
    a = ap.parse_args()
    strategies = a.strategies.split(",")
    with tempfile.TemporaryDirectory() as tmp:
        for scene in a.scenes:
            name = os.path.splitext(os.path.basename(scene))[0]
            sides = strategies + (["pt"] if a.bound else [])
            outs = {m: [] for m in sides}
            for seed in range(1, a.seeds + 1):
                for m in sides if seed % 2 else sides[::-1]:
                    out = os.path.join(tmp, f"{name}-{m}-{seed}.exr")
                    how = ["--integrator", "pt"] if m == "pt" else ["--photon_emission", m, "--elements", "caustics"]
                    run([a.nimbus, "render", scene, "-o", out, "--time", str(a.time), "--seed", str(seed),
                         "--threads", str(a.threads), "-q"] + how)
                    outs[m].append(out)
            pt_iterations = statistics.median(int(exr_metadata(o).get("nimbus:iterations", 0)) for o in outs["pt"]) \
                if a.bound else 0
            for m in strategies:
                beauty = [read_rgb(o) for o in outs[m]]
                caustics = [read_rgb(o, "caustics") for o in outs[m]]
                everything = beauty[0][..., 0] == beauty[0][..., 0]
                b, c, rest = [], [], []
                for i in range(a.seeds):
                    j = (i + 1) % a.seeds
                    scale = (beauty[i] + beauty[j]) / 2
                    b.append(relmse(beauty[i], beauty[j], everything, scale))
                    c.append(relmse(caustics[i], caustics[j], everything, scale))
                    rest.append(relmse(beauty[i] - caustics[i], beauty[j] - caustics[j], everything, scale))
                meta = [exr_metadata(o) for o in outs[m]]
                iterations = [int(md.get("nimbus:iterations", 0)) for md in meta]
                used = statistics.median(float(md.get("nimbus:stat:caustics_used_path_fraction", 0)) for md in meta)
                line = (f"{name:14s} {m:13s} beauty {statistics.median(b):.4g} caustics {statistics.median(c):.4g} "
                        f"iterations {iterations} used {used:.3f}")
                if a.bound:
                    floor = statistics.median(rest) * statistics.median(iterations) / pt_iterations
                    line += (f" | not caustics {statistics.median(rest):.4g}, nimbus.pt iterations {pt_iterations:g}: "
                             f"floor {floor:.4g}, largest gain {statistics.median(b) / floor:.2f}x")
                print(line, flush=True)


if __name__ == "__main__":
    main()
