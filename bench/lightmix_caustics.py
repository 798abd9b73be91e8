#!/usr/bin/python3
"""Every LightMix group's caustic on scenes/caustics/many-lights.yaml against an independent reference, and
the solver's photon light selection (adaptive, power) at equal time.

The reference of group g is a `nimbus.lt` render of the scene with group g's lamps alone (no sun, no sky,
the other lamps removed): light transport is linear, so it equals the group's LightMix layer, and the
light tracer, which emits only from those lamps, converges on the caustics of weak groups as well as
strong ones. Each group has two lamps beside glass balls; its caustic region is the pixels of the ground in
those balls' shadows from their lamps (within 1.6 m; there the caustic is most of the light) whose
reference luminance exceeds twice the median of those shadows.
The solver renders the whole scene with `--elements lightmix`; per group and selection the script prints
the region mean of the group's layer over the reference's (median over seeds, with the spread of the
seeds), and the region's relMSE against the reference.

    bench/lightmix_caustics.py [--time 30] [--reference-time 60] [--seeds 3]

Not part of CI (renders for about twenty minutes)."""
import argparse
import os
import re
import statistics
import tempfile

import numpy as np
import yaml

from nimbus_tools import read_rgb, run

SCENE = "scenes/caustics/many-lights.yaml"
LAMPS = "scenes/caustics/assets/many_lights.yaml"
LUMINANCE = np.array([0.2126, 0.7152, 0.0722])


def group_scene(tmp, group):
    """The scene with group's lamps alone (the include's other lights, the sun and the sky removed)."""
    lines = [l for l in open(LAMPS).read().splitlines()
             if not (m := re.search(r"group: (\w+)", l)) or m.group(1) == group]
    lamps = os.path.join(tmp, f"lamps-{group}.yaml")
    with open(lamps, "w") as f:
        f.write("\n".join(lines) + "\n")
    scene = yaml.safe_load(open(SCENE))
    scene["include"] = lamps
    scene.pop("lights", None)
    scene.pop("environment", None)
    path = os.path.join(tmp, f"only-{group}.yaml")
    with open(path, "w") as f:
        yaml.safe_dump(scene, f)
    return path


def camera_rays(scene):
    """Unit directions of the rays through every pixel centre of the scene's pinhole camera (rows x columns
    x 3, host/world/camera.hpp's convention), and its position."""
    cam, (w, h) = scene["camera"], scene["render"]["resolution"]
    pos, at, up = (np.array(cam[k], float) for k in ("position", "look_at", "up"))
    fwd = (at - pos) / np.linalg.norm(at - pos)
    right = np.cross(fwd, up)
    right /= np.linalg.norm(right)
    upv = np.cross(right, fwd)
    t = np.tan(np.radians(cam["fov"]) / 2)
    sx = (2 * (np.arange(w) + 0.5) / w - 1) * t
    sy = (1 - 2 * (np.arange(h) + 0.5) / h) * t * h / w
    d = fwd + sx[None, :, None] * right + sy[:, None, None] * upv
    return d / np.linalg.norm(d, axis=-1, keepdims=True), pos


def caustic_windows(scene):
    """Per group, the pixels that see the ground within 1.6 m of one of its two glass balls and see no
    ball (the light tracer cannot render glass seen directly). The twenty lamps beside the balls come
    first in the include, in the balls' order."""
    inc = yaml.safe_load(open(LAMPS))
    balls = [(np.array(o["center"], float), o["radius"]) for o in inc["objects"] if o.get("material") == "glass"]
    lamps = inc["lights"][:len(balls)]
    d, pos = camera_rays(scene)
    t = -pos[2] / np.where(d[..., 2] < 0, d[..., 2], -1e-30)  # to the ground, z = 0
    ground = pos + t[..., None] * d
    sees_ball = np.zeros(d.shape[:2], bool)
    for c, r in balls:
        oc = pos - c
        b = d @ oc
        sees_ball |= (b * b - (oc @ oc - r * r) > 0) & (b < 0)
    windows = {}
    for (c, r), lamp in zip(balls, lamps):
        # In the ball's shadow: the segment from the ground point to the lamp passes through the ball.
        to_lamp = np.array(lamp["position"], float) - ground
        to_lamp /= np.linalg.norm(to_lamp, axis=-1, keepdims=True)
        oc = ground - c
        b = np.einsum("ijk,ijk->ij", to_lamp, oc)
        shadow = (b * b - (np.einsum("ijk,ijk->ij", oc, oc) - r * r) > 0) & (b < 0)
        near = (d[..., 2] < 0) & (np.hypot(ground[..., 0] - c[0], ground[..., 1] - c[1]) <= 1.6)
        window = near & shadow & ~sees_ball
        windows[lamp["group"]] = windows.get(lamp["group"], np.zeros_like(window)) | window
    return windows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--time", type=float, default=30, help="seconds per solver render")
    ap.add_argument("--reference-time", type=float, default=60, help="seconds per group reference")
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--nimbus", default="build/bin/nimbus")
    a = ap.parse_args()
    scene = yaml.safe_load(open(SCENE))
    windows = caustic_windows(scene)
    with tempfile.TemporaryDirectory() as tmp:
        refs = {}
        for g in sorted(windows):
            out = os.path.join(tmp, f"ref-{g}.exr")
            run([a.nimbus, "render", group_scene(tmp, g), "-o", out, "--integrator", "lt",
                 "--time", str(a.reference_time), "--seed", "1000", "-q"])
            refs[g] = read_rgb(out)
        layers = {"adaptive": [], "power": []}
        for seed in range(1, a.seeds + 1):
            for sel in ("adaptive", "power") if seed % 2 else ("power", "adaptive"):
                out = os.path.join(tmp, f"solver-{sel}-{seed}.exr")
                run([a.nimbus, "render", SCENE, "-o", out, "--time", str(a.time), "--seed", str(seed),
                     "--elements", "lightmix", "--photon_light_selection", sel, "-q"])
                layers[sel].append({g: read_rgb(out, f"lightmix.{g}") for g in windows})
    print(f"{'group':12s} {'pixels':>6s}  {'adaptive: mean ratio (seeds)':34s} rel. error "
          f"{'power: mean ratio (seeds)':34s} rel. error")
    for g in sorted(windows):
        lum = refs[g] @ LUMINANCE
        region = windows[g] & (lum > 2 * np.median(lum[windows[g]]))
        ref_mean = float(lum[region].mean())
        row = f"{g:12s} {int(region.sum()):6d}"
        for sel in ("adaptive", "power"):
            ratios = [float((l[g] @ LUMINANCE)[region].mean()) / ref_mean for l in layers[sel]]
            # The squared error over the region's squared reference mean: comparable across groups
            # whose light differs by six decades (relMSE's +0.01 would swamp the dim ones).
            errors = [float((((l[g] - refs[g]) @ LUMINANCE)[region] ** 2).mean()) / ref_mean**2
                      for l in layers[sel]]
            spread = ", ".join(f"{r:.3f}" for r in ratios)
            row += f"  {statistics.median(ratios):.3f} ({spread}){'':4s} {statistics.median(errors):.4g}"
        print(row, flush=True)


if __name__ == "__main__":
    main()
