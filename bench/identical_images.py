#!/usr/bin/python3
"""Checks that two builds of Nimbus render the same pixels: a refactoring must change no bit.

    bench/identical_images.py --old OLD_BUILD_DIR --new NEW_BUILD_DIR [--scenes DIR_OR_FILE ...]
        [--iterations N] [--threads N] [--seed S] [--out DIR] [--extra-args "..."]

A build directory holds bin/nimbus and lib/nimbus/plugins/ (a build tree or an install prefix); each
build runs with NIMBUS_PLUGIN_PATH set to its own plugin directory, so that neither picks up the other's
plugins (a warning is printed if `nimbus plugins` still lists a plugin from elsewhere).

Every scene under --scenes (default: the repository's scenes/, searched recursively for *.yaml) is
rendered by OLD, then by NEW - one render at a time, never concurrently - with the same --seed, --threads
and --iterations (which replaces the scene's stopping rules, so no time budget decides anything; the
resolution and everything else stay as the scene writes them), in up to three variants:

  as-written    the scene as it is;
  elements      with --elements listing every element the integrator registers (asked from each build:
                a render requesting an unknown element is refused with the list of available ones) and
                lightmix when the integrator supports it; both builds' lists are merged, so an element
                only one build has makes the other fail;
  caustics-off  with --caustics off, for scenes rendered by the caustics integrator.

A YAML file that another scene includes and that has no render/camera/environment section is an include
fragment: it is reported as SKIPPED, not rendered. A scene that fails the same way with both builds is
reported as FAILED and says so.

The two EXRs of each (scene, variant) are compared bit for bit: the same parts (subimages) with the same
names and data windows, the same channel names, types and sampling, and the same stored bits of every
sample (so +0 and -0, or two NaNs with different payloads, count as different). Header attributes are
not part of the check: timing metadata (nimbus:seconds, nimbus:stat:*_seconds, the DateTime/capDate
stamp) naturally differs between runs and is ignored; any other attribute that differs (nimbus:rays,
nimbus:version, ...) is mentioned as a note on an otherwise IDENTICAL line. PNG previews and
checkpoints are not compared (checkpoints are deleted as soon as each render ends).

Output: one line per (scene, variant) -
  IDENTICAL  scene  variant
  DIFFERENT  scene  variant  pixels and channels that differ, largest absolute difference
  FAILED     scene  variant  which build failed and the last line of its stderr
then `N passed, M failed` alone on a line. The exit status is 1 if anything differed or failed.

With --out the images are kept there; by default they go to a temporary directory, where identical pairs
are deleted as soon as they are compared and the directory is removed at the end if everything passed
(otherwise its path is printed).

Run with OLD and NEW both naming the same build, the script checks that rendering is deterministic at a
fixed seed and thread count. Self-check: --new-seed S (not listed among the options) renders the NEW
side with another seed; every variant must then come out DIFFERENT.

Default iterations: 8. Over the repository's scenes (10 scenes, 27 variants, 54 renders at 640x360 or
512x512, --threads 2) a run costs about 230 s of CPU at 8 iterations (390 s at 16: ~20 s per
iteration, ~75 s fixed for loading scenes and writing images), i.e. an estimated 2 to 3 minutes on 2 idle
cores; measured: 8.3 minutes on 2 cores shared with three compile jobs (load average 7.5). More iterations
check more of the caustics solver's photon schedule (its passes back off over 2^b iterations); fewer
fit a slower machine.
"""
import argparse
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

from exr_compare import compare_images
from nimbus_tools import plugin_dir, remove_render_outputs

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RENDER_TIMEOUT = 1800  # seconds; a render that takes longer is reported as FAILED
PROBE_ELEMENT = "nimbus_probe_no_such_element"
# The element lists of the built-in integrators (plugins/pathtracer/pathtracer.cpp,
# plugins/caustics/caustics.cpp), used only when a build does not say which elements it has.
PT_ELEMENTS = ["albedo", "depth", "direct", "emission", "indirect", "lightmix", "normal"]
STATIC_ELEMENTS = {"pt": PT_ELEMENTS, "caustics": PT_ELEMENTS + ["caustics", "caustics_merge"],
                   "lt": ["lightmix"]}


class Build:
    """One side of the comparison: its nimbus executable and the environment it runs in."""

    def __init__(self, label, path):
        self.label = label
        path = os.path.abspath(path)
        self.exe = path if os.path.isfile(path) else os.path.join(path, "bin", "nimbus")
        if not os.access(self.exe, os.X_OK):
            sys.exit(f"{label}: no nimbus executable at {self.exe}")
        self.root = os.path.dirname(os.path.dirname(self.exe))
        self.plugin_dir = plugin_dir(self.exe)
        self.env = dict(os.environ)
        self.env.pop("NIMBUS_PLUGIN_PATH", None)
        if os.path.isdir(self.plugin_dir):
            self.env["NIMBUS_PLUGIN_PATH"] = self.plugin_dir
        self.help = self.call(["render", "--help"]).stdout
        self.version = self.call(["--version"]).stdout.strip()

    def call(self, args, timeout=120):
        return subprocess.run([self.exe] + args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                              env=self.env, timeout=timeout)

    def describe(self):
        """The build, and a warning if it loads plugins from outside its own tree."""
        listing = self.call(["plugins"]).stdout
        loaded = [line.split()[-1] for line in listing.splitlines() if " loaded " in line]
        root = os.path.realpath(self.root) + os.sep
        foreign = [p for p in loaded if not os.path.realpath(p).startswith(root)]
        text = f"{self.label}: {self.exe} ({self.version}), {len(loaded)} plugins loaded"
        if foreign:
            text += f"\n  WARNING: {self.label} loads plugins from outside its build: {', '.join(foreign)}"
        return text


def last_line(text):
    lines = [line.strip() for line in text.splitlines() if line.strip()]
    return lines[-1] if lines else "(no output on stderr)"


# --- Scenes ------------------------------------------------------------------------------------------

def top_level_keys(text):
    return set(re.findall(r"^([A-Za-z_]\w*)\s*:", text, flags=re.M))


def included_files(path, text):
    """The files a scene's `include:` names (one file, a flow list or a block list), as absolute paths."""
    names = []
    for m in re.finditer(r"^include\s*:[ \t]*(.*)$", text, flags=re.M):
        value = m.group(1).split(" #")[0].strip()
        if value.startswith("["):
            names += [v.strip().strip("'\"") for v in value.strip("[]").split(",") if v.strip()]
        elif value:
            names.append(value.strip("'\""))
        else:
            for line in text[m.end():].splitlines()[1:]:
                item = re.match(r"^\s+-\s*(.+?)\s*(#.*)?$", line)
                if not item:
                    if line.strip() and not line.lstrip().startswith("#"):
                        break
                    continue
                names.append(item.group(1).strip("'\""))
    base = os.path.dirname(path)
    return {os.path.normpath(os.path.join(base, n)) for n in names}


def scene_integrator(text):
    """render.integrator as written (block or flow style), or None."""
    m = re.search(r"^render\s*:(.*(?:\n(?:[ \t]+.*|[ \t]*))*)", text, flags=re.M)
    if m:
        found = re.search(r"\bintegrator\s*:\s*([\w.\-]+)", m.group(1))
        if found:
            return found.group(1)
    return None


def find_scenes(args_scenes):
    """(path, label, fragment_of) for every *.yaml given or found; fragment_of names an including file
    when the file is an include fragment."""
    paths = []
    for item in args_scenes:
        if os.path.isdir(item):
            for dirpath, dirnames, filenames in os.walk(item):
                dirnames.sort()
                paths += [os.path.join(dirpath, f) for f in sorted(filenames) if f.endswith((".yaml", ".yml"))]
        elif os.path.isfile(item):
            paths.append(item)
        else:
            sys.exit(f"no such scene or directory: {item}")
    paths = [os.path.normpath(os.path.abspath(p)) for p in paths]
    paths = sorted(set(paths), key=paths.index)
    texts = {}
    for p in paths:
        with open(p, encoding="utf-8", errors="replace") as f:
            texts[p] = f.read()
    includers = {}
    for p in paths:
        for inc in included_files(p, texts[p]):
            includers.setdefault(inc, p)
    scenes = []
    for p in paths:
        fragment = None
        if p in includers and not top_level_keys(texts[p]) & {"render", "camera", "environment"}:
            fragment = label_of(includers[p])
        scenes.append((p, label_of(p), fragment, scene_integrator(texts[p])))
    return scenes


def label_of(path):
    rel = os.path.relpath(path, REPO)
    return path if rel.startswith("..") else rel


# --- Rendering ---------------------------------------------------------------------------------------

def render_args(args, seed):
    return ["--iterations", str(args.iterations), "--threads", str(args.threads), "--seed", str(seed), "-q"]


def probe_elements(build, scene, args, extra, tmp):
    """The elements `build` can render for `scene` (besides beauty; lightmix included when available),
    or None if the build does not say."""
    out = os.path.join(tmp, f"probe-{build.label}.exr")
    for request in ("lightmix," + PROBE_ELEMENT, PROBE_ELEMENT):
        try:
            proc = build.call(["render", scene, "-o", out] + render_args(args, args.seed) + extra
                              + ["--elements", request], timeout=RENDER_TIMEOUT)
        except subprocess.TimeoutExpired:
            return None
        m = re.search(r"unknown render element '" + PROBE_ELEMENT + r"' \(available: ([^)]*)\)", proc.stderr)
        if m:
            names = {n.strip() for n in m.group(1).split(",") if n.strip()}
            return sorted({"lightmix" if n.startswith("lightmix.") else n for n in names} - {"beauty"})
    return None


def render(build, scene, out, args, seed, extra, variant_args):
    """Renders; returns (error message or None, seconds)."""
    for stale in (out, out + ".ckpt"):
        if os.path.exists(stale):
            os.remove(stale)
    cmd = ["render", scene, "-o", out] + render_args(args, seed) + extra + variant_args
    start = time.monotonic()
    try:
        proc = build.call(cmd, timeout=RENDER_TIMEOUT)
    except subprocess.TimeoutExpired:
        return f"timed out after {RENDER_TIMEOUT} s", time.monotonic() - start
    seconds = time.monotonic() - start
    for leftover in (out + ".ckpt",):
        if os.path.exists(leftover):
            os.remove(leftover)
    if proc.returncode != 0:
        return f"exit {proc.returncode}: {last_line(proc.stderr)}", seconds
    if not os.path.isfile(out):
        return f"exit 0 but no image written ({last_line(proc.stderr)})", seconds
    return None, seconds


# --- Main --------------------------------------------------------------------------------------------

def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--old", required=True, help="build directory (or nimbus executable) before the change")
    ap.add_argument("--new", required=True, help="build directory (or nimbus executable) after the change")
    ap.add_argument("--scenes", nargs="+", default=[os.path.join(REPO, "scenes")],
                    help="scene files or directories searched recursively for *.yaml (default: scenes/)")
    ap.add_argument("--iterations", type=int, default=8, help="samples per pixel (default 8)")
    ap.add_argument("--threads", type=int, default=2, help="worker threads (default 2)")
    ap.add_argument("--seed", type=int, default=1, help="random seed (default 1)")
    ap.add_argument("--out", help="directory for the images (default: a temporary directory)")
    ap.add_argument("--extra-args", default="", help="more `nimbus render` arguments for every render")
    ap.add_argument("--new-seed", type=int, help=argparse.SUPPRESS)  # self-check: NEW renders another seed
    args = ap.parse_args()

    wall = time.monotonic()
    old, new = Build("OLD", args.old), Build("NEW", args.new)
    extra = shlex.split(args.extra_args)
    new_seed = args.seed if args.new_seed is None else args.new_seed
    temporary = args.out is None
    out_dir = tempfile.mkdtemp(prefix="identical-images-") if temporary else os.path.abspath(args.out)
    os.makedirs(out_dir, exist_ok=True)

    print(old.describe())
    print(new.describe())
    if os.path.realpath(old.exe) == os.path.realpath(new.exe):
        print("note: OLD and NEW are the same build: this run checks that renders repeat bit for bit")
    print(f"settings: --iterations {args.iterations} --threads {args.threads} --seed {args.seed}"
          + (f" (NEW: --seed {new_seed})" if new_seed != args.seed else "")
          + (f" {args.extra_args}" if extra else "") + f"; images in {out_dir}", flush=True)
    has_elements = any("--elements" in b.help for b in (old, new))
    has_caustics_switch = any("--caustics" in b.help for b in (old, new))
    if not has_elements:
        print("note: neither build has --elements: no elements variant")
    if not has_caustics_switch:
        print("note: neither build has --caustics: no caustics-off variant")
    extra_integrator = None
    for i, a in enumerate(extra):
        if a == "--integrator" and i + 1 < len(extra):
            extra_integrator = extra[i + 1]
        elif a.startswith("--integrator="):
            extra_integrator = a.split("=", 1)[1]

    passed = failed = 0
    for scene, label, fragment, integrator in find_scenes(args.scenes):
        if fragment:
            print(f"SKIPPED    {label}  include fragment (included by {fragment}; rendered as part of it)",
                  flush=True)
            continue
        integrator = extra_integrator or integrator or "pt"
        short = integrator[len("nimbus."):] if integrator.startswith("nimbus.") else integrator
        scene_dir = os.path.join(out_dir, re.sub(r"[^\w.\-]+", "_", label))
        os.makedirs(scene_dir, exist_ok=True)
        variants = [("as-written", [])]
        if has_elements:
            lists = [probe_elements(b, scene, args, extra, scene_dir) for b in (old, new)]
            if all(lst is None for lst in lists):
                elements = STATIC_ELEMENTS.get(short, ["lightmix"])
                source = " (builds did not list their elements: the built-in list of " + short + ")"
            else:
                elements = sorted(set().union(*[set(lst) for lst in lists if lst is not None]))
                source = ""
            if elements:
                variants.append((f"elements={','.join(elements)}{source}", ["--elements", ",".join(elements)]))
            if "caustics_merge" in elements:
                short = "caustics"
        if has_caustics_switch and short == "caustics":
            variants.append(("caustics-off", ["--caustics", "off"]))

        for name, variant_args in variants:
            tag = name.split("=")[0]
            paths = {b.label: os.path.join(scene_dir, f"{tag}-{b.label.lower()}.exr") for b in (old, new)}
            errors, seconds = {}, {}
            for build, seed in ((old, args.seed), (new, new_seed)):  # one render at a time
                errors[build.label], seconds[build.label] = render(build, scene, paths[build.label], args,
                                                                   seed, extra, variant_args)
            timing = f"[{seconds['OLD']:.1f} s + {seconds['NEW']:.1f} s]"
            if errors["OLD"] or errors["NEW"]:
                if errors["OLD"] == errors["NEW"]:
                    detail = (f"both builds fail the same way (not a renderable scene?): "
                              f"{errors['OLD']}")
                else:
                    detail = "; ".join(f"{k}: {v}" for k, v in errors.items() if v)
                status = "FAILED"
            else:
                try:
                    same, detail, notes = compare_images(paths["OLD"], paths["NEW"])
                except Exception as e:  # an unreadable image fails this variant, not the run
                    same, detail, notes = False, f"cannot compare: {e}", []
                status = "IDENTICAL" if same else "DIFFERENT"
                if notes:
                    detail = (detail + "; " if detail else "") + "note: " + "; ".join(notes)
                if same and temporary:
                    for p in paths.values():
                        remove_render_outputs(p)
            if status == "IDENTICAL":
                passed += 1
            else:
                failed += 1
            print(f"{status:<10} {label}  {name}  {timing}" + (f"  {detail}" if detail else ""), flush=True)

    if temporary and failed == 0:
        shutil.rmtree(out_dir, ignore_errors=True)
    elif failed:
        print(f"images kept in {out_dir}")
    print(f"wall time {time.monotonic() - wall:.0f} s")
    print(f"{passed} passed, {failed} failed")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
