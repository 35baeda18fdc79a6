#!/usr/bin/env python3
"""Checks that every crate's module graph is acyclic.

A module is a source file (`foo.rs`, `foo/mod.rs`, `lib.rs`, `main.rs`). An edge A -> B is a
path `crate::b::...` (or `super::...`, `self::...`) written in A that names module B or an item
in it. Edges are lifted to the children of the two modules' lowest common ancestor, so
"surface/torus.rs uses geometry::Ray" is the edge surface -> geometry; an edge between a module
and its own ancestor or descendant (a parent re-exporting a child, a child using its parent's
items) is not a layering edge and is ignored. A cycle among siblings is an error: the layers of
every directory must read top-down.

Usage: module_graph.py CRATE_SRC_DIR... (prints each crate's layers; exits 1 on a cycle)
"""
import os
import re
import sys

PATH_RE = re.compile(r"\b(crate|super|self)((?:::[A-Za-z_][A-Za-z0-9_]*)+)")
USE_GROUP_RE = re.compile(r"\buse\s+(crate|super|self)::\{([^;]*)\};", re.S)
COMMENT_RE = re.compile(r"//[^\n]*|/\*.*?\*/", re.S)
STRING_RE = re.compile(r'"(?:\\.|[^"\\])*"')


def modules(src):
    """Maps module path tuples to files, from the files under src."""
    mods = {}
    for root, _, files in os.walk(src):
        for f in files:
            if not f.endswith(".rs"):
                continue
            rel = os.path.relpath(os.path.join(root, f), src)
            parts = rel[:-3].split(os.sep)
            if parts[0] == "bin":
                continue
            if parts[-1] in ("mod", "lib", "main"):
                parts = parts[:-1]
            mods[tuple(parts)] = os.path.join(root, f)
    return mods


def resolve(mods, here, kind, segs):
    if kind == "crate":
        base = ()
    elif kind == "self":
        base = here
    else:
        base = here[:-1]
        while segs and segs[0] == "super":
            base = base[:-1]
            segs = segs[1:]
    path = base
    for s in segs:
        if path + (s,) in mods:
            path = path + (s,)
        else:
            break
    return path


def edges(mods):
    out = set()
    for here, f in mods.items():
        text = open(f, encoding="utf-8").read()
        text = STRING_RE.sub('""', COMMENT_RE.sub("", text))
        refs = []
        for m in USE_GROUP_RE.finditer(text):
            for item in re.split(r",", m.group(2)):
                item = item.strip().split("{")[0]
                if item:
                    refs.append((m.group(1), [s for s in item.split("::") if s]))
        for m in PATH_RE.finditer(text):
            refs.append((m.group(1), [s for s in m.group(2).split("::") if s]))
        for kind, segs in refs:
            there = resolve(mods, here, kind, segs)
            i = 0
            while i < len(here) and i < len(there) and here[i] == there[i]:
                i += 1
            if i == len(here) or i == len(there):
                continue  # ancestor or descendant
            out.add((here[: i + 1], there[: i + 1]))
    return out


def find_cycle(nodes, adj):
    colour = {n: 0 for n in nodes}
    stack = []

    def visit(n):
        colour[n] = 1
        stack.append(n)
        for m in sorted(adj.get(n, ())):
            if colour[m] == 1:
                return stack[stack.index(m):] + [m]
            if colour[m] == 0:
                c = visit(m)
                if c:
                    return c
        stack.pop()
        colour[n] = 2
        return None

    for n in sorted(nodes):
        if colour[n] == 0:
            c = visit(n)
            if c:
                return c
    return None


def main(dirs):
    bad = False
    for src in dirs:
        mods = modules(src)
        adj = {}
        for a, b in edges(mods):
            adj.setdefault(a, set()).add(b)
        name = "::".join
        cycle = find_cycle(set(mods) | set(adj), adj)
        while cycle:
            bad = True
            print(f"{src}: module cycle: " + " -> ".join(name(c) for c in cycle))
            # Report every cycle: cut the closing edge and look again.
            adj[cycle[-2]].discard(cycle[-1])
            cycle = find_cycle(set(mods) | set(adj), adj)
        if bad:
            pass
        else:
            print(f"{src}: acyclic ({len(mods)} modules, {sum(len(v) for v in adj.values())} edges)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
