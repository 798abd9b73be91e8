#!/usr/bin/python3
"""Proves the layout checker can fail and can pass: each case builds a tiny tree in a temporary folder,
runs check_layout.main() on it in-process (the code path ctest runs) and compares the exit status and
the lines the report must (and must not) contain.

    check_layout_selftest.py
"""

from __future__ import annotations

import contextlib
import io
import os
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True
sys.path.insert(0, HERE)
import check_layout  # noqa: E402

# The smallest tree that keeps every rule: a host unit using core and the SDK, SDK headers including
# each other, a plugin using the SDK and its own header.
BASE = {
    "host/core/math.hpp": "#pragma once\n#include <cmath>\n",
    "host/render/session.cpp": '#include "core/math.hpp"\n#include <nimbus/nimbus.h>\n#include <vector>\n',
    "sdk/include/nimbus/nimbus.h": '#include "host.h"\n',
    "sdk/include/nimbus/host.h": "#include <stdint.h>\n",
    "plugins/pt/pt.cpp": '#include <nimbus/nimbus.h>\n#include "record.hpp"\n',
    "plugins/pt/record.hpp": "#pragma once\n",
    "tests/core/math_test.cpp": '#include "core/math.hpp"\n#include "render/session.cpp"\n',
}


def lines(n: int, head: str = "") -> str:
    return head + "".join(f"int x{i};\n" for i in range(n - head.count("\n")))


@dataclass
class Case:
    name: str
    files: dict[str, str]  # written over BASE
    status: int
    expect: list[str] = field(default_factory=list)  # each must appear in the report
    refuse: list[str] = field(default_factory=list)  # none may appear in the report
    args: list[str] = field(default_factory=list)
    git: bool = False  # the tree is a git work tree: `files` are committed to the index, then
    untracked: dict[str, str] = field(default_factory=dict)  # these are written, not added
    deleted: list[str] = field(default_factory=list)  # and these removed from the work tree only


CASES = [
    Case("clean tree", {}, 0, ["4 units, 3 edges between them (3 include lines), 6 files in the include",
                               "0 include cycle(s)", "0 long file(s): ok"], ["FAIL", "warning:"]),
    Case("cycle host/a <-> host/b", {
        "host/a/a.hpp": '#pragma once\n#include "b/b.hpp"\n',
        "host/b/b.hpp": '#pragma once\n\n#include "a/a.hpp"\n',
    }, 1, ["FAIL include cycle between 2 units: host/a, host/b", "cycle: host/a -> host/b -> host/a",
           'host/a -> host/b (1 include line), e.g. host/a/a.hpp:2: #include "b/b.hpp"',
           'host/b -> host/a (1 include line), e.g. host/b/b.hpp:3: #include "a/a.hpp"']),
    Case("cycle through three units", {
        "host/a/a.cpp": '#include "b/b.hpp"\n',
        "host/b/b.hpp": '#include "c/c.hpp"\n',
        "host/c/c.hpp": '#include "a/a.hpp"\n',
        "host/a/a.hpp": "#pragma once\n",
    }, 1, ["between 3 units: host/a, host/b, host/c", "cycle: host/a -> host/b -> host/c -> host/a",
           "e.g. host/c/c.hpp:1:"], ["cycle: host/b", "cycle: host/c"]),
    Case("one-way edges are no cycle", {
        "host/a/a.cpp": '#include "b/b.hpp"\n#include "core/math.hpp"\n',
        "host/b/b.hpp": '#include "core/math.hpp"\n',
    }, 0, ["0 include cycle(s)"]),
    Case("include in a comment is no edge", {
        "host/a/a.hpp": '#include "b/b.hpp"\n',
        "host/b/b.hpp": '/* example:\n#include "a/a.hpp"\n*/\n// #include "a/a.hpp"\n',
    }, 0, ["0 include cycle(s)"]),
    Case("plugin includes a host header", {
        "plugins/pt/record.hpp": '#pragma once\n#include "core/math.hpp"\n',
    }, 1, ["FAIL 1 include(s) of host/ files from plugins/",
           'plugins/pt/record.hpp:2: #include "core/math.hpp"  -> host/core/math.hpp']),
    Case("plugin includes a host header with angle brackets", {
        "plugins/pt/pt.cpp": "#include <core/math.hpp>\n",
    }, 1, ["plugins/pt/pt.cpp:1: #include <core/math.hpp>  -> host/core/math.hpp"]),
    Case("plugin's own header shadows host/", {
        "plugins/pt/core/math.hpp": "#pragma once\n",
        "plugins/pt/pt.cpp": '#include "core/math.hpp"\n',
    }, 0, ["0 plugin->host include(s)"]),
    Case("a plugin's subfolder includes from the plugin's folder", {
        "plugins/ex/c/normals.c": '#include "shared.h"\n', "plugins/ex/shared.h": "#pragma once\n",
    }, 0, ["0 warning(s)", "5 units, 3 edges"]),
    Case("SDK includes a host header", {
        "sdk/include/nimbus/host.h": '#include "core/math.hpp"\n',
    }, 1, ["FAIL 1 include(s) of files outside sdk/ from sdk/",
           'sdk/include/nimbus/host.h:1: #include "core/math.hpp"  -> host/core/math.hpp']),
    Case("C++ kit is a unit of its own", {
        "sdk/include/nimbus/cpp/kit.hpp": "#include <nimbus/nimbus.h>\n",
        "sdk/include/nimbus/host.h": '#include "cpp/kit.hpp"\n',
    }, 1, ["units: sdk/include/nimbus, sdk/include/nimbus/cpp"]),
    Case("unresolved quoted include warns only", {
        "host/render/session.cpp": '#include "generated/table.inc"\n#include <nimbus/missing.h>\n',
    }, 0, ['warning: host/render/session.cpp:1: #include "generated/table.inc" names no file',
           "warning: host/render/session.cpp:2: #include <nimbus/missing.h>", "2 warning(s)"]),
    Case("tests include anything", {}, 0, [], ["tests/core"], args=["--graph"]),
    Case("401-line file", {"host/render/big.cpp": lines(401)}, 1,
         ["FAIL 1 source file(s) over 400 lines:", "host/render/big.cpp: 401 lines (max 400)"]),
    Case("400-line file", {"host/render/big.cpp": lines(400)}, 0, ["0 long file(s): ok"]),
    Case("last line without newline counts", {"tests/big.py": lines(400) + "x = 1"}, 1,
         ["tests/big.py: 401 lines"]),
    Case("long CMakeLists.txt, shell script and cmake file", {
        "tests/CMakeLists.txt": lines(401), "packaging/x.sh": lines(402), "sdk/cmake/x.cmake": lines(403),
    }, 1, ["tests/CMakeLists.txt: 401", "packaging/x.sh: 402", "sdk/cmake/x.cmake: 403"]),
    Case("long file with the marker and a reason", {
        "tests/render/cases_test.cpp": lines(900, "// Cases.\n// nimbus-layout: long-file-ok: many cases\n"),
    }, 0, ["0 long file(s): ok"]),
    Case("marker without a reason", {
        "tests/render/cases_test.cpp": lines(900, "// nimbus-layout: long-file-ok\n"),
    }, 1, ["tests/render/cases_test.cpp: 900 lines (max 400); its nimbus-layout: long-file-ok marker gives"]),
    Case("marker with punctuation only", {
        "tests/render/cases_test.cpp": lines(900, "/* nimbus-layout: long-file-ok */\n"),
    }, 1, ["marker gives no reason"]),
    Case("marker below the first 5 lines", {
        "tests/render/cases_test.cpp": lines(900, "//\n" * 5 + "// nimbus-layout: long-file-ok: table\n"),
    }, 1, ["tests/render/cases_test.cpp: 900 lines (max 400)"]),
    Case("data files, frozen SDK copies and other folders are not measured", {
        "scenes/big.yaml": lines(999), "tests/data/mesh.obj": lines(999), "docs/tool.py": lines(999),
        "tests/abi/sdk-1.0/include/nimbus/nimbus.hpp": lines(999), "tests/scenes/table.csv": lines(999),
    }, 0, ["0 long file(s): ok"]),
    Case("--max-lines", {"host/render/big.cpp": lines(120)}, 1, ["big.cpp: 120 lines (max 100)"],
         args=["--max-lines", "100"]),
    Case("--graph", {"host/a/a.hpp": '#include "core/math.hpp"\n#include "core/math.hpp"\n',
                     "host/lone/lone.hpp": "#pragma once\n"}, 0,
         ["host/a -> host/core: 2", "host/render -> sdk/include/nimbus: 1", "units with no edge: host/lone"],
         args=["--graph"]),
    Case("--graph tags cycles and forbidden edges", {
        "host/a/a.hpp": '#include "b/b.hpp"\n', "host/b/b.hpp": '#include "a/a.hpp"\n',
        "plugins/pt/pt.cpp": '#include "core/math.hpp"\n',
    }, 1, ["host/a -> host/b: 1  [cycle]", "plugins/pt -> host/core: 1  [plugin->host]"], args=["--graph"]),
    Case("git: ignored and deleted files are not read, untracked ones are", {
        ".gitignore": "/host/gen/\n", "host/gen/core/big.hpp": lines(999),
        "host/gen/a.hpp": '#include "render/x.hpp"\n', "host/render/x.hpp": '#include "gen/a.hpp"\n',
        "host/render/gone.cpp": lines(999),
    }, 1, ["host/render/new.cpp: 401 lines", "(files from git)", "0 include cycle(s)"],
        ["gen/", "gone.cpp"], git=True,
        untracked={"host/render/new.cpp": lines(401)}, deleted=["host/render/gone.cpp"]),
    Case("walk: hidden folders are not read", {
        "host/.cache/big.cpp": lines(999), "host/render/__pycache__/big.py": lines(999),
        "host/.cache/a.hpp": '#include "render/x.hpp"\n', "host/render/x.hpp": '#include ".cache/a.hpp"\n',
    }, 0, ["(files from walk)", "0 include cycle(s)"]),
    Case("walk: other folders are read", {"host/builders/big.cpp": lines(401)}, 1,
         ["host/builders/big.cpp: 401 lines"]),
]


def write_tree(root: str, files: dict[str, str], base: bool = True) -> None:
    tree = dict(BASE) if base else {}
    tree.update(files)
    for path, text in tree.items():
        full = os.path.join(root, path)
        os.makedirs(os.path.dirname(full), exist_ok=True)
        with open(full, "w", encoding="utf-8") as f:
            f.write(text)


def run(case: Case) -> list[str]:
    with tempfile.TemporaryDirectory() as tmp:
        root = os.path.join(tmp, "tree")
        write_tree(root, case.files)
        if case.git:
            if not shutil.which("git"):
                print(f"skipped (no git): {case.name}")
                return []
            subprocess.run(["git", "init", "-q", root], check=True)
            subprocess.run(["git", "-C", root, "add", "-A"], check=True)
            write_tree(root, case.untracked, base=False)
            for path in case.deleted:
                os.remove(os.path.join(root, path))
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            status = check_layout.main(["--root", root] + case.args)
        report = (out.getvalue() + err.getvalue()).replace(root + os.sep, "")
    errors = []
    if status != case.status:
        errors.append(f"exit status {status}, expected {case.status}")
    errors += [f"missing: {want}" for want in case.expect if want not in report]
    errors += [f"unexpected: {bad}" for bad in case.refuse if bad in report]
    return [f"case '{case.name}': {e}" for e in errors] + ([f"--- report:\n{report}"] if errors else [])


def main(argv: list[str]) -> int:
    if argv:
        print(__doc__, file=sys.stderr)
        return 2
    errors = [e for case in CASES for e in run(case)]
    for e in errors:
        print(e, file=sys.stderr)
    print(f"{len(CASES)} layout checker cases: {'FAILED' if errors else 'ok'}")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
