"""Helpers shared by the benchmark scripts in bench/: running a command, reading a render's metadata."""
import subprocess
import sys


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
