#!/usr/bin/env python3
"""Self-test of scripts/import_cycles.py on small synthetic workspaces: a three-file cycle
(which a pair check misses), a loop between two folders with no file cycle, a `pub use`
re-export that must not count as an import of the crate root, test-only modules that are
skipped, and a clean tree. Exits 1 on the first wrong count."""
import contextlib
import importlib.util
import io
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
spec = importlib.util.spec_from_file_location("import_cycles", os.path.join(HERE, "import_cycles.py"))
checker = importlib.util.module_from_spec(spec)
spec.loader.exec_module(checker)


def count(files):
    """Cycles `check` finds in a workspace with the given `{path: text}` files."""
    with tempfile.TemporaryDirectory() as root:
        for path, text in files.items():
            full = os.path.join(root, path)
            os.makedirs(os.path.dirname(full), exist_ok=True)
            with open(full, "w", encoding="utf-8") as fh:
                fh.write(text)
        with contextlib.redirect_stdout(io.StringIO()):
            return checker.check(root)


CASES = [
    (
        "three files in a ring (no pair imports each other)",
        {
            "crates/a/src/lib.rs": "mod x; mod y; mod z;",
            "crates/a/src/x.rs": "use crate::y::Y; pub struct X;",
            "crates/a/src/y.rs": "use crate::z::Z; pub struct Y;",
            "crates/a/src/z.rs": "use crate::x::X; pub struct Z;",
        },
        # the file ring, and the same ring between the crate root's entries
        2,
    ),
    (
        "two folders importing each other through different files",
        {
            "src/lib.rs": "mod p; mod q;",
            "src/p/mod.rs": "mod a; mod b;",
            "src/p/a.rs": "use crate::q::c::C; pub struct A;",
            "src/p/b.rs": "pub struct B;",
            "src/q/mod.rs": "pub mod c; mod d;",
            "src/q/c.rs": "pub struct C;",
            "src/q/d.rs": "use crate::p::b::B; pub struct D;",
        },
        1,
    ),
    (
        "a re-export at the root and a child using the item through it",
        {
            "src/lib.rs": "mod a; mod b; pub use a::A;",
            "src/a.rs": "pub struct A;",
            "src/b.rs": "use crate::A; pub struct B(A);",
        },
        0,
    ),
    (
        "a child importing its parent's glob while the parent re-exports the child",
        {
            "src/lib.rs": "mod s;",
            "src/s/mod.rs": "mod k; pub use k::K; pub struct S;",
            "src/s/k.rs": "use super::*; pub struct K(S);",
        },
        # files s/mod.rs <-> s/k.rs, and the same pair as entries of s/
        2,
    ),
    (
        "test code is not an import",
        {
            "src/lib.rs": "mod a; mod b;",
            "src/a.rs": "pub struct A;\n#[cfg(test)]\nmod tests { use crate::b::B; }",
            "src/b.rs": "use crate::a::A; pub struct B;",
        },
        0,
    ),
]


def main():
    failed = 0
    for name, files, expected in CASES:
        found = count(files)
        status = "ok" if found == expected else "FAILED"
        print(f"{status}: {name}: {found} cycles (expected {expected})")
        failed += found != expected
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
