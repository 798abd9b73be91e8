"""A small reader for the Nimbus SDK's C headers, shared by the header lint and the layout generator.

It understands exactly the subset the SDK uses (sdk-idioms.md §1.1): typedef'd structs of plain
members, function-pointer members and typedefs, #define lines and static inline helpers. Anything it
does not understand inside a struct is reported rather than skipped, so a new construct forces this
reader (and the lint rule built on it) to be extended deliberately instead of going unchecked.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

IDENT = re.compile(r"[A-Za-z_]\w*")


class HeaderError(Exception):
    """A construct the reader cannot model; carries file:line."""


@dataclass
class Comment:
    line: int  # first line (1-based)
    end_line: int
    text: str  # without the comment markers


@dataclass
class Param:
    text: str
    name: str | None  # None when the parameter is unnamed
    is_pointer: bool  # '*', an array (decays to a pointer) or a pointer typedef
    is_function: bool  # a function-pointer typedef such as nimbus_task_fn


@dataclass
class Decl:
    """One declaration: a struct member, or a file-scope function-pointer typedef."""

    text: str  # code only, comments removed, whitespace collapsed
    line: int
    end_line: int
    comments: list[Comment] = field(default_factory=list)  # directly above, inside, or trailing
    names: list[str] = field(default_factory=list)  # declarator names (several for `float a, b;`)
    pointer_names: list[str] = field(default_factory=list)  # those declared as pointers
    is_function_pointer: bool = False
    returns_pointer: bool = False
    params: list[Param] = field(default_factory=list)

    @property
    def comment_text(self) -> str:
        return "\n".join(c.text for c in self.comments)


@dataclass
class Struct:
    name: str  # the struct tag, e.g. nimbus_ray
    typedef: str | None  # e.g. nimbus_ray_t
    line: int
    header_comments: list[Comment]
    members: list[Decl]

    @property
    def header_text(self) -> str:
        return "\n".join(c.text for c in self.header_comments)


@dataclass
class Header:
    path: str
    structs: list[Struct]
    fn_typedefs: list[Decl]  # file-scope `typedef R (*name)(...)`
    prototypes: list[Decl]  # file-scope non-inline function declarations (the SDK has none today)
    comments: list[Comment]
    pointer_typedefs: set[str] = field(default_factory=set)  # `typedef struct x *x_handle;` and the like


def _tokenize(src: str, path: str):
    """Splits source into tokens: ('comment', Comment), ('pp', line) for a preprocessor line, ('nl', line),
    ('punct', char, line) for { } ;, and ('code', text, line) for the code between them."""
    tokens = []
    i, line, n = 0, 1, len(src)
    at_line_start = True

    def comment_end(i):
        end = src.find("*/", i + 2)
        if end < 0:
            raise HeaderError(f"{path}:{line}: unterminated comment")
        return end

    while i < n:
        c = src[i]
        if c == "\n":
            tokens.append(("nl", line))
            line += 1
            i += 1
            at_line_start = True
            continue
        if c in " \t\r\f\v":
            i += 1
            continue
        if at_line_start and c == "#":
            start = line
            while i < n and src[i] != "\n":
                if src[i] == "\\" and src[i + 1 : i + 2] == "\n":
                    line += 1
                    i += 2
                elif src.startswith("/*", i):  # a comment on a #define line belongs to the macro
                    end = comment_end(i)
                    line += src.count("\n", i, end)
                    i = end + 2
                else:
                    i += 1
            tokens.append(("pp", start))
            continue
        at_line_start = False
        if src.startswith("/*", i):
            end = comment_end(i)
            body = src[i + 2 : end]
            text = "\n".join(l.strip().lstrip("*").strip() for l in body.split("\n")).strip()
            tokens.append(("comment", Comment(line, line + body.count("\n"), text)))
            line += body.count("\n")
            i = end + 2
            continue
        if src.startswith("//", i):
            end = src.find("\n", i)
            end = n if end < 0 else end
            tokens.append(("comment", Comment(line, line, src[i + 2 : end].strip())))
            i = end
            continue
        if c in "{};":
            tokens.append(("punct", c, line))
            i += 1
            continue
        j = i + 1
        if c in "\"'":
            while j < n and src[j] != c:
                j += 2 if src[j] == "\\" else 1
            j += 1
        else:
            while j < n and src[j] not in "\n{};\"'" and not src.startswith("/*", j) and not src.startswith("//", j):
                j += 1
        tokens.append(("code", src[i:j], line))
        i = j
    return tokens


def _split_top(text: str, sep: str) -> list[str]:
    """Splits at `sep` outside (), [] and {}."""
    parts, depth, cur = [], 0, []
    for ch in text:
        if ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
        if ch == sep and depth == 0:
            parts.append("".join(cur))
            cur = []
        else:
            cur.append(ch)
    parts.append("".join(cur))
    return [p.strip() for p in parts]


FN_PTR = re.compile(r"^(?P<ret>.*?)\(\s*\*\s*(?P<name>[A-Za-z_]\w*)\s*\)\s*\((?P<params>.*)\)$", re.S)


def _parse_params(text: str, pointer_types: set[str], fn_types: set[str], where: str) -> list[Param]:
    text = text.strip()
    if text in ("", "void"):
        return []
    params = []
    for p in _split_top(text, ","):
        if "(" in p:
            raise HeaderError(f"{where}: inline function-pointer parameter '{p}': use a typedef")
        bare = re.sub(r"\[[^\]]*\]", "", p).strip()
        idents = IDENT.findall(bare)
        named = bool(idents) and bare.endswith(idents[-1]) and len(idents) >= 2
        # `const T *` and `T` alone are unnamed; `struct x *name` ends with the name.
        if named and idents[-1] in ("const", "volatile", "restrict"):
            named = False
        name = idents[-1] if named else None
        type_idents = set(idents[:-1] if named else idents)
        is_fn = bool(type_idents & fn_types) and "*" not in p
        is_ptr = "*" in p or "[" in p or bool(type_idents & pointer_types) or is_fn
        params.append(Param(p, name, is_ptr, is_fn))
    return params


def _analyse(decl: Decl, pointer_types: set[str], fn_types: set[str], where: str) -> None:
    text = decl.text
    m = FN_PTR.match(text)
    if m:
        decl.is_function_pointer = True
        decl.names = [m.group("name")]
        decl.returns_pointer = "*" in m.group("ret") or bool(set(IDENT.findall(m.group("ret"))) & pointer_types)
        decl.params = _parse_params(m.group("params"), pointer_types, fn_types, where)
        return
    if "(" in text:
        raise HeaderError(f"{where}: cannot read member '{text}'")
    if re.search(r"(?<![:\w]):(?!:)", text):
        raise HeaderError(f"{where}: bitfield '{text}' (sdk-idioms §1.1 forbids bitfields)")
    declarators = _split_top(text, ",")
    first_idents = IDENT.findall(re.sub(r"\[[^\]]*\]", "", declarators[0]))
    if len(first_idents) < 2:
        raise HeaderError(f"{where}: cannot read member '{text}'")
    base_type = set(first_idents[:-1])
    base_is_ptr = bool(base_type & pointer_types)
    decl.is_function_pointer = bool(base_type & fn_types) and "*" not in declarators[0]
    for i, d in enumerate(declarators):
        bare = re.sub(r"\[[^\]]*\]", "", d)
        idents = IDENT.findall(bare)
        if not idents:
            raise HeaderError(f"{where}: cannot read declarator '{d}'")
        name = idents[-1]
        decl.names.append(name)
        # In `const char *a, b` only `a` is a pointer; `*` binds to the declarator, not the type.
        star = ("*" in bare.split(name)[0]) if i == 0 else ("*" in d)
        if star or base_is_ptr:
            decl.pointer_names.append(name)


PROTO = re.compile(r"^(?P<ret>.*?\W)(?P<name>[A-Za-z_]\w*)\s*\((?P<params>.*)\)$", re.S)


def _analyse_prototype(decl: Decl, pointer_types: set[str], fn_types: set[str], where: str) -> None:
    """A file-scope function declaration is checked like a function-pointer member."""
    m = PROTO.match(decl.text)
    if not m:
        raise HeaderError(f"{where}: cannot read declaration '{decl.text}'")
    decl.is_function_pointer = True
    decl.names = [m.group("name")]
    decl.returns_pointer = "*" in m.group("ret") or bool(set(IDENT.findall(m.group("ret"))) & pointer_types)
    decl.params = _parse_params(m.group("params"), pointer_types, fn_types, where)


def parse_header(path: str, pointer_types=(), fn_types=()) -> Header:
    """`pointer_types`/`fn_types`: typedef names from other headers (see parse_headers)."""
    with open(path, encoding="utf-8") as f:
        src = f.read()
    return parse_source(src, path, pointer_types, fn_types)


def parse_headers(paths: list[str]) -> list[Header]:
    """Parses headers that use each other's typedefs: a first pass collects the pointer and
    function-pointer typedef names, the second reads every header knowing all of them."""
    first = [parse_header(p) for p in paths]
    ptr = set().union(*(h.pointer_typedefs for h in first)) if first else set()
    fns = set().union(*(set(d.names) for h in first for d in h.fn_typedefs)) if first else set()
    return [parse_header(p, ptr, fns) for p in paths]


def parse_source(src: str, path: str, known_pointer_types=(), known_fn_types=()) -> Header:
    tokens = _tokenize(src, path)
    pointer_types: set[str] = set(known_pointer_types)
    fn_types: set[str] = set(known_fn_types)
    header = Header(path, [], [], [], [t[1] for t in tokens if t[0] == "comment"])

    pending: list[Comment] = []  # the comment block directly above the next declaration
    pending_end = None
    cur: list[str] = []
    cur_line = cur_comments = None
    last_decl, last_decl_line = None, None  # receives trailing comments on its last line
    stack: list[Struct] = []  # open struct definitions; nesting is refused
    extern_depth = 0
    i = 0
    while i < len(tokens):
        tok = tokens[i]
        i += 1
        kind = tok[0]
        if kind == "nl":
            continue
        if kind == "pp":  # a #define between a comment and a declaration detaches the comment
            pending, pending_end = [], None
            last_decl = None
            continue
        if kind == "comment":
            c = tok[1]
            if not cur and last_decl is not None and c.line == last_decl_line:
                last_decl.comments.append(c)
            elif cur:
                cur_comments.append(c)
            else:
                if pending_end is not None and c.line > pending_end + 1:
                    pending = []
                pending.append(c)
                pending_end = c.end_line
            continue
        text, line = tok[1], tok[2]
        if not cur and kind == "code":
            if pending_end is None or line > pending_end + 1:
                pending = []
            cur_line, cur_comments = line, pending
            pending, pending_end, last_decl = [], None, None
        where = f"{path}:{cur_line if cur else line}"
        head = " ".join("".join(cur).split())
        if kind == "code":
            cur.append(text)
        elif text == "{":
            m = re.match(r"^(?:typedef\s+)?struct\s+([A-Za-z_]\w*)$", head)
            if m:
                if stack:
                    raise HeaderError(f"{where}: nested struct '{head}' is not supported")
                stack.append(Struct(m.group(1), None, cur_line, cur_comments, []))
            elif head == 'extern "C"' and not stack:
                extern_depth += 1
            elif "(" in head and not stack:
                # A function body (static inline helpers): compiled into the plugin, nothing crosses. Skip it.
                depth = 1
                while depth:
                    t = tokens[i]
                    i += 1
                    if t[0] == "punct" and t[1] in "{}":
                        depth += 1 if t[1] == "{" else -1
                if not head.startswith("static inline"):
                    proto = Decl(head, cur_line, line, cur_comments)
                    _analyse_prototype(proto, pointer_types, fn_types, where)
                    header.prototypes.append(proto)
            else:
                raise HeaderError(f"{where}: cannot read '{head} {{'")
            cur, last_decl = [], None
        elif text == "}":
            if head:
                raise HeaderError(f"{where}: unexpected '}}' after '{head}'")
            if stack:
                cur, cur_line, cur_comments = ["}"], line, []
            elif extern_depth:
                extern_depth -= 1
            else:
                raise HeaderError(f"{path}:{line}: unbalanced '}}'")
        else:  # ';'
            decl = Decl(head, cur_line, line, cur_comments)
            cur = []
            if head.startswith("}"):
                s = stack.pop()
                s.typedef = head[1:].strip() or None
                header.structs.append(s)
                continue
            last_decl, last_decl_line = decl, line
            if stack:
                _analyse(decl, pointer_types, fn_types, where)
                stack[-1].members.append(decl)
            elif head.startswith("typedef"):
                body = head[len("typedef") :].strip()
                m = FN_PTR.match(body)
                if m:
                    decl.text = body
                    _analyse(decl, pointer_types, fn_types, where)
                    fn_types.add(m.group("name"))
                    header.fn_typedefs.append(decl)
                elif "*" in body:
                    pointer_types.add(IDENT.findall(body)[-1])
                    header.pointer_typedefs.add(IDENT.findall(body)[-1])
            elif "(" in head and not head.startswith("static inline"):
                _analyse_prototype(decl, pointer_types, fn_types, where)
                header.prototypes.append(decl)
    if stack:
        raise HeaderError(f"{path}: struct {stack[-1].name} is not closed")
    return header
