"""Import cycles among the modules of a Rust crate: prints the module graph's cycles
(strongly connected components of more than one module) and exits 1 when there is one.

A module is a file under SRC (`core/model.rs` is `core::model`, `core/mod.rs` is
`core`); it imports the modules that its `crate::`, `super::` and `self::` paths name
(`use` lines, grouped `use super::{a, b}` and paths in code alike), nearest enclosing
module first. Imports of a module's own parent or children are not edges (Rust
resolves them through the module tree, not as a dependency between siblings).

Usage: python3 scripts/module_cycles.py [SRC]   (default: crates/fmu/fmi/src)
"""

import re
import sys
from pathlib import Path

PATH = re.compile(r"\b((?:crate|super|self)(?:::\w+)+)")
GROUP = re.compile(r"\b((?:crate|super|self)(?:::\w+)*)::\{([^}]*)\}")


def modules(src: Path) -> dict[str, Path]:
    """Module path -> file."""
    out = {}
    for f in sorted(src.rglob("*.rs")):
        parts = list(f.relative_to(src).with_suffix("").parts)
        if parts[-1] in ("mod", "lib", "main"):
            parts = parts[:-1]
        out["::".join(parts)] = f
    return out


def resolve(known, current: str, path: str) -> str | None:
    """The longest known module a path from `current` names, if any."""
    segments = path.split("::")
    base = current.split("::") if current else []
    head = segments.pop(0)
    if head == "crate":
        base = []
    elif head == "super":
        base = base[:-1]
        while segments and segments[0] == "super":
            base, segments = base[:-1], segments[1:]
    for k in range(len(segments), 0, -1):
        candidate = "::".join(base + segments[:k])
        if candidate in known:
            return candidate
    return None


def edges(known: dict[str, Path]) -> dict[str, set[str]]:
    graph = {m: set() for m in known}
    for m, f in known.items():
        text = re.sub(r"//[^\n]*", "", f.read_text())
        paths = [p.group(1) for p in PATH.finditer(text)]
        for group in GROUP.finditer(text):
            paths += [f"{group.group(1)}::{item.strip().split('::')[0].split(' ')[0]}"
                      for item in group.group(2).split(",") if item.strip()]
        for p in paths:
            t = resolve(known, m, p)
            related = t is None or t == m or m.startswith(t + "::") or t.startswith(m + "::")
            if not related:
                graph[m].add(t)
    return graph


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components of more than one module (Tarjan)."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while not component or component[-1] != v:
                component.append(stack.pop())
                on_stack.discard(component[-1])
            if len(component) > 1:
                found.append(sorted(component))

    sys.setrecursionlimit(max(1000, 4 * len(graph)))
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def main() -> int:
    src = Path(sys.argv[1] if len(sys.argv) > 1 else "crates/fmu/fmi/src")
    graph = edges(modules(src))
    found = cycles(graph)
    n_edges = sum(len(e) for e in graph.values())
    print(f"{src}: {len(graph)} modules, {n_edges} imports, {len(found)} cycles")
    for component in found:
        print("  cycle: " + ", ".join(component))
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
