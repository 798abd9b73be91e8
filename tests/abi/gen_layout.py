#!/usr/bin/python3
"""Writes layout_<major>_<minor>.c: literal sizeof/offsetof/alignof of every struct of the SDK headers.

    gen_layout.py SDK_INCLUDE_DIR [CC] > layout_1_0.c

Run once when a minor ships, to freeze its layout; never to make a failing build pass (a failure means a
shipped struct moved). The members are read with sdk_headers.py, the numbers come from compiling and
running a probe with the C compiler, so they are the compiler's, not this script's.
"""

from __future__ import annotations

import glob
import os
import subprocess
import sys
import tempfile

sys.dont_write_bytecode = True  # keep the source tree clean when ctest imports the reader
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sdk_headers  # noqa: E402

# Embedded at the start of other structs, so they can never grow even though they look like headers.
ALWAYS_FROZEN = {"nimbus_struct_header_t", "nimbus_version_t"}


def growable(s) -> bool:
    """Function tables (`struct_size` first) and info structs (`header` first) may gain members at the end."""
    if s.typedef in ALWAYS_FROZEN or not s.members:
        return False
    return s.members[0].names[0] in ("struct_size", "header")


def probe(include_dir: str, cc: str, structs) -> list[list[int]]:
    lines = ["#include <nimbus/nimbus.h>", "#include <stdio.h>", "int main(void) {"]
    for s in structs:
        t = s.typedef
        lines.append(f'  printf("%zu %zu\\n", sizeof({t}), _Alignof({t}));')
        for m in s.members:
            for n in m.names:
                lines.append(f'  printf("%zu %zu\\n", offsetof({t}, {n}), sizeof((({t} *)0)->{n}));')
    lines += ["  return 0;", "}"]
    with tempfile.TemporaryDirectory() as tmp:
        src, exe = os.path.join(tmp, "probe.c"), os.path.join(tmp, "probe")
        with open(src, "w") as f:
            f.write("\n".join(lines) + "\n")
        subprocess.run([cc, "-std=c11", "-I", include_dir, src, "-o", exe], check=True)
        out = subprocess.run([exe], check=True, capture_output=True, text=True).stdout
    return [[int(x) for x in l.split()] for l in out.splitlines()]


def main(argv: list[str]) -> int:
    include_dir = argv[0]
    cc = argv[1] if len(argv) > 1 else "cc"
    headers = sdk_headers.parse_headers(sorted(glob.glob(os.path.join(include_dir, "nimbus", "*.h"))))
    with open(os.path.join(include_dir, "nimbus", "version.h")) as f:
        ver = {l.split()[1]: l.split()[2] for l in f if l.startswith("#define NIMBUS_ABI_M")}
    major, minor = ver["NIMBUS_ABI_MAJOR"], ver["NIMBUS_ABI_MINOR"]
    structs = [s for h in headers for s in h.structs]
    numbers = iter(probe(include_dir, cc, structs))
    out = [
        f"/* Layout of the Nimbus SDK {major}.{minor} structs on x86-64 System V (sdk-idioms.md §4.2), checked",
        " * against the live headers at compile time: appending members keeps this file compiling; moving,",
        " * resizing or removing one breaks the build. Generated once by gen_layout.py when the minor shipped;",
        " * the numbers are literal on purpose: never regenerate it to make a failing build pass.",
        " * Tables and info structs may grow at the end (sizeof >=); hot-path records are frozen (sizeof ==). */",
        "#include <nimbus/nimbus.h>",
        "#include <stddef.h>",
        "",
        "#if defined(__x86_64__) && !defined(_WIN32)",
        f"_Static_assert(NIMBUS_ABI_MAJOR == {major} && NIMBUS_ABI_MINOR >= {minor}, \"not a {major}.x SDK\");",
        "",
        "#define NIMBUS_MEMBER(T, m, off, size) \\",
        "  _Static_assert(offsetof(T, m) == (off) && sizeof(((T *)0)->m) == (size), #T \".\" #m \" moved\")",
        "#define NIMBUS_FROZEN(T, size, align) \\",
        "  _Static_assert(sizeof(T) == (size) && _Alignof(T) == (align), #T \" changed size\")",
        "#define NIMBUS_GROWABLE(T, size, align) \\",
        "  _Static_assert(sizeof(T) >= (size) && _Alignof(T) == (align), #T \" shrank\")",
    ]
    current = None
    for s in structs:
        header = os.path.basename(next(h.path for h in headers if s in h.structs))
        if header != current:
            out += ["", f"/* {header} */"]
            current = header
        size, align = next(numbers)
        out.append(f"{'NIMBUS_GROWABLE' if growable(s) else 'NIMBUS_FROZEN'}({s.typedef}, {size}, {align});")
        for m in s.members:
            for n in m.names:
                off, msize = next(numbers)
                out.append(f"NIMBUS_MEMBER({s.typedef}, {n}, {off}, {msize});")
    out += ["#else", "typedef int nimbus_layout_not_checked; /* another ABI: the numbers above do not apply */",
            "#endif"]
    print("\n".join(out))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
