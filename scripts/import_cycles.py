#!/usr/bin/env python3
"""Lists pairs of source files that import each other (a `use` or an inline path in both
directions), in every crate of the workspace. Exit code 1 if there is one.

Module paths are resolved to files: `crate::a::b` to `src/a/b.rs` or `src/a/b/mod.rs` (the
longest prefix that is a file), `super::` and `self::` relative to the file's module, a
leading name that is a child module (`use child::X`) to that child. `mod` declarations are
not imports.
"""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def crate_roots():
    roots = [os.path.join(ROOT, "src")]
    for c in sorted(os.listdir(os.path.join(ROOT, "crates"))):
        src = os.path.join(ROOT, "crates", c, "src")
        if os.path.isdir(src):
            roots.append(src)
    return roots


def module_of(src, path):
    rel = os.path.relpath(path, src)[:-3].split(os.sep)
    if rel[-1] in ("mod", "lib", "main"):
        rel = rel[:-1]
    return tuple(rel)


PATH = re.compile(r"\b((?:crate|super|self)(?:::[A-Za-z_][A-Za-z0-9_]*)+)")
USE = re.compile(r"\buse\s+([^;]+);", re.S)


def strip_comments(text):
    text = re.sub(r"//[^\n]*", "", text)
    return re.sub(r'"(?:\\.|[^"\\])*"', '""', text)


def main():
    cycles = []
    for src in crate_roots():
        files = {}
        for d, _, fs in os.walk(src):
            for f in fs:
                if f.endswith(".rs"):
                    p = os.path.join(d, f)
                    files[module_of(src, p)] = p
        edges = {m: set() for m in files}

        def resolve(module, parts):
            parts = list(parts)
            base = list(module)
            if parts and parts[0] == "crate":
                base, parts = [], parts[1:]
            while parts and parts[0] in ("super", "self"):
                if parts[0] == "super":
                    base = base[:-1]
                parts = parts[1:]
            best = None
            for k in range(len(parts) + 1):
                cand = tuple(base + parts[:k])
                if cand in files:
                    best = cand
            return best

        for m, p in files.items():
            text = strip_comments(open(p, encoding="utf-8").read())
            targets = set()
            for expr in PATH.findall(text):
                targets.add(resolve(m, expr.split("::")))
            for use in USE.findall(text):
                use = re.sub(r"\s+", "", use)
                head = re.split(r"::|\{", use)[0]
                if head not in ("crate", "super", "self") and tuple(list(m) + [head]) in files:
                    targets.add(tuple(list(m) + [head]))
                # groups: crate::a::{b, c::d}
                prefix = use.split("{")[0].rstrip(":")
                for inner in re.findall(r"\{([^{}]*)\}", use):
                    for item in inner.split(","):
                        item = item.strip().split(" as ")[0]
                        if item and prefix:
                            targets.add(resolve(m, (prefix + "::" + item).split("::")))
            for t in targets:
                if t is not None and t != m:
                    edges[m].add(t)
        for a in edges:
            for b in edges[a]:
                if a < b and a in edges.get(b, ()):
                    cycles.append((files[a], files[b]))
    for a, b in cycles:
        print(os.path.relpath(a, ROOT), "<->", os.path.relpath(b, ROOT))
    print(f"{len(cycles)} pairs of files import each other")
    return 1 if cycles else 0


if __name__ == "__main__":
    sys.exit(main())
