#!/usr/bin/python3
"""nimbus.pt against Embree's own tutorial path tracer, side by side on Embree's Cornell box.

    bench/embree_pathtracer_ab.py [--nimbus build/bin/nimbus] [--runs 5] [--size 512 512]
        [--threads 2] [--frames 10] [--max-depth 8] [--ecs /usr/share/doc/embree3/models/cornell_box.ecs]

Needs Debian's embree-tools (`apt-get install embree-tools`: /usr/bin/pathtracer and the model).

The scene Nimbus renders is written from the .ecs file the tutorial reads: the same OBJ (with its .mtl
materials), the same point light, camera position, target, up vector and field of view (Embree's is
vertical, Nimbus's horizontal: converted for the aspect ratio), and the same maximum path length
(Embree's --max-path-length counts closest-hit rays, as Nimbus's max_depth counts segments). Each run
renders the tutorial (`--benchmark 2 FRAMES`: two frames of warm-up, then FRAMES timed), then
`nimbus.pt` for FRAMES iterations, then `nimbus.caustics` with caustics off, alternating, so that the
machine's drift falls on all of them alike. Figures:

  samples/s  pixels x frames (or iterations) per second of rendering; Embree: its average frame rate
             times the pixel count (one sample per pixel per frame); Nimbus: the render loop's seconds
             (nimbus:seconds, no scene build and no file output);
  rays/s     Embree: its MRAYPS figure (closest-hit and shadow rays); Nimbus: nimbus:rays (the same
             two kinds) over the same seconds.

Per run the ratio Nimbus / Embree of both figures; printed: every run, then the medians.

Then the time to first pixel of each --first-pixel scene (default: scenes/default.yaml and the pool):
`nimbus render SCENE --iterations 1`, RUNS times, medians of the EXR's nimbus:load_seconds (reading the
scene and loading plugins), setup_seconds (world and plugins), first_iteration_seconds and
time_to_first_pixel, and of the whole command's wall time (which adds process start-up and writing the
image).

With --instructions, also the instructions each renderer executes per camera sample, counted by
callgrind (Debian's valgrind) and so exact and repeatable where times drift: the difference between
renders of 8 and 4 frames (iterations) at --instructions-size (default 128x128), one thread, so that
start-up, loading and writing cancel; split into Embree's share (its library) and the rest. A few
minutes; `--runs 0 --instructions` counts instructions alone.

With --perf, also where each renderer's time goes (Debian's linux-perf; no hardware counters needed):
one thread, `perf record` at 4 kHz of the tutorial (its warm-up frames included) and of `nimbus.pt`
(loading and writing included), and per renderer the CPU milliseconds in Embree's library per million
rays traced and outside it per frame. Equal instructions per ray in Embree (--instructions) with more
time per ray flags stalls in what feeds it (how store-forwarding stalls on the rays were found). Not
part of CI.
"""
import argparse
import math
import os
import re
import shlex
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

from nimbus_tools import callgrind_instructions, exr_metadata


def parse_ecs(path):
    """The tutorial's command-line options in an .ecs file, as a dict of option -> list of words."""
    words = shlex.split(open(path).read())
    opts, key = {}, None
    for w in words:
        if w.startswith("-") and not re.match(r"^-?[0-9.]+$", w):
            key = w.lstrip("-")
            opts.setdefault(key, [])
        elif key is not None:
            opts[key].append(w)
    return opts


def nimbus_scene(ecs, size, max_depth):
    """The YAML scene matching the .ecs file."""
    o = parse_ecs(ecs)
    obj = os.path.join(os.path.dirname(os.path.abspath(ecs)), o["i"][0])
    vp, vi, vu = o["vp"][:3], o["vi"][:3], o["vu"][:3]
    vfov = float(o["fov"][0])
    w, h = size
    hfov = math.degrees(2 * math.atan(math.tan(math.radians(vfov) / 2) * w / h))
    light = o["pointlight"]
    lines = [
        "# Written by bench/embree_pathtracer_ab.py from " + ecs,
        "render: { resolution: [%d, %d], max_depth: %d, integrator: pt, seed: 1 }" % (w, h, max_depth),
        "camera: { position: [%s], look_at: [%s], up: [%s], fov: %.6g }" % (
            ", ".join(vp), ", ".join(vi), ", ".join(vu), hfov),
        "objects:",
        "  - { shape: mesh, file: %s }" % obj,
        "lights:",
        "  - { type: point, position: [%s], intensity: [%s] }" % (", ".join(light[:3]), ", ".join(light[3:6])),
    ]
    return "\n".join(lines) + "\n"


def tutorial_command(pathtracer, ecs, size, threads, frames, max_depth, warmup=2):
    """The tutorial's benchmark command (`warmup` untimed frames, then `frames` timed); run it in ecs's folder."""
    return [pathtracer, "-c", ecs, "--size", str(size[0]), str(size[1]), "--benchmark", str(warmup), str(frames),
            "--threads", str(threads), "--max-path-length", str(max_depth)]


def tutorial_figures(out):
    """(frames/s, rays/s) from the tutorial's benchmark output."""
    fps = float(re.search(r"BENCHMARK_RENDER_AVG\s+([0-9.eE+-]+)", out).group(1))
    mrays = float(re.search(r"BENCHMARK_RENDER_MRAYPS_AVG\s+([0-9.eE+-]+)", out).group(1))
    return fps, mrays * 1e6


def embree_run(pathtracer, ecs, size, threads, frames, max_depth):
    """(samples/s, rays/s) of one tutorial benchmark run."""
    cmd = tutorial_command(pathtracer, ecs, size, threads, frames, max_depth)
    out = subprocess.run(cmd, capture_output=True, text=True, check=True, cwd=os.path.dirname(ecs)).stdout
    fps, rays = tutorial_figures(out)
    return fps * size[0] * size[1], rays


def nimbus_run(nimbus, scene, size, threads, frames, out, extra):
    """(samples/s, rays/s) of one Nimbus render of `frames` iterations."""
    cmd = [nimbus, "render", scene, "-o", out, "--iterations", str(frames), "--threads", str(threads), "-q"]
    subprocess.run(cmd + extra, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    meta = exr_metadata(out)
    seconds = float(meta["nimbus:seconds"])
    return size[0] * size[1] * frames / seconds, float(meta["nimbus:rays"]) / seconds


def first_pixel(nimbus, scene, threads, out):
    """(load, setup, first iteration, time to first pixel, wall) seconds of one 1-iteration render."""
    cmd = [nimbus, "render", scene, "-o", out, "--iterations", "1", "--threads", str(threads), "-q"]
    start = time.monotonic()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    wall = time.monotonic() - start
    m = exr_metadata(out)
    keys = ("load_seconds", "setup_seconds", "first_iteration_seconds", "time_to_first_pixel")
    return tuple(float(m["nimbus:" + k]) for k in keys) + (wall,)


def instructions_per_sample(a, tmp):
    """Rows (renderer, instructions per sample, of them in Embree) of the tutorial and nimbus.pt."""
    w, h = a.instructions_size
    scene = os.path.join(tmp, "embree_cornell_box_small.yaml")
    with open(scene, "w") as f:
        f.write(nimbus_scene(a.ecs, (w, h), a.max_depth))
    out = os.path.join(tmp, "instructions.exr")
    ecs = os.path.abspath(a.ecs)

    def tutorial(n):
        return tutorial_command(a.pathtracer, ecs, (w, h), 1, n, a.max_depth, warmup=0), os.path.dirname(ecs)

    def nimbus(n):
        return [a.nimbus, "render", scene, "-o", out, "--iterations", str(n), "--threads", "1", "-q"], None

    samples = w * h * 4  # the 4 frames between the two counts
    rows = []
    for name, command in (("embree tutorial pathtracer", tutorial), ("nimbus.pt", nimbus)):
        low, high = (callgrind_instructions(*command(n)) for n in (4, 8))
        rows.append((name, (high[0] - low[0]) / samples, (high[1] - low[1]) / samples))
    return rows


def perf_dso_milliseconds(cmd, cwd, tmp):
    """(milliseconds in libembree, milliseconds in all, the command's output) of one command, from `perf
    record` at 4 kHz."""
    data = os.path.join(tmp, "perf.data")
    out = subprocess.run(["perf", "record", "-q", "-F", "4000", "-o", data] + cmd, cwd=cwd, check=True,
                         capture_output=True, text=True).stdout
    report = subprocess.run(["perf", "report", "-i", data, "--stdio", "--sort", "dso", "-n"],
                            capture_output=True, text=True, check=True).stdout
    embree = total = 0
    for line in report.splitlines():
        m = re.match(r"\s*[0-9.]+%\s+([0-9]+)\s+(\S+)", line)
        if m:
            total += int(m.group(1))
            embree += int(m.group(1)) if "libembree" in m.group(2) else 0
    return embree / 4.0, total / 4.0, out


def time_split(a, tmp, scene):
    """Rows (renderer, Embree ms per million rays, other ms per frame) from one-thread perf profiles."""
    ecs = os.path.abspath(a.ecs)
    frames = a.frames
    cmd = tutorial_command(a.pathtracer, ecs, a.size, 1, frames, a.max_depth)
    e_ms, all_ms, out = perf_dso_milliseconds(cmd, os.path.dirname(ecs), tmp)
    fps, rays_per_s = tutorial_figures(out)
    tutorial_rays = rays_per_s / fps * (frames + 2)  # rays per frame, warm-up frames included
    rows = [("embree tutorial pathtracer", e_ms / (tutorial_rays / 1e6), (all_ms - e_ms) / (frames + 2))]
    image = os.path.join(tmp, "perf.exr")
    cmd = [a.nimbus, "render", scene, "-o", image, "--iterations", str(frames), "--threads", "1", "-q"]
    e_ms, all_ms, _ = perf_dso_milliseconds(cmd, None, tmp)
    rays = float(exr_metadata(image)["nimbus:rays"])
    rows.append(("nimbus.pt", e_ms / (rays / 1e6), (all_ms - e_ms) / frames))
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--nimbus", default="build/bin/nimbus")
    ap.add_argument("--pathtracer", default="/usr/bin/pathtracer")
    ap.add_argument("--ecs", default="/usr/share/doc/embree3/models/cornell_box.ecs")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--size", type=int, nargs=2, default=[512, 512])
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--frames", type=int, default=10)
    ap.add_argument("--max-depth", type=int, default=8)
    ap.add_argument("--first-pixel", nargs="*", default=["scenes/default.yaml", "scenes/caustics/pool.yaml"],
                    help="scenes whose time to first pixel is measured")
    ap.add_argument("--instructions", action="store_true",
                    help="also count instructions per camera sample with callgrind")
    ap.add_argument("--instructions-size", type=int, nargs=2, default=[128, 128])
    ap.add_argument("--perf", action="store_true",
                    help="also split each renderer's time into Embree per ray and the rest per frame (linux-perf)")
    a = ap.parse_args()
    for tool in (a.pathtracer, a.ecs):
        if not os.path.exists(tool):
            sys.exit("%s is missing: apt-get install embree-tools" % tool)
    if a.instructions and not shutil.which("valgrind"):
        sys.exit("--instructions needs valgrind: apt-get install valgrind")
    if a.perf and not shutil.which("perf"):
        sys.exit("--perf needs perf: apt-get install linux-perf")

    tmp_dir = tempfile.TemporaryDirectory(prefix="nimbus_embree_ab_")  # removed at exit
    tmp = tmp_dir.name
    scene = os.path.join(tmp, "embree_cornell_box.yaml")
    with open(scene, "w") as f:
        f.write(nimbus_scene(a.ecs, a.size, a.max_depth))
    out = os.path.join(tmp, "out.exr")
    sides = [("nimbus.pt", []), ("nimbus.caustics, caustics off", ["--integrator", "caustics", "--caustics", "off"])]
    rows = {name: [] for name, _ in sides}
    embree = []
    print("scene: %s (from %s), %dx%d, %d threads, max path length %d, %d frames per run" % (
        scene, a.ecs, a.size[0], a.size[1], a.threads, a.max_depth, a.frames))
    for run in range(a.runs):
        e = embree_run(a.pathtracer, a.ecs, a.size, a.threads, a.frames, a.max_depth)
        embree.append(e)
        line = "run %d  embree %.3f M samples/s %.2f M rays/s" % (run + 1, e[0] / 1e6, e[1] / 1e6)
        for name, extra in sides:
            n = nimbus_run(a.nimbus, scene, a.size, a.threads, a.frames, out, extra)
            rows[name].append((n[0], n[1], n[0] / e[0], n[1] / e[1]))
            line += " | %s %.3f M samples/s %.2f M rays/s (%.2fx, %.2fx)" % (
                name, n[0] / 1e6, n[1] / 1e6, n[0] / e[0], n[1] / e[1])
        print(line, flush=True)

    med = statistics.median
    if a.runs:  # --runs 0: instructions only
        print("\nmedians of %d runs" % a.runs)
        print("%-32s %14s %12s %16s %14s" % ("", "M samples/s", "M rays/s", "samples ratio", "rays ratio"))
        print("%-32s %14.3f %12.2f %16s %14s" % ("embree tutorial pathtracer", med(e[0] for e in embree) / 1e6,
                                                 med(e[1] for e in embree) / 1e6, "", ""))
        for name, r in rows.items():
            print("%-32s %14.3f %12.2f %15.2fx %13.2fx" % (name, med(x[0] for x in r) / 1e6, med(x[1] for x in r) / 1e6,
                                                         med(x[2] for x in r), med(x[3] for x in r)))

    first_pixel_scenes = a.first_pixel if a.runs else []
    if first_pixel_scenes:
        print("\ntime to first pixel, seconds (medians of %d renders of 1 iteration, %d threads)" % (a.runs, a.threads))
        print("%-32s %8s %8s %16s %14s %10s" % ("scene", "load", "setup", "first iteration", "first pixel",
                                                 "command"))
    for scene in first_pixel_scenes:
        runs = [first_pixel(a.nimbus, scene, a.threads, out) for _ in range(a.runs)]
        print("%-32s %8.3f %8.3f %16.3f %14.3f %10.3f" % ((scene,) + tuple(med(r[k] for r in runs) for k in range(5))))

    if a.perf:
        print("\nwhere the time goes (perf record, one thread, %d frames at %dx%d; loading and writing included)"
              % (a.frames, a.size[0], a.size[1]))
        print("%-32s %24s %28s" % ("", "Embree ms per M rays", "outside Embree, ms per frame"))
        for name, per_ray, per_frame in time_split(a, tmp, scene):
            print("%-32s %24.1f %28.1f" % (name, per_ray, per_frame))

    if a.instructions:
        rows = instructions_per_sample(a, tmp)
        print("\ninstructions per camera sample (callgrind, %dx%d, 8 frames minus 4, one thread)" % tuple(
            a.instructions_size))
        print("%-32s %10s %10s %14s %18s" % ("", "all", "Embree", "outside Embree", "ratio to tutorial"))
        for name, total, embree in rows:
            print("%-32s %10.0f %10.0f %14.0f %17.2fx" % (name, total, embree, total - embree, total / rows[0][1]))


if __name__ == "__main__":
    main()
