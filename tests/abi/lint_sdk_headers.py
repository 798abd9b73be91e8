#!/usr/bin/python3
"""Header lint for the Nimbus SDK (sdk-idioms.md §1.5, §1.7): thread tags and pointer ownership.

    lint_sdk_headers.py [DIR | HEADER.h ...]     (default: sdk/include/nimbus)

The rule, precisely (a summary is in the conventions comment of base.h):

"Own comment" of a declaration: the comment block directly above it (no blank or preprocessor line in
between), comments inside it, and comments starting on its last line after it.
"Header comment" of a struct: the own comment of its `typedef struct name {` line.
"Clause": a piece of comment text between ';' and sentence-ending '.' (a '.' followed by space or end).
"Covers p": a clause names `p` as a whole word and an ownership word follows later in that clause.
Ownership words: borrowed, out, host-owned, plugin-owned, caller storage.

T  Every function-pointer member, function-pointer typedef, member typed with such a typedef, and
   function declaration has exactly one thread tag in its own comment: [main-thread], [render-thread]
   or [any-thread], optionally narrowed by qualifiers, e.g. [main-thread, !rendering]. A bracketed
   text mentioning "thread" that is not a valid tag is an error (a typo is not a tag).
P  Every pointer parameter of those (declared with '*', as an array, which decays to a pointer, or with
   a pointer typedef) is named and covered by a clause of the own comment or of the struct's header
   comment. Exempt: receivers (`const nimbus_host_t *`, `const nimbus_plugin_t *`,
   `const nimbus_thread_ctx_t *`, also spelt `const struct nimbus_host *` ...), borrowed by the
   convention base.h states, and parameters of function-pointer typedef type (code, not data; their
   typedef carries its own tag).
R  A returned pointer is described by `host-owned` or `plugin-owned` in the own comment: it outlives
   the call, so neither `borrowed` nor `out` can describe it.
F  Every pointer member is covered by an ownership word anywhere in its own comment, or by a clause of
   the struct's header comment that names it.
Headers the reader cannot model (nested structs, bitfields, inline function-pointer parameters) fail
with file:line rather than being skipped.
"""

from __future__ import annotations

import glob
import os
import re
import sys

sys.dont_write_bytecode = True  # keep the source tree clean when ctest imports the reader
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sdk_headers  # noqa: E402

OWNERSHIP = re.compile(r"\b(borrowed|out|host-owned|plugin-owned|caller\s+storage)\b", re.I)
OWNER_OF_RETURN = re.compile(r"\b(host-owned|plugin-owned)\b", re.I)
THREAD_LIKE = re.compile(r"\[[^\[\]]*thread[^\[\]]*\]")
THREAD_TAG = re.compile(r"\[(main|render|any)-thread(\s*,\s*!?[A-Za-z][\w-]*)*\]")
RECEIVER = re.compile(r"^const\s+(struct\s+nimbus_host\b|nimbus_host_t\b|struct\s+nimbus_plugin\b|"
                      r"nimbus_plugin_t\b|struct\s+nimbus_thread_ctx\b|nimbus_thread_ctx_t\b)\s*\*")
# The conventions comment (base.h; version.h in SDKs up to 1.1) must keep stating the receiver convention
# the P rule relies on.
RECEIVER_CONVENTION = ("nimbus_host_t", "nimbus_plugin_t", "nimbus_thread_ctx_t")


def clauses(text: str) -> list[str]:
    text = re.sub(r"[`*]", " ", text)
    return [c for c in re.split(r";|\.(?=\s|$)", text) if c.strip()]


def covers(text: str, name: str) -> bool:
    word = re.compile(r"(?<![\w.>-])" + re.escape(name) + r"\b")
    for clause in clauses(text):
        for m in word.finditer(clause):
            if OWNERSHIP.search(clause, m.end()):
                return True
    return False


def check_tag(decl, label: str, errors: list[str], where: str) -> None:
    text = decl.comment_text
    for bad in THREAD_LIKE.findall(text):
        if not THREAD_TAG.fullmatch(bad):
            errors.append(f"{where}: {label}: malformed thread tag '{bad}'")
    tags = THREAD_TAG.findall(text)
    if len(tags) != 1:
        found = [m.group(0) for m in THREAD_TAG.finditer(text)]
        errors.append(f"{where}: {label}: needs exactly one thread tag ([main-thread], [render-thread] or "
                      f"[any-thread]) in its comment, found {len(tags)}{' ' + str(found) if found else ''}")


def check_function(decl, label: str, header_text: str, errors: list[str], where: str) -> None:
    check_tag(decl, label, errors, where)
    own = decl.comment_text
    if decl.returns_pointer and not OWNER_OF_RETURN.search(own):
        errors.append(f"{where}: {label}: returns a pointer; say who owns it (host-owned/plugin-owned until ...)")
    for p in decl.params:
        if not p.is_pointer or p.is_function or RECEIVER.match(p.text):
            continue
        if p.name is None:
            errors.append(f"{where}: {label}: unnamed pointer parameter '{p.text}' cannot be tagged; name it")
        elif not (covers(own, p.name) or covers(header_text, p.name)):
            errors.append(f"{where}: {label}: pointer parameter '{p.name}' has no ownership word "
                          "(borrowed, out, caller storage, host-owned, plugin-owned) after its name in a clause")


def lint(headers) -> list[str]:
    errors: list[str] = []
    for h in headers:
        rel = os.path.relpath(h.path)
        for s in h.structs:
            for m in s.members:
                where = f"{rel}:{m.line}"
                label = f"{s.typedef or s.name}.{','.join(m.names)}"
                if m.is_function_pointer:
                    check_function(m, label, s.header_text, errors, where)
                for name in m.pointer_names:
                    if m.is_function_pointer:
                        continue
                    if not (OWNERSHIP.search(m.comment_text) or covers(s.header_text, name)):
                        errors.append(f"{where}: {s.typedef or s.name}.{name}: pointer member has no ownership "
                                      "word (borrowed, out, caller storage, host-owned, plugin-owned)")
        for d in h.fn_typedefs + h.prototypes:
            check_function(d, d.names[0], "", errors, f"{rel}:{d.line}")
        if os.path.basename(h.path) == conventions_header(os.path.dirname(h.path)):
            first = h.comments[0].text if h.comments else ""
            missing = [t for t in RECEIVER_CONVENTION if t not in first]
            if missing or "borrowed" not in first:
                errors.append(f"{rel}: the conventions comment must state that receivers "
                              f"({', '.join(RECEIVER_CONVENTION)}) are borrowed; the lint exempts them on that basis")
    return errors


def conventions_header(directory: str) -> str:
    """The header whose first comment states the conventions: base.h since SDK 1.2, version.h before."""
    return "base.h" if os.path.exists(os.path.join(directory, "base.h")) else "version.h"


def header_paths(args: list[str]) -> list[str]:
    if not args:
        args = [os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "sdk", "include", "nimbus")]
    paths = []
    for a in args:
        if os.path.isdir(a):
            found = sorted(glob.glob(os.path.join(a, "*.h")))
            if not any(os.path.basename(p) == "version.h" for p in found):
                raise sdk_headers.HeaderError(f"{a}: no version.h; is this the SDK include directory?")
            paths += found
        else:
            paths.append(a)
    return paths


def main(argv: list[str]) -> int:
    try:
        paths = header_paths(argv)
        headers = sdk_headers.parse_headers(paths)
    except (sdk_headers.HeaderError, OSError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    structs = sum(len(h.structs) for h in headers)
    functions = sum(len(h.fn_typedefs) + len(h.prototypes) for h in headers)
    if structs + functions == 0:
        print("error: no structs or function types found: nothing was checked", file=sys.stderr)
        return 2
    errors = lint(headers)
    for e in errors:
        print(e, file=sys.stderr)
    members = sum(len(s.members) for h in headers for s in h.structs)
    print(f"{len(paths)} headers, {structs} structs, {members} members, {functions} function types: "
          f"{'%d problem(s)' % len(errors) if errors else 'ok'}")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
