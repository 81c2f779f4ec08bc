"""Import circles between the files of a Rust crate: which files import each other, directly or
through others (strongly connected components of the file-level import graph).

    python3 scripts/import_cycles.py CRATE_SRC_DIR...

A file's module is its path (`a/b.rs` and `a/b/mod.rs` are `a::b`; `lib.rs` and `mod.rs` at the
top are the root). An import is any path that starts with `crate::`, `super::` or `self::` in
the code (comments and `#[cfg(test)]` modules left out: a test may reach anywhere), braces
included (`use super::{a::X, b::Y}`); it points at the longest prefix of the path that is a
file. Exits 1 and lists each circle if there is one."""
from __future__ import annotations

import re
import sys
from pathlib import Path

PATH = re.compile(r"\b(crate|super|self)((?:::(?:[A-Za-z_][A-Za-z0-9_]*|\{[^{}]*\}))+)")


def modules(src: Path) -> dict[tuple[str, ...], Path]:
    out = {}
    for p in src.rglob("*.rs"):
        parts = list(p.relative_to(src).with_suffix("").parts)
        if parts[-1] in ("mod", "lib") and (parts[-1] == "mod" or len(parts) == 1):
            parts = parts[:-1]
        out[tuple(parts)] = p
    return out


def code_of(p: Path) -> str:
    text = re.sub(r"//[^\n]*", "", p.read_text())
    cut = text.find("#[cfg(test)]")
    return text if cut < 0 else text[:cut]


def expand(segments: str) -> list[list[str]]:
    """`::a::{b::C, d}` → [[a, b, C], [a, d]] (one level of braces)."""
    head, _, group = segments.partition("::{")
    base = [s for s in head.split("::") if s]
    if not group:
        return [base]
    return [base + [s for s in item.strip().split("::") if s] for item in group.rstrip("}").split(",")
            if item.strip()]


def imports(mod: tuple[str, ...], p: Path, files: dict) -> set[tuple[str, ...]]:
    found = set()
    for m in PATH.finditer(code_of(p)):
        kind = m.group(1)
        for path in expand(m.group(2)):
            if kind == "crate":
                base = []
            elif kind == "self":
                base = list(mod)
            else:
                base = list(mod[:-1])
                while path and path[0] == "super":
                    base, path = base[:-1], path[1:]
            full = base + path
            for k in range(len(full), 0, -1):
                if tuple(full[:k]) in files:
                    if tuple(full[:k]) != mod:
                        found.add(tuple(full[:k]))
                    break
    return found


def circles(src: Path) -> list[list[tuple[str, ...]]]:
    files = modules(src)
    edges = {m: imports(m, p, files) for m, p in files.items()}
    index, low, stack, on, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in edges[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in files:
        if v not in index:
            visit(v)
    return out


def main(argv: list[str]) -> int:
    bad = 0
    for src in map(Path, argv):
        for comp in circles(src):
            bad += 1
            print(f"{src}: " + " ↔ ".join("::".join(m) or "<root>" for m in comp))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
