#!/usr/bin/env python3
"""Finds import cycles of any length in every crate of the workspace, between files and
between folders, prints each, and exits 1 if there is one (0 otherwise).

Imports: a `use` or an inline path (`crate::a::b`, `super::x`, `self::y`) in a file's code.
Comments, string literals, macro-body paths (`$crate::..`) and test code (inline
`#[cfg(test)] mod .. { .. }` blocks and `#[cfg(test)] mod name;` files) are skipped; `mod`
declarations are not imports. Module paths are resolved to files: `crate::a::b` to
`src/a/b.rs` or `src/a/b/mod.rs` (the longest prefix that is a file), `super::` and `self::`
relative to the file's module, a leading name that is a child module (`use child::X`) to that
child. A name re-exported by a module (`pub use child::{A, B as C}` in a `mod.rs` or `lib.rs`)
resolves to the file that defines it: importing `crate::A` depends on the file of `A`, not on
the crate root, while the re-export itself is an import of the child by the root.

Two graphs are checked for strongly connected components (Tarjan's algorithm), so a cycle of
any length is found, not only a pair:

- files: `a -> b` when file `a` imports file `b`;
- folders: in every folder, its entries (the files and the subfolders, a subfolder standing
  for every file under it) with `X -> Y` when a file in `X` imports a file in `Y`. A cycle
  there (e.g. `commands/ <-> scale/`) is a loop between rooms even when no files form one.

Each component is printed with one cycle through it, naming the import behind every edge.

Usage: `python3 scripts/import_cycles.py [workspace root]` (default: this script's workspace).
"""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

PATH = re.compile(r"(?<![$\w])((?:crate|super|self)(?:::[A-Za-z_][A-Za-z0-9_]*)+)")
USE = re.compile(r"\buse\s+([^;]+);", re.S)
PUB_USE = re.compile(r"\bpub(?:\([a-z]+\))?\s+use\s+([^;]+);", re.S)
TEST_MODULE = re.compile(
    r"#\[cfg\(test\)\]\s*(?:pub(?:\([a-z]+\))?\s+)?mod\s+([A-Za-z_][A-Za-z0-9_]*)\s*([;{])"
)


def crate_roots(root):
    roots = [os.path.join(root, "src")]
    crates = os.path.join(root, "crates")
    for c in sorted(os.listdir(crates)) if os.path.isdir(crates) else []:
        roots.append(os.path.join(crates, c, "src"))
    return [r for r in roots if os.path.isdir(r)]


def module_of(src, path):
    rel = os.path.relpath(path, src)[:-3].split(os.sep)
    if rel[-1] in ("mod", "lib", "main"):
        rel = rel[:-1]
    return tuple(rel)


def strip_comments(text):
    text = re.sub(r"//[^\n]*", "", text)
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    text = re.sub(r'"(?:\\.|[^"\\])*"', '""', text)
    return re.sub(r"'(?:\\.|[^'\\])'", "' '", text)


def strip_tests(text):
    """`(code, declared)`: `text` without its inline `#[cfg(test)] mod name { .. }` blocks,
    and the names of the test modules it declares as files (`#[cfg(test)] mod name;`)."""
    out, declared, pos = [], set(), 0
    for m in TEST_MODULE.finditer(text):
        if m.start() < pos:
            continue
        if m.group(2) == ";":
            declared.add(m.group(1))
            continue
        depth, i = 1, m.end()
        while i < len(text) and depth:
            depth += {"{": 1, "}": -1}.get(text[i], 0)
            i += 1
        out.append(text[pos : m.start()])
        pos = i
    out.append(text[pos:])
    return "".join(out), declared


def normalise(use):
    """A `use` tree on one line, without spaces around `::`, braces and commas."""
    use = re.sub(r"\s+", " ", use).strip()
    return re.sub(r"\s*(::|\{|\}|,)\s*", r"\1", use)


def use_items(use):
    """`(path, name)` for every item of a normalised `use` tree: `a::{b,c::d as e}` gives
    `(a::b, b)` and `(a::c::d, e)`. Nested braces are flattened one level at a time."""
    if "{" not in use:
        path, _, alias = use.partition(" as ")
        last = path.split("::")[-1]
        return [] if last in ("*", "self") else [(path, alias or last)]
    prefix = use[: use.index("{")].rstrip(":")
    body = use[use.index("{") + 1 : use.rindex("}")]
    items, depth, start = [], 0, 0
    for i, ch in enumerate(body + ","):
        if ch == "{":
            depth += 1
        elif ch == "}":
            depth -= 1
        elif ch == "," and depth == 0:
            if body[start:i]:
                items.append(body[start:i])
            start = i + 1
    out = []
    for item in items:
        out += use_items("::".join(x for x in (prefix, item) if x))
    return out


def file_graph(src):
    """`(files, edges)`: module path -> file, and module -> set of imported modules."""
    files, texts, test_only = {}, {}, set()
    for d, _, fs in os.walk(src):
        for f in fs:
            if f.endswith(".rs"):
                p = os.path.join(d, f)
                files[module_of(src, p)] = p
    for m, p in files.items():
        with open(p, encoding="utf-8") as fh:
            texts[m], declared = strip_tests(strip_comments(fh.read()))
        test_only |= {m + (d,) for d in declared}
    for m in list(files):
        if any(m[:k] in test_only for k in range(1, len(m) + 1)):
            del files[m], texts[m]

    def locate(module, parts):
        """`(file, rest)`: the longest prefix of the path that is a file, the names after it."""
        parts = list(parts)
        base = list(module)
        if parts and parts[0] == "crate":
            base, parts = [], parts[1:]
        elif parts and parts[0] not in ("super", "self") and module + (parts[0],) not in files:
            return None  # another crate
        while parts and parts[0] in ("super", "self"):
            if parts[0] == "super":
                base = base[:-1]
            parts = parts[1:]
        best = None
        for k in range(len(parts) + 1):
            cand = tuple(base + parts[:k])
            if cand in files:
                best = (cand, parts[k:])
        return best

    # `pub use` re-exports: name -> (file, rest of the path) of the item
    exports = {m: {} for m in files}
    for m in files:
        for use in PUB_USE.findall(texts[m]):
            for path, name in use_items(normalise(use)):
                found = locate(m, path.split("::"))
                if found is not None and found[0] != m:
                    exports[m][name] = found

    def resolve(module, parts):
        found = locate(module, parts)
        for _ in range(16):  # follow chains of re-exports
            if found is None or not found[1] or found[1][0] not in exports[found[0]]:
                break
            target, rest = exports[found[0]][found[1][0]]
            found = (target, rest + found[1][1:])
        return None if found is None else found[0]

    edges = {}
    for m in files:
        text = texts[m]
        targets = {resolve(m, expr.split("::")) for expr in PATH.findall(text)}
        for use in USE.findall(text):
            for path, _ in use_items(normalise(use)):
                targets.add(resolve(m, path.split("::")))
            # `use a::{self, ..}` and globs: the module itself
            head = normalise(use).split("{")[0].rstrip(":").removesuffix("::*")
            if head:
                targets.add(resolve(m, head.split("::")))
        edges[m] = {t for t in targets if t is not None and t != m}
    return files, edges


def strongly_connected(nodes, edges):
    """Tarjan's algorithm (iterative): the components of more than one node, each sorted."""
    index, low, on_stack, stack, out = {}, {}, set(), [], []
    for start in sorted(nodes):
        if start in index:
            continue
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        work = [(start, iter(sorted(edges.get(start, ()))))]
        while work:
            v, successors = work[-1]
            descended = False
            for w in successors:
                if w not in index:
                    index[w] = low[w] = len(index)
                    stack.append(w)
                    on_stack.add(w)
                    work.append((w, iter(sorted(edges.get(w, ())))))
                    descended = True
                    break
                if w in on_stack:
                    low[v] = min(low[v], index[w])
            if descended:
                continue
            work.pop()
            if work:
                parent = work[-1][0]
                low[parent] = min(low[parent], low[v])
            if low[v] == index[v]:
                component = []
                while True:
                    w = stack.pop()
                    on_stack.discard(w)
                    component.append(w)
                    if w == v:
                        break
                if len(component) > 1:
                    out.append(sorted(component))
    return sorted(out)


def cycle_through(component, edges):
    """A shortest cycle through the component's first node (breadth-first), start repeated."""
    members, start = set(component), component[0]
    parent, queue = {start: None}, [start]
    while queue:
        v = queue.pop(0)
        for w in sorted(edges.get(v, ())):
            if w == start:
                path = [v]
                while parent[path[-1]] is not None:
                    path.append(parent[path[-1]])
                return list(reversed(path)) + [start]
            if w in members and w not in parent:
                parent[w] = v
                queue.append(w)
    raise AssertionError("a strongly connected component has a cycle through every node")


def folder_of(files, m):
    """The folder (module path) a file lies in: its own for `mod.rs` / `lib.rs`."""
    name = os.path.basename(files[m])
    return m if name in ("mod.rs", "lib.rs", "main.rs") else m[:-1]


def folder_graphs(files, edges):
    """`{folder: {x: {y: (a, b)}}}`: for every folder, the edges between its entries (`x`, `y`
    names of files or subfolders, `mod` for its own `mod.rs`/`lib.rs`), each with one file
    import `a -> b` that makes it."""
    def entry(m, folder):
        k = len(folder)
        own = folder_of(files, m) == m
        return "mod" if own and m == folder else m[k]

    graphs = {}
    for a, targets in edges.items():
        for b in targets:
            fa, fb = folder_of(files, a), folder_of(files, b)
            k = 0
            while k < min(len(fa), len(fb)) and fa[k] == fb[k]:
                k += 1
            # every folder from the common one down that holds both a and b
            for depth in range(k + 1):
                folder = fa[:depth]
                x, y = entry(a, folder), entry(b, folder)
                if x != y:
                    graphs.setdefault(folder, {}).setdefault(x, {}).setdefault(y, (a, b))
    return graphs


def entry_name(src, folder, entry):
    if entry == "mod":
        return "lib.rs" if not folder else "mod.rs"
    return entry + "/" if os.path.isdir(os.path.join(src, *folder, entry)) else entry + ".rs"


def check(root):
    """Prints every cycle of the workspace at `root`; returns how many components it found."""
    found = 0
    for src in crate_roots(root):
        files, edges = file_graph(src)

        def rel(m):
            return os.path.relpath(files[m], root)

        for comp in strongly_connected(files, edges):
            found += 1
            print(f"files: {len(comp)} form a cycle: " + ", ".join(rel(m) for m in comp))
            print("  " + " -> ".join(rel(m) for m in cycle_through(comp, edges)))
        for folder, graph in sorted(folder_graphs(files, edges).items()):
            simple = {x: set(ys) for x, ys in graph.items()}
            for comp in strongly_connected(set(graph), simple):
                found += 1
                where = os.path.relpath(os.path.join(src, *folder), root)
                names = [entry_name(src, folder, e) for e in comp]
                print(f"folders: in {where}/ the entries " + ", ".join(names) + " form a cycle")
                cycle = cycle_through(comp, simple)
                for x, y in zip(cycle, cycle[1:]):
                    a, b = graph[x][y]
                    print(f"  {entry_name(src, folder, x)} -> {entry_name(src, folder, y)}:"
                          f" {rel(a)} imports {rel(b)}")
    return found


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else ROOT
    found = check(root)
    print(f"{found} import cycles (strongly connected components of files or of folders)")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
