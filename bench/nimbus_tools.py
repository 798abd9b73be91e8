"""Helpers shared by the benchmark scripts in bench/: running a command, reading a render's metadata,
swapping builds of one plugin library."""
import os
import shutil
import subprocess
import sys
import tempfile


def run(cmd, echo=True, env=None):
    """Runs cmd (in env, or this process's environment); exits with its stderr if it fails; returns its
    stdout."""
    if echo:
        print("+", " ".join(cmd), flush=True)
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    if proc.returncode != 0:
        sys.exit(f"command failed ({proc.returncode}): {' '.join(cmd)}\n{proc.stderr}")
    return proc.stdout


def exr_metadata(path):
    """The nimbus:* attributes of an EXR header as strings (oiiotool, from Debian's openimageio-tools)."""
    meta = {}
    for line in run(["oiiotool", "--info", "-v", path], echo=False).splitlines():
        line = line.strip()
        if line.startswith("nimbus:"):
            key, _, value = line.partition(": ")
            meta[key] = value.strip().strip('"')
    return meta


def add_ab_arguments(ap, what):
    """The arguments of the side-by-side scripts: scenes, the two builds of `what`, iterations, runs."""
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--a", required=True, help=f"{what}, build A")
    ap.add_argument("--b", required=True, help=f"{what}, build B")
    ap.add_argument("--iterations", type=int, default=16)
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--nimbus", default="build/bin/nimbus")


class PluginSwap:
    """Builds of one plugin library, swapped into a nimbus build's plugin directory one at a time, for
    side-by-side timings in one run. The library that was there is put back at exit.

        with PluginSwap("build/bin/nimbus", "libnimbus_caustics.so", {"A": "a.so", "B": "b.so"}) as swap:
            swap.use("A")  # the next renders load build A
    """

    def __init__(self, nimbus, library, builds):
        root = os.path.dirname(os.path.dirname(os.path.abspath(nimbus)))
        self.plugin = os.path.join(root, "lib", "nimbus", "plugins", library)
        self.builds = builds
        self.tmp = None
        self.libs = {}

    def __enter__(self):
        self.tmp = tempfile.TemporaryDirectory()
        shutil.copy2(self.plugin, os.path.join(self.tmp.name, "saved.so"))
        for name, path in self.builds.items():  # copies: the originals may be rebuilt meanwhile
            self.libs[name] = os.path.join(self.tmp.name, f"build-{name}.so")
            shutil.copy2(path, self.libs[name])
        return self

    def use(self, name):
        shutil.copy2(self.libs[name], self.plugin)

    def __exit__(self, *exc):
        shutil.copy2(os.path.join(self.tmp.name, "saved.so"), self.plugin)
        self.tmp.cleanup()
        return False
