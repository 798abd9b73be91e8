#!/usr/bin/python3
"""Proves a layout_1_<minor>.c can fail: compiles it against edited copies of the live headers.

    layout_mutation_test.py CC SDK_INCLUDE_DIR LAYOUT_C

appending to a table        -> must compile (tables grow within a major)
swapping two table members  -> must not compile (every plugin built earlier would call the wrong hook)
appending to a hot record   -> must not compile (records live in arrays; their size is frozen)
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile

BEGIN = "  nimbus_status_t (*begin_iteration)(const nimbus_plugin_t *plugin, uint64_t iteration);\n"
END = "  nimbus_status_t (*end_iteration)(const nimbus_plugin_t *plugin, uint64_t iteration);\n"
TABLE_END = "} nimbus_integrator_v1_t;"
RAY_END = "} nimbus_ray_t;"

MUTATIONS = [
    ("append to nimbus_integrator_v1_t", "integrator.h",
     lambda s: s.replace(TABLE_END, "  void (*added_in_1_1)(const nimbus_plugin_t *plugin);\n" + TABLE_END), True),
    ("swap begin_iteration and end_iteration", "integrator.h",
     lambda s: s.replace(BEGIN, "@@").replace(END, BEGIN).replace("@@", END), False),
    ("append to nimbus_ray_t", "scene.h", lambda s: s.replace(RAY_END, "  float time;\n" + RAY_END), False),
]


def compiles(cc: str, include: str, source: str) -> tuple[bool, str]:
    r = subprocess.run([cc, "-std=c11", "-pedantic", "-Wall", "-Werror", "-fsyntax-only", "-I", include, source],
                       capture_output=True, text=True, timeout=60)
    return r.returncode == 0, r.stderr


def main(argv: list[str]) -> int:
    cc, include, layout = argv
    ok, err = compiles(cc, include, layout)
    if not ok:
        print(f"{os.path.basename(layout)} does not compile against the live headers:\n{err}", file=sys.stderr)
        return 1
    failures = []
    for label, header, edit, should_compile in MUTATIONS:
        with tempfile.TemporaryDirectory() as tmp:
            shutil.copytree(os.path.join(include, "nimbus"), os.path.join(tmp, "nimbus"))
            path = os.path.join(tmp, "nimbus", header)
            with open(path) as f:
                before = f.read()
            after = edit(before)
            if after == before:
                failures.append(f"{label}: the edit did not apply to {header}; update this test")
                continue
            with open(path, "w") as f:
                f.write(after)
            ok, err = compiles(cc, tmp, layout)
            if ok != should_compile:
                failures.append(f"{label}: expected {'success' if should_compile else 'a layout error'}, got "
                                f"{'success' if ok else 'failure'}\n{err}")
            elif not ok and "moved" not in err and "changed size" not in err:
                failures.append(f"{label}: failed for another reason than a layout assertion:\n{err}")
            else:
                print(f"{label}: {'compiles' if ok else 'refused'} as expected")
    for f in failures:
        print(f, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
