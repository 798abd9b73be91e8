#!/usr/bin/python3
"""Start-up and time to first pixel of two builds, measured side by side.

    bench/startup_ab.py --a OLD/build/bin/nimbus --b build/bin/nimbus [--runs 7] \
        [--scenes scenes/default.yaml scenes/caustics/pool.yaml]

Each run times, with build A then build B (B first in every other run), the commands that touch no
image (`--version`, `plugins`, a render of a scene with a syntax error) and a one-iteration render of
each scene, whose EXR gives load, setup, first-iteration and time-to-first-pixel seconds. The script
prints medians over runs of each build's figures and of the per-run ratio B / A of the commands' wall
times. Not part of CI.
"""
import argparse
import os
import statistics
import subprocess
import tempfile
import time

from embree_pathtracer_ab import first_pixel

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
QUICK = [("--version", ["--version"]), ("plugins", ["plugins"]),
         ("scene with a syntax error", ["render", os.path.join(ROOT, "tests/e2e/scenes/syntax_error.yaml")])]


def wall(nimbus, args, cwd):
    """Seconds of one command (its exit code is not checked: the syntax error exits 1)."""
    start = time.monotonic()
    subprocess.run([nimbus] + args, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.monotonic() - start


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--a", required=True, help="the nimbus executable of build A")
    ap.add_argument("--b", required=True, help="the nimbus executable of build B")
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--scenes", nargs="*", default=["scenes/default.yaml", "scenes/caustics/pool.yaml"])
    a = ap.parse_args()
    tmp_dir = tempfile.TemporaryDirectory(prefix="nimbus_startup_ab_")  # removed at exit
    tmp = tmp_dir.name
    builds = {"A": os.path.abspath(a.a), "B": os.path.abspath(a.b)}
    quick = {(name, side): [] for name, _ in QUICK for side in builds}
    renders = {(scene, side): [] for scene in a.scenes for side in builds}
    for run in range(a.runs):
        for side in ("A", "B") if run % 2 == 0 else ("B", "A"):
            for name, args in QUICK:
                quick[(name, side)].append(wall(builds[side], args, tmp))
            for scene in a.scenes:
                renders[(scene, side)].append(first_pixel(builds[side], scene, a.threads, os.path.join(tmp, "out.exr")))

    med = statistics.median
    print("A: %s\nB: %s\nmedians of %d alternating runs, seconds\n" % (builds["A"], builds["B"], a.runs))
    print("%-32s %8s %8s %8s" % ("command", "A", "B", "B / A"))
    for name, _ in QUICK:
        ta, tb = quick[(name, "A")], quick[(name, "B")]
        print("%-32s %8.3f %8.3f %8.3f" % (name, med(ta), med(tb), med(y / x for x, y in zip(ta, tb))))
    print("\none-iteration renders (%d threads): load, setup, first iteration, time to first pixel, command" %
          a.threads)
    for scene in a.scenes:
        for side in builds:
            runs = renders[(scene, side)]
            print("%-32s %s %8.3f %8.3f %8.3f %8.3f %8.3f" % ((scene, side) + tuple(med(r[k] for r in runs)
                                                                                 for k in range(5))))
        ratio = med(b[4] / x[4] for x, b in zip(renders[(scene, "A")], renders[(scene, "B")]))
        print("%-32s   command B / A %.3f" % ("", ratio))


if __name__ == "__main__":
    main()
