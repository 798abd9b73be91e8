"""Helpers shared by the benchmark scripts in bench/: running a command, reading a render's metadata,
finding a build's plugin directory, removing a render's files, swapping builds of one plugin library,
reading an EXR's pixels bit for bit (read_exr, needs numpy)."""
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib


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


def plugin_dir(nimbus):
    """The plugin directory of the build (a build tree or an install prefix) that holds bin/nimbus."""
    return os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(nimbus))), "lib", "nimbus", "plugins")


def callgrind_instructions(cmd, cwd=None, part="libembree"):
    """(all, in objects whose path contains `part`) instructions one command executes, counted by callgrind
    (Debian's valgrind): exact and repeatable where times on a shared machine drift."""
    with tempfile.TemporaryDirectory(prefix="nimbus_callgrind_") as tmp:
        out_file = os.path.join(tmp, "callgrind.out")
        subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=" + out_file] + cmd, cwd=cwd,
                       check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        report = subprocess.run(["callgrind_annotate", "--threshold=100", "--inclusive=no", "--show-percs=no",
                                 out_file], capture_output=True, text=True, check=True).stdout
    total = in_part = 0
    for line in report.splitlines():
        m = re.match(r"\s*([0-9,]+)\s+(.*)$", line)
        if not m:
            continue
        n = int(m.group(1).replace(",", ""))
        if m.group(2).startswith("PROGRAM TOTALS"):
            total = n
        elif part in m.group(2):
            in_part += n
    return total, in_part


def remove_render_outputs(out):
    """Removes the files a render to `out` leaves: the image, its checkpoint and its PNG preview."""
    for path in (out, out + ".ckpt", os.path.splitext(out)[0] + ".png"):
        if os.path.exists(path):
            os.remove(path)


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
        self.plugin = os.path.join(plugin_dir(nimbus), library)
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


# --- Reading OpenEXR pixels bit for bit (numpy; no OpenImageIO Python module needed) ---------------

EXR_UINT, EXR_HALF, EXR_FLOAT = 0, 1, 2
_EXR_BITS_DTYPE = {EXR_UINT: "<u4", EXR_HALF: "<u2", EXR_FLOAT: "<u4"}   # the stored bits of a sample
_EXR_VALUE_DTYPE = {EXR_UINT: "<u4", EXR_HALF: "<f2", EXR_FLOAT: "<f4"}  # the same bits as numbers
_EXR_LINES_PER_BLOCK = {0: 1, 1: 1, 2: 1, 3: 16}  # NONE, RLE, ZIPS, ZIP: the compressions decoded here


class ExrUnsupported(Exception):
    """A file read_exr does not decode itself (tiled, deep, or PIZ/PXR24/B44/DWA… compression)."""


class ExrPart:
    """One part (subimage) of an EXR file: `name` (None in a single-part file), `attributes` (attribute
    name -> (type name, raw bytes)), `channels` [(name, pixel type, x sampling, y sampling)] in file
    order, `data_window` (xmin, ymin, xmax, ymax) and `pixels` (channel name -> 2-D numpy array of the
    samples' stored bits: uint16 for half, uint32 for float and uint)."""

    def __init__(self, attributes):
        self.attributes = attributes
        self.name = _exr_string(attributes["name"][1]) if "name" in attributes else None
        self.channels = _exr_chlist(attributes["channels"][1])
        self.data_window = struct.unpack("<4i", attributes["dataWindow"][1])
        self.compression = attributes["compression"][1][0]
        self.pixels = {}

    def values(self, channel):
        """The samples of `channel` as numbers (float16, float32 or uint32)."""
        ptype = next(c[1] for c in self.channels if c[0] == channel)
        return self.pixels[channel].view(_EXR_VALUE_DTYPE[ptype])

    def attribute_text(self, name):
        """An attribute's value as text, for messages."""
        return _exr_attribute_text(*self.attributes[name])


def _exr_string(raw):
    return raw.decode("utf-8", "replace")


def _exr_chlist(raw):
    channels, pos = [], 0
    while raw[pos] != 0:
        end = raw.index(b"\0", pos)
        name = _exr_string(raw[pos:end])
        ptype, _linear, xs, ys = struct.unpack_from("<iB3xii", raw, end + 1)
        channels.append((name, ptype, xs, ys))
        pos = end + 1 + 16
    return channels


def _exr_attribute_text(atype, raw):
    simple = {"int": "<i", "float": "<f", "double": "<d", "box2i": "<4i", "box2f": "<4f", "v2i": "<2i",
              "v2f": "<2f", "v3i": "<3i", "v3f": "<3f", "compression": "<B", "lineOrder": "<B"}
    if atype == "string":
        return repr(_exr_string(raw))
    if atype in simple and len(raw) == struct.calcsize(simple[atype]):
        values = struct.unpack(simple[atype], raw)
        return " ".join(repr(v) for v in values)
    if atype == "chlist":
        return ",".join(c[0] for c in _exr_chlist(raw))
    return f"<{atype}, {len(raw)} bytes, {raw[:16].hex()}{'…' if len(raw) > 16 else ''}>"


def _exr_rows(lo, hi, sampling):
    """The coordinates in [lo, hi] that hold samples at this sampling rate."""
    return [v for v in range(lo, hi + 1) if v % sampling == 0]


def _exr_undo_zip_filters(raw):
    """OpenEXR's ZIP/RLE post-processing undone: the byte delta predictor, then the split of even and
    odd bytes into two halves."""
    import numpy as np
    t = np.frombuffer(raw, dtype=np.uint8).astype(np.int64)
    t[1:] -= 128
    t = (np.cumsum(t) & 0xFF).astype(np.uint8)
    out = np.empty_like(t)
    half = (len(t) + 1) // 2
    out[0::2] = t[:half]
    out[1::2] = t[half:]
    return out.tobytes()


def _exr_rle_decompress(raw):
    out, pos = bytearray(), 0
    while pos < len(raw):
        count = struct.unpack_from("b", raw, pos)[0]
        pos += 1
        if count < 0:
            out += raw[pos:pos - count]
            pos -= count
        else:
            out += raw[pos:pos + 1] * (count + 1)
            pos += 1
    return bytes(out)


def _exr_decode_block(part, data, expected):
    if len(data) == expected:  # OpenEXR stores a block raw when compressing did not make it smaller
        return data
    if part.compression == 3 or part.compression == 2:
        data = _exr_undo_zip_filters(zlib.decompress(data))
    elif part.compression == 1:
        data = _exr_undo_zip_filters(_exr_rle_decompress(data))
    if len(data) != expected:
        raise ValueError(f"EXR block of {len(data)} bytes, expected {expected}")
    return data


def _exr_read_native(path):
    import numpy as np
    with open(path, "rb") as f:
        buf = f.read()
    magic, version = struct.unpack_from("<ii", buf, 0)
    if magic != 20000630:
        raise ValueError(f"{path}: not an OpenEXR file")
    if version & 0x800:
        raise ExrUnsupported("deep data")
    multipart = bool(version & 0x1000)
    if version & 0x200 and not multipart:
        raise ExrUnsupported("tiled image")
    pos, parts = 8, []
    while True:  # headers: attributes up to an empty name; in a multi-part file, headers up to an empty one
        attributes = {}
        while buf[pos] != 0:
            end = buf.index(b"\0", pos)
            name = _exr_string(buf[pos:end])
            tend = buf.index(b"\0", end + 1)
            atype = _exr_string(buf[end + 1:tend])
            size = struct.unpack_from("<i", buf, tend + 1)[0]
            attributes[name] = (atype, buf[tend + 5:tend + 5 + size])
            pos = tend + 5 + size
        pos += 1
        if not attributes:
            break
        parts.append(ExrPart(attributes))
        if not multipart:
            break
    counts = []
    for part in parts:
        kind = _exr_string(part.attributes["type"][1]) if "type" in part.attributes else "scanlineimage"
        if kind != "scanlineimage":
            raise ExrUnsupported(kind)
        if part.compression not in _EXR_LINES_PER_BLOCK:
            raise ExrUnsupported(f"compression {part.compression}")
        xmin, ymin, xmax, ymax = part.data_window
        lpb = _EXR_LINES_PER_BLOCK[part.compression]
        counts.append(struct.unpack("<i", part.attributes["chunkCount"][1])[0]
                      if "chunkCount" in part.attributes else (ymax - ymin + lpb) // lpb)
    tables = []
    for count in counts:
        tables.append(struct.unpack_from(f"<{count}Q", buf, pos))
        pos += 8 * count
    for index, (part, table) in enumerate(zip(parts, tables)):
        xmin, ymin, xmax, ymax = part.data_window
        lpb = _EXR_LINES_PER_BLOCK[part.compression]
        layout = []  # per channel: name, bytes per sample, samples per line, row index of each line y
        for name, ptype, xs, ys in part.channels:
            rows = {y: i for i, y in enumerate(_exr_rows(ymin, ymax, ys))}
            width = len(_exr_rows(xmin, xmax, xs))
            part.pixels[name] = np.zeros((len(rows), width), dtype=_EXR_BITS_DTYPE[ptype])
            layout.append((name, np.dtype(_EXR_BITS_DTYPE[ptype]), width, rows))
        seen = set()
        for offset in table:
            p = offset
            if multipart:
                if struct.unpack_from("<i", buf, p)[0] != index:
                    raise ValueError(f"{path}: chunk of another part in part {index}'s offset table")
                p += 4
            y0, size = struct.unpack_from("<ii", buf, p)
            lines = range(y0, min(y0 + lpb, ymax + 1))
            expected = sum(width * dt.itemsize for y in lines for _, dt, width, rows in layout if y in rows)
            data = _exr_decode_block(part, buf[p + 8:p + 8 + size], expected)
            q = 0
            for y in lines:
                for name, dt, width, rows in layout:
                    if y in rows:
                        n = width * dt.itemsize
                        part.pixels[name][rows[y]] = np.frombuffer(data, dtype=dt, count=width, offset=q)
                        q += n
            seen.add(y0)
        if len(seen) != len(table):
            raise ValueError(f"{path}: part {index} has repeated blocks")
    return parts


def read_exr(path):
    """Every part of an EXR file with its pixels as stored bits (see ExrPart). Scanline images with no,
    RLE, ZIPS or ZIP compression (what Nimbus writes) are decoded here; anything else is first rewritten
    by oiiotool as uncompressed scanlines (half and float samples survive that bit for bit)."""
    try:
        return _exr_read_native(path)
    except ExrUnsupported:
        with tempfile.TemporaryDirectory() as tmp:
            plain = os.path.join(tmp, "plain.exr")
            cmd = ["oiiotool", "-a", path, "--scanline", "--compression", "none", "-o", plain]
            proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
            if proc.returncode != 0:
                raise ValueError(f"{' '.join(cmd)} failed: {proc.stdout.strip()}")
            return _exr_read_native(plain)


def read_rgb(path, layer="beauty"):
    """A render element's R, G, B (channels R, G, B for beauty, LAYER.R... otherwise) of an EXR's first
    part as float64, rows x columns x 3. Raises KeyError when the file has no such element."""
    import numpy as np
    part = read_exr(path)[0]
    prefix = "" if layer == "beauty" else layer + "."
    return np.stack([part.values(prefix + c).astype(np.float64) for c in "RGB"], axis=-1)
