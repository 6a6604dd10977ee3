#!/usr/bin/env python3
"""Fail when files under src/ import each other in a circle.

A file imports another when it names an item of the other's module through `crate::`,
`super::` or `self::` (in a `use` or inline). An item a `mod.rs` re-exports from one of its
modules counts as the module's own. A module's `mod.rs` (or `lib.rs`) declaring and
re-exporting its own modules is not an import: a room's front door may point inside it.
Test files (`tests.rs`, `tests/`) and the generated bindings are left out.

Usage: scripts/import_circles.py [SRC_DIR]   (exit 1 and one line a circle when any)
"""
import os
import re
import sys

SRC = sys.argv[1] if len(sys.argv) > 1 else "src"


def module_of(path):
    """src/a/b.rs -> ['a', 'b']; src/a/mod.rs -> ['a']; src/lib.rs -> []."""
    rel = os.path.relpath(path, SRC)[:-3].split(os.sep)
    if rel[-1] in ("mod", "lib"):
        rel = rel[:-1]
    return rel


files = {}
for root, dirs, names in os.walk(SRC):
    if os.path.relpath(root, SRC).split(os.sep)[0] == "bin":
        continue  # binaries are crates of their own, above the library
    dirs[:] = [d for d in dirs if d != "tests"]
    for n in names:
        if n.endswith(".rs") and n not in ("tests.rs", "ffi.rs"):
            p = os.path.join(root, n)
            files[tuple(module_of(p))] = p


def strip(text):
    text = re.sub(r"//[^\n]*", "", text)
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    text = re.sub(r'"(\\.|[^"\\])*"', '""', text)
    # inline test modules
    m = re.search(r"#\[cfg\(test\)\]\s*mod\s+\w+\s*\{", text)
    return text[: m.start()] if m else text


def expand(tree):
    """'a::{b, c::{d, e}}' -> ['a::b', 'a::c::d', 'a::c::e']."""
    tree = re.sub(r"\s+", "", tree)
    m = re.match(r"^(.*?)\{(.*)\}$", tree)
    if not m:
        return [tree]
    head, body = m.group(1), m.group(2)
    parts, depth, cur = [], 0, ""
    for ch in body:
        if ch == "," and depth == 0:
            parts.append(cur)
            cur = ""
            continue
        depth += ch == "{"
        depth -= ch == "}"
        cur += ch
    parts.append(cur)
    return [x for p in parts if p for x in expand(head + p)]


reexports = {}  # module -> {name: child module}
for mod, path in files.items():
    text = strip(open(path).read())
    table = {}
    for tree in re.findall(r"\bpub(?:\([^)]*\))?\s+use\s+([^;]+);", text):
        for item in expand(tree):
            segs = [s.split(" as ")[0] for s in item.replace("self::", "").split("::")]
            if segs and segs[0] not in ("crate", "super", "std") and len(segs) >= 2:
                table[segs[-1]] = list(mod) + segs[:-1]
    reexports[mod] = table


def resolve(mod, segs):
    """The file a path names: its longest module prefix, through one mod.rs re-export."""
    if segs[0] == "crate":
        base, rest = [], segs[1:]
    else:
        base = list(mod)
        rest = segs
        while rest and rest[0] in ("super", "self"):
            if rest[0] == "super":
                base = base[:-1]
            rest = rest[1:]
    full = base + rest
    for k in range(len(full), -1, -1):
        target = tuple(full[:k])
        if target in files:
            name = full[k] if k < len(full) else None
            via = reexports.get(target, {}).get(name) if name else None
            if via:
                for j in range(len(via), len(target), -1):
                    if tuple(via[:j]) in files:
                        return tuple(via[:j])
            return target
    return None


edges = {m: set() for m in files}
for mod, path in files.items():
    text = strip(open(path).read())
    paths = []
    for tree in re.findall(r"\buse\s+((?:crate|super|self)::[^;]+);", text):
        paths += expand(tree)
    paths += re.findall(r"(?<![\w:])((?:crate|super)(?:::\w+)+)", text)
    for p in paths:
        segs = [s.split(" as ")[0].strip() for s in p.split("::")]
        segs = [s for s in segs if s and s != "*"]
        target = resolve(mod, segs)
        if target is None or target == mod:
            continue
        if target[: len(mod)] == mod and os.path.basename(path) in ("mod.rs", "lib.rs"):
            continue  # a room's front door pointing inside it
        edges[mod].add(target)

# Tarjan's strongly connected components.
index, low, stack, on, comps, counter = {}, {}, [], set(), [], [0]
sys.setrecursionlimit(10000)


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
        comp = []
        while True:
            w = stack.pop()
            on.discard(w)
            comp.append(w)
            if w == v:
                break
        if len(comp) > 1:
            comps.append(comp)


for v in sorted(edges):
    if v not in index:
        visit(v)
for comp in comps:
    names = sorted(files[m] for m in comp)
    ties = [f"{files[a]} -> {files[b]}" for a in comp for b in sorted(edges[a]) if b in comp]
    print("import circle: " + ", ".join(names) + "  (" + "; ".join(ties) + ")")
if comps:
    sys.exit(1)
print(f"no import circles among {len(files)} files under {SRC}")
