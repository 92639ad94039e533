#!/usr/bin/env python3
"""Reads capstan's VTU files with meshio and checks them against what the writer was given.

Usage: check_vtu.py EXPECTED.json

EXPECTED.json lists cases, each with:
  path         the .vtu file
  points       [[x, y, z], ...] as passed to the writer
  n2, n3, periodic
  cells        expected quad connectivity [[p0, p1, p2, p3], ...]
  point_data   {name: {"components": c, "values": [...]}}
  cell_data    {name: {"components": c, "values": [...]}}
  time         TimeValue or null
  ellipse      optional {"a": a, "b": b, "x3": [...]}: the body sits on sigma = (x1, a sin t, b cos t)
  atol         optional absolute tolerance for point_data values (default 0: exact)
  point_shapes optional {name: components}: further point arrays checked for shape and
               finiteness only (for fields the test cannot recompute, e.g. stress)

Values must match exactly unless `atol` is given: both encodings (ASCII shortest round-trip,
raw binary) are lossless.
Exits non-zero with a message on the first mismatch.
"""
import json
import sys

import meshio
import numpy as np


def fail(case, message):
    sys.exit(f"{case['path']}: {message}")


def check_arrays(case, kind, got, expected, tuples, shapes=None, atol=0.0):
    shapes = shapes or {}
    if set(got) != set(expected) | set(shapes):
        fail(case, f"{kind} names {sorted(got)} != {sorted(set(expected) | set(shapes))}")
    for name, c in shapes.items():
        shape = (tuples,) if c == 1 else (tuples, c)
        have = np.asarray(got[name])
        if have.shape != shape:
            fail(case, f"{kind} {name}: shape {have.shape}, expected {shape}")
        if not np.all(np.isfinite(have)):
            fail(case, f"{kind} {name}: non-finite values")
    for name, spec in expected.items():
        c = spec["components"]
        want = np.array(spec["values"], dtype=np.float64)
        shape = (tuples,) if c == 1 else (tuples, c)
        want = want.reshape(shape)
        have = np.asarray(got[name])
        if have.dtype != np.float64:
            fail(case, f"{kind} {name}: dtype {have.dtype}, expected float64")
        if have.shape != shape:
            fail(case, f"{kind} {name}: shape {have.shape}, expected {shape}")
        if atol == 0.0:
            same = np.array_equal(have, want)
        else:
            same = np.allclose(have, want, rtol=0.0, atol=atol)
        if not same:
            fail(case, f"{kind} {name}: values differ, max |diff| {np.abs(have - want).max()}")


def check(case):
    mesh = meshio.read(case["path"])
    n2, n3 = case["n2"], case["n3"]
    points = np.array(case["points"], dtype=np.float64)
    if mesh.points.shape != (n2 * n3, 3):
        fail(case, f"points shape {mesh.points.shape}, expected {(n2 * n3, 3)}")
    if not np.array_equal(mesh.points, points):
        fail(case, "points differ")

    if len(mesh.cells) != 1 or mesh.cells[0].type != "quad":
        fail(case, f"cell blocks {[c.type for c in mesh.cells]}, expected one 'quad' block")
    quads = mesh.cells[0].data
    n_cells = (n2 if case["periodic"] else n2 - 1) * (n3 - 1)
    if quads.shape != (n_cells, 4):
        fail(case, f"cells shape {quads.shape}, expected {(n_cells, 4)}")
    if not np.array_equal(quads, np.array(case["cells"])):
        fail(case, "connectivity differs")

    check_arrays(
        case,
        "point data",
        mesh.point_data,
        case["point_data"],
        n2 * n3,
        case.get("point_shapes"),
        case.get("atol", 0.0),
    )
    cell_data = {name: blocks[0] for name, blocks in mesh.cell_data.items()}
    check_arrays(case, "cell data", cell_data, case["cell_data"], n_cells)

    if case["time"] is None:
        if "TimeValue" in mesh.field_data:
            fail(case, "unexpected TimeValue")
    else:
        t = np.asarray(mesh.field_data.get("TimeValue"))
        if t.shape != (1,) or t[0] != case["time"]:
            fail(case, f"TimeValue {t}, expected [{case['time']}]")

    if "ellipse" in case:
        # Independent of the writer: the inner face lies on the ellipse, each x3 line leaves it
        # along the normal, at distance x3, and every quad is non-degenerate in E^3.
        a, b, x3 = case["ellipse"]["a"], case["ellipse"]["b"], case["ellipse"]["x3"]
        p = mesh.points.reshape(n2, n3, 3)
        on = (p[:, 0, 1] / a) ** 2 + (p[:, 0, 2] / b) ** 2
        if not np.allclose(on, 1.0, rtol=0, atol=1e-12):
            fail(case, f"inner face off the ellipse by {np.abs(on - 1).max()}")
        d = np.linalg.norm(p - p[:, :1, :], axis=2)
        if not np.allclose(d, np.array(x3)[None, :], rtol=0, atol=1e-12):
            fail(case, "x3 lines are not at distance x3 from the surface")
        q = mesh.points[quads]
        area = np.linalg.norm(np.cross(q[:, 1] - q[:, 0], q[:, 3] - q[:, 0]), axis=1)
        if area.min() <= 0:
            fail(case, "degenerate quad")


def main():
    with open(sys.argv[1]) as f:
        cases = json.load(f)
    for case in cases:
        check(case)
    print(f"check_vtu: {len(cases)} files read back by meshio {meshio.__version__}")


if __name__ == "__main__":
    main()
