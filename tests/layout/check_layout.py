#!/usr/bin/python3
"""Architecture rules of the Nimbus source tree.

    check_layout.py [--root DIR] [--graph] [--max-lines N]

1. Includes. Every `#include "..."` and `#include <nimbus/...>` of the .h/.hpp/.c/.cpp files under host/,
   sdk/ and plugins/ (tests/ and bench/ may include anything) is resolved to a file of the tree, in this
   order: quoted includes relative to the including file's folder, then to host/ (the host's include path,
   "core/math.hpp" -> host/core/math.hpp), then to the plugin's own folder plugins/<name>/, then to
   sdk/include/; `<nimbus/...>` -> sdk/include/nimbus/...; another <...> that names a file under host/
   counts as that file, any other is a system header and ignored. An unresolved quoted or <nimbus/...>
   include is a warning. Each file belongs to a folder unit: host/<first folder>, sdk/include/nimbus (the
   C headers), sdk/include/nimbus/cpp (the C++ kit), plugins/<name>. The rules:
   - no cycle between units (each strongly connected component is reported with its cycles, one example
     include line per edge);
   - no file under plugins/ includes a file under host/ (plugins depend on the SDK alone);
   - no file under sdk/ includes a file outside sdk/.
2. Length. No source file (.c .cpp .h .hpp .py .sh .cmake, CMakeLists.txt) under host/ sdk/ plugins/
   tests/ bench/ packaging/ scenes/ has more than --max-lines lines (400), unless one of its first 5 lines
   holds `nimbus-layout: long-file-ok` followed by the reason (generated tables, tests of many cases).
   The frozen SDK copies under tests/abi/sdk-1.*/ are not checked; data files have none of those endings.
Files come from `git ls-files --cached --others --exclude-standard` when DIR is the top of a git work
tree (so build folders and ignored files are left out), else from walking the folders above without
hidden folders and __pycache__.
--graph also prints the folder graph: every edge between units with its number of include lines.
Exit status: 0 when the tree keeps the rules, 1 when it does not, 2 on usage errors.
"""

from __future__ import annotations

import argparse
import os
import posixpath
import re
import subprocess
import sys
from collections import defaultdict
from dataclasses import dataclass

sys.dont_write_bytecode = True  # keep the source tree clean when the self-test imports the checker

GRAPH_ROOTS = ("host", "sdk", "plugins")
GRAPH_EXTS = (".h", ".hpp", ".c", ".cpp")
LENGTH_ROOTS = ("host", "sdk", "plugins", "tests", "bench", "packaging", "scenes")
LENGTH_EXTS = (".c", ".cpp", ".h", ".hpp", ".py", ".sh", ".cmake")
LENGTH_NAMES = ("CMakeLists.txt",)
FROZEN_SDK = re.compile(r"^tests/abi/sdk-1\.[^/]+/")
MARKER = "nimbus-layout: long-file-ok"
MARKER_LINES = 5
INCLUDE = re.compile(r'^\s*#\s*include\s*(?:"([^"]+)"|<([^>]+)>)')
MAX_CYCLES_PER_COMPONENT = 20


@dataclass(frozen=True)
class Include:
    src: str  # including file, relative to the root
    line: int
    text: str  # the directive as written
    dst: str  # resolved file, relative to the root

    def where(self) -> str:
        return f"{self.src}:{self.line}: {self.text}"


# ---------------------------------------------------------------------------------------------- files
def list_files(root: str) -> tuple[list[str], str]:
    """Relative POSIX paths of the tree's files, and where they came from ("git" or "walk")."""
    try:
        top = subprocess.run(["git", "-C", root, "rev-parse", "--show-toplevel"], capture_output=True,
                             text=True, check=True).stdout.strip()
        if os.path.realpath(top) == os.path.realpath(root):
            out = subprocess.run(["git", "-C", root, "ls-files", "-z", "--cached", "--others",
                                  "--exclude-standard"], capture_output=True, text=True, check=True).stdout
            paths = {p for p in out.split("\0") if p and os.path.isfile(os.path.join(root, p))}
            return sorted(paths), "git"
    except (OSError, subprocess.CalledProcessError):
        pass
    paths = []
    for top in LENGTH_ROOTS:  # every folder a rule reads; build folders sit beside them
        for folder, dirs, names in os.walk(os.path.join(root, top)):
            dirs[:] = sorted(d for d in dirs if not d.startswith(".") and d != "__pycache__")
            rel = os.path.relpath(folder, root).replace(os.sep, "/")
            paths += [posixpath.join(rel, name) for name in names]
    return sorted(paths), "walk"


def read_text(root: str, path: str) -> str:
    with open(os.path.join(root, path), encoding="utf-8", errors="replace") as f:
        return f.read()


def count_lines(text: str) -> int:
    return text.count("\n") + (1 if text and not text.endswith("\n") else 0)


# ------------------------------------------------------------------------------------------- includes
def code_lines(text: str):
    """(line number, line) of the lines that start outside a block comment; text inside comments and
    string literals does not open or close one."""
    in_block = False
    for number, line in enumerate(text.split("\n"), 1):
        starts_in_block = in_block
        i, quote = 0, ""
        while i < len(line):
            two = line[i:i + 2]
            if in_block:
                if two == "*/":
                    in_block, i = False, i + 1
            elif quote:
                if line[i] == "\\":
                    i += 1
                elif line[i] == quote:
                    quote = ""
            elif two == "//":
                break
            elif two == "/*":
                in_block, i = True, i + 1
            elif line[i] in "\"'" and not line.lstrip().startswith("#"):
                quote = line[i]
            i += 1
        if not starts_in_block:
            yield number, line


def unit_of(path: str) -> str:
    parts = path.split("/")
    if parts[0] == "sdk":
        if path.startswith("sdk/include/nimbus/cpp/"):
            return "sdk/include/nimbus/cpp"
        if path.startswith("sdk/include/nimbus/"):
            return "sdk/include/nimbus"
    if parts[0] in ("host", "sdk", "plugins", "tests", "bench") and len(parts) > 2:
        return f"{parts[0]}/{parts[1]}"
    return parts[0] if len(parts) > 1 else "."


def resolve(src: str, quoted: bool, name: str, exists) -> str | None:
    if quoted:
        candidates = [posixpath.join(posixpath.dirname(src), name), posixpath.join("host", name)]
        parts = src.split("/")
        if parts[0] == "plugins" and len(parts) > 2:
            candidates.append(posixpath.join("plugins", parts[1], name))
        candidates.append(posixpath.join("sdk/include", name))
    elif name.startswith("nimbus/"):
        candidates = [posixpath.join("sdk/include", name)]
    else:
        candidates = [posixpath.join("host", name)]
    for candidate in candidates:
        candidate = posixpath.normpath(candidate)
        if not candidate.startswith("../") and exists(candidate):
            return candidate
    return None


def scan_includes(root: str, files: list[str]) -> tuple[list[Include], list[str]]:
    includes, warnings = [], []
    exists = lambda p: os.path.isfile(os.path.join(root, p))  # noqa: E731
    for src in files:
        for number, line in code_lines(read_text(root, src)):
            m = INCLUDE.match(line)
            if not m:
                continue
            quoted, name = (True, m.group(1)) if m.group(1) is not None else (False, m.group(2))
            text = f'#include "{name}"' if quoted else f"#include <{name}>"
            dst = resolve(src, quoted, name, exists)
            if dst is not None:
                includes.append(Include(src, number, text, dst))
            elif quoted or name.startswith("nimbus/"):
                warnings.append(f"{src}:{number}: {text} names no file of the tree")
    return includes, warnings


# ---------------------------------------------------------------------------------------------- graph
def strongly_connected(nodes: list[str], succ: dict[str, list[str]]) -> list[list[str]]:
    """Tarjan's algorithm, iterative; components in a deterministic order, each sorted."""
    index, low, on_stack, stack, result = {}, {}, set(), [], []
    for start in nodes:
        if start in index:
            continue
        work = [(start, 0)]
        while work:
            node, child = work.pop()
            if child == 0:
                index[node] = low[node] = len(index)
                stack.append(node)
                on_stack.add(node)
            targets = succ.get(node, [])
            if child < len(targets):
                work.append((node, child + 1))
                nxt = targets[child]
                if nxt not in index:
                    work.append((nxt, 0))
                elif nxt in on_stack:
                    low[node] = min(low[node], index[nxt])
                continue
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                result.append(sorted(component))
            if work:
                parent = work[-1][0]
                low[parent] = min(low[parent], low[node])
    return sorted(result)


def elementary_cycles(component: list[str], succ: dict[str, list[str]], limit: int) -> list[list[str]]:
    """Cycles inside one component, each starting at its smallest unit, at most `limit` of them."""
    members, cycles = set(component), []
    for start in component:
        path, seen = [start], {start}

        def walk(node: str) -> None:
            for nxt in succ.get(node, []):
                if len(cycles) >= limit or nxt not in members or nxt < start:
                    continue
                if nxt == start:
                    cycles.append(list(path))
                elif nxt not in seen:
                    path.append(nxt)
                    seen.add(nxt)
                    walk(nxt)
                    seen.discard(path.pop())

        walk(start)
    return cycles[:limit]


# ---------------------------------------------------------------------------------------------- rules
def check_includes(includes: list[Include]):
    edges: dict[tuple[str, str], list[Include]] = defaultdict(list)
    plugin_host, sdk_out = [], []
    for inc in includes:
        if inc.src.startswith("plugins/") and inc.dst.startswith("host/"):
            plugin_host.append(inc)
        if inc.src.startswith("sdk/") and not inc.dst.startswith("sdk/"):
            sdk_out.append(inc)
        a, b = unit_of(inc.src), unit_of(inc.dst)
        if a != b:
            edges[(a, b)].append(inc)
    return edges, plugin_host, sdk_out


def check_lengths(root: str, files: list[str], max_lines: int) -> tuple[list[str], int]:
    problems, checked = [], 0
    for path in files:
        name = posixpath.basename(path)
        if (path.split("/")[0] not in LENGTH_ROOTS or FROZEN_SDK.match(path)
                or not (name.endswith(LENGTH_EXTS) or name in LENGTH_NAMES)):
            continue
        checked += 1
        text = read_text(root, path)
        lines = count_lines(text)
        if lines <= max_lines:
            continue
        head = "\n".join(text.split("\n")[:MARKER_LINES])
        at = head.find(MARKER)
        if at >= 0:
            reason = head[at + len(MARKER):].split("\n")[0]
            if re.search(r"[A-Za-z]{3,}", reason):
                continue
            problems.append(f"{path}: {lines} lines (max {max_lines}); its {MARKER} marker gives no reason")
        else:
            problems.append(f"{path}: {lines} lines (max {max_lines})")
    return problems, checked


def print_graph(units: list[str], edges, cyclic: set[tuple[str, str]]) -> None:
    print(f"folder graph: {len(units)} units, {len(edges)} edges (unit -> unit it includes: include lines)")
    for (a, b), incs in sorted(edges.items()):
        tags = []
        if (a, b) in cyclic:
            tags.append("cycle")
        if a.startswith("plugins/") and b.startswith("host/"):
            tags.append("plugin->host")
        if a.startswith("sdk/") and not b.startswith("sdk/"):
            tags.append("sdk->outside")
        print(f"  {a} -> {b}: {len(incs)}" + (f"  [{', '.join(tags)}]" if tags else ""))
    alone = [u for u in units if not any(u in e for e in edges)]
    if alone:
        print(f"  units with no edge: {', '.join(alone)}")
    print()


def main(argv: list[str]) -> int:
    default_root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    parser = argparse.ArgumentParser(description="Architecture rules of the Nimbus source tree.")
    parser.add_argument("--root", default=default_root, help="the repository's top folder")
    parser.add_argument("--graph", action="store_true", help="also print the folder graph")
    parser.add_argument("--max-lines", type=int, default=400, help="longest source file allowed")
    args = parser.parse_args(argv)
    root = os.path.abspath(args.root)
    if not all(os.path.isdir(os.path.join(root, d)) for d in ("host", "sdk")):
        print(f"error: {root} has no host/ and sdk/ folders: not a Nimbus tree", file=sys.stderr)
        return 2

    files, source = list_files(root)
    sources = [p for p in files if p.split("/")[0] in GRAPH_ROOTS and p.endswith(GRAPH_EXTS)]
    includes, warnings = scan_includes(root, sources)
    edges, plugin_host, sdk_out = check_includes(includes)
    units = sorted({unit_of(p) for p in sources} | {u for e in edges for u in e})
    succ: dict[str, list[str]] = defaultdict(list)
    for a, b in sorted(edges):
        succ[a].append(b)
    components = [c for c in strongly_connected(units, succ) if len(c) > 1]
    cyclic = {(a, b) for c in components for a in c for b in succ.get(a, []) if b in c}
    long_files, length_checked = check_lengths(root, files, args.max_lines)

    if args.graph:
        print_graph(units, edges, cyclic)
    for w in warnings:
        print(f"warning: {w}")
    for component in components:
        cycles = elementary_cycles(component, succ, MAX_CYCLES_PER_COMPONENT)
        print(f"FAIL include cycle between {len(component)} units: {', '.join(component)}")
        for cycle in cycles:
            print("  cycle: " + " -> ".join(cycle + cycle[:1]))
            for a, b in zip(cycle, cycle[1:] + cycle[:1]):
                incs = edges[(a, b)]
                print(f"    {a} -> {b} ({len(incs)} include line{'s' * (len(incs) != 1)}), "
                      f"e.g. {min(incs, key=lambda i: (i.src, i.line)).where()}")
        if len(cycles) == MAX_CYCLES_PER_COMPONENT:
            print(f"  (first {MAX_CYCLES_PER_COMPONENT} cycles only)")
    if plugin_host:
        print(f"FAIL {len(plugin_host)} include(s) of host/ files from plugins/ (plugins use the SDK alone):")
        for inc in plugin_host:
            print(f"  {inc.where()}  -> {inc.dst}")
    if sdk_out:
        print(f"FAIL {len(sdk_out)} include(s) of files outside sdk/ from sdk/:")
        for inc in sdk_out:
            print(f"  {inc.where()}  -> {inc.dst}")
    if long_files:
        print(f"FAIL {len(long_files)} source file(s) over {args.max_lines} lines:")
        for problem in long_files:
            print(f"  {problem}")

    failed = bool(components or plugin_host or sdk_out or long_files)
    print(f"layout: {len(units)} units, {len(edges)} edges between them ({sum(map(len, edges.values()))} "
          f"include lines), {len(sources)} files in the include graph, {length_checked} files checked for "
          f"length (files from {source}), {len(warnings)} warning(s)")
    print(f"layout: {len(components)} include cycle(s), {len(plugin_host)} plugin->host include(s), "
          f"{len(sdk_out)} sdk->outside include(s), {len(long_files)} long file(s): "
          f"{'FAILED' if failed else 'ok'}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
