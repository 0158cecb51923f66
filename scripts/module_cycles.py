#!/usr/bin/env python3
"""Finds circular imports between the files of each crate's `src/`.

Reads every `crate::`, `super::` and `self::` path of each file (comments
and the inline `#[cfg(test)] mod tests` block skipped, brace imports
expanded), resolves it to the file of the module it names, and looks for
strongly connected components of that graph (Tarjan's algorithm). A module
naming its own ancestor (a parent's re-exports) is not counted, since the
parent declares the child. Prints one line per crate and exits with 1 if
any crate has a cycle.

Usage: python3 scripts/module_cycles.py crates/*/src
"""

import os
import re
import sys

PATH = re.compile(r"\b((?:crate|super|self)(?:::\w+)+)")
BRACES = re.compile(r"\b((?:crate|super|self)(?:::\w+)*)::\{([^}]*)\}")
TESTS = re.compile(r"#\[cfg\(test\)\]\s*mod tests\s*\{.*", re.S)


def modules(src):
    """Module path (`a::b`, `` for the crate root) → file."""
    found = {}
    for root, _, names in os.walk(src):
        for name in names:
            if not name.endswith(".rs"):
                continue
            path = os.path.join(root, name)
            parts = os.path.relpath(path, src)[:-3].split(os.sep)
            if parts[-1] in ("mod", "lib", "main"):
                parts = parts[:-1]
            found["::".join(parts)] = path
    return found


def resolve(files, module, path):
    """The longest module prefix of `path` as seen from `module`."""
    segs = path.split("::")
    if segs[0] == "crate":
        cur, segs = [], segs[1:]
    else:
        cur = module.split("::") if module else []
        while segs and segs[0] in ("super", "self"):
            if segs[0] == "super":
                cur = cur[:-1]
            segs = segs[1:]
    for i in range(len(segs), -1, -1):
        candidate = "::".join(cur + segs[:i])
        if candidate in files:
            return candidate
    return None


def imports(files, module, text):
    text = TESTS.sub("", text)
    text = "\n".join(l for l in text.split("\n") if not l.strip().startswith("//"))
    paths = [m.group(1) for m in PATH.finditer(text)]
    for m in BRACES.finditer(text):
        for item in m.group(2).split(","):
            head = item.strip().split("::")[0].split(" ")[0]
            if head:
                paths.append(m.group(1) + "::" + head)
    targets = set()
    for p in paths:
        t = resolve(files, module, p)
        # The crate root and a module's own ancestors declare it: not imports.
        if t is None or t == module or t == "" or module.startswith(t + "::"):
            continue
        targets.add(t)
    return targets


def cycles(edges):
    index, low, stack, on, found = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    sys.setrecursionlimit(10_000)
    for v in edges:
        if v not in index:
            visit(v)
    return found


def main(sources):
    bad = False
    for src in sources:
        files = modules(src)
        edges = {m: imports(files, m, open(p, encoding="utf-8").read()) for m, p in files.items()}
        found = cycles(edges)
        count = sum(len(e) for e in edges.values())
        print(f"{src}: {len(files)} files, {count} imports between them, cycles: {found or 'none'}")
        bad |= bool(found)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
