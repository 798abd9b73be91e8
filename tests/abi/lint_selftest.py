#!/usr/bin/python3
"""Proves the header lint can fail: each lint_cases/*.h names on its first line the one problem the lint
must report (or `ok`), and a copy of the real SDK headers with a member appended to a live table must be
refused unless the new member is tagged. Runs the lint's main() as ctest does, in-process.

    lint_selftest.py SDK_INCLUDE_NIMBUS_DIR
"""

from __future__ import annotations

import contextlib
import glob
import io
import os
import re
import shutil
import sys
import tempfile
from dataclasses import dataclass

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True
sys.path.insert(0, HERE)
import lint_sdk_headers  # noqa: E402

PROBLEMS = re.compile(r"(\d+) problem\(s\)")


@dataclass
class Result:
    returncode: int
    stdout: str
    stderr: str


def run_lint(*args: str) -> Result:
    """The lint's command line, run in-process: same code path as ctest's, without an interpreter start."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = lint_sdk_headers.main(list(args))
    return Result(code, out.getvalue(), err.getvalue())


def check_case(path: str) -> list[str]:
    with open(path, encoding="utf-8") as f:
        m = re.match(r"/\* expect: (.*?) \*/", f.readline())
    if not m:
        return [f"{path}: first line must be /* expect: <message or ok> */"]
    want = m.group(1)
    r = run_lint(path)
    out = r.stdout + r.stderr
    if want == "ok":
        return [] if r.returncode == 0 else [f"{path}: expected to pass, lint said:\n{out}"]
    if r.returncode == 0:
        return [f"{path}: expected failure '{want}', but the lint passed"]
    if want not in out:
        return [f"{path}: expected '{want}' in the lint's output, got:\n{out}"]
    count = PROBLEMS.search(out)
    if count and count.group(1) != "1":  # one planted problem, one report: the rule is precise
        return [f"{path}: expected exactly one problem, got {count.group(1)}:\n{out}"]
    return []


def check_appended_member(sdk_dir: str) -> list[str]:
    """A new member of nimbus_integrator_v1 must be refused untagged and accepted once tagged."""
    errors = []
    added = {
        "untagged": ("  void (*new_hook)(const nimbus_plugin_t *plugin, float *values);\n", 2),
        "tag only": ("  /* [main-thread] Fills values. */\n"
                     "  void (*new_hook)(const nimbus_plugin_t *plugin, float *values);\n", 1),
        "tagged": ("  /* [main-thread] Fills values (out, caller storage). */\n"
                   "  void (*new_hook)(const nimbus_plugin_t *plugin, float *values);\n", 0),
    }
    for label, (member, problems) in added.items():
        with tempfile.TemporaryDirectory() as tmp:
            inc = os.path.join(tmp, "nimbus")
            shutil.copytree(sdk_dir, inc)
            path = os.path.join(inc, "integrator.h")
            with open(path, encoding="utf-8") as f:
                src = f.read()
            end = "} nimbus_integrator_v1_t;"
            if src.count(end) != 1:
                return [f"{path}: cannot find '{end}' to append a member to"]
            with open(path, "w", encoding="utf-8") as f:
                f.write(src.replace(end, member + end))
            r = run_lint(inc)
            out = r.stdout + r.stderr
            got = PROBLEMS.search(out)
            got_n = int(got.group(1)) if got else (0 if r.returncode == 0 else -1)
            if got_n != problems or (problems and "new_hook" not in out):
                errors.append(f"appended {label} member: expected {problems} problem(s) naming new_hook, got:\n{out}")
    return errors


def main(argv: list[str]) -> int:
    if len(argv) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    cases = sorted(glob.glob(os.path.join(HERE, "lint_cases", "*.h")))
    if len(cases) < 2:
        print("error: no lint cases found", file=sys.stderr)
        return 2
    errors = [e for c in cases for e in check_case(c)] + check_appended_member(argv[0])
    for e in errors:
        print(e, file=sys.stderr)
    print(f"{len(cases)} cases + appended-member check: {'FAILED' if errors else 'ok'}")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
