#!/usr/bin/env python3
"""Peer benchmark: the paper's linear stand-in of capstan (problem `paper`) solved with NGSolve
on curved triangles geometrically refined toward the four singular corners.

Problem (capstan's `PaperEllipse`, `capstan bench work-precision` problem `paper`): the half
annulus 2 <= r <= 3, y >= 0 (the body over the circle a = b = 2, h = 1, x2 in [-pi/2, pi/2];
capstan's chart point (a sin x2, b cos x2) is (x, y) here), plane strain, E = 1e3, nu = 1/4;
clamped on r = 2 (the contact face, u = 0), free on r = 3; on the two ends (y = 0) the hoop
stress T^2_2 = tau and no shear, i.e. the traction (0, -tau): tau0 = 1 on x < 0 (x2 = -pi/2),
tau_max = 2 on x > 0 (x2 = pi/2). The four corners where the ends meet r = 2 and r = 3 are
singular.

Mesh (what an NGSolve user does for corner singularities): netgen.geom2d `SplineGeometry`, the
arcs as rational quadratic splines (exact circles), the four corners appended with
`hpref=1` and, for level m > 0, the local mesh size `corner_maxh / m` (default 0.5 / m);
unstructured triangles with `maxh` elsewhere (default 0.5 = h/2), then `mesh.RefineHP(m,
factor)` (m geometric layers toward the marked corners, default factor 0.125, NGSolve's
default), then `mesh.Curve(p)`. Level 0 is the plain maxh mesh. (RefineHP alone leaves the
elements next to the refined corner patches at size maxh, where the corner functions are
still far from smooth: at maxh = 0.5 the error stops near 7e-5 for p = 6 whatever the
levels; the local corner size lets it fall to ~4e-6 at p = 6 and ~2e-7 at p = 8 by m = 8 to
12.) Space `VectorH1(order=p,
dirichlet="contact")`; form 2 mu eps(u):eps(v) + lambda div u div v; static condensation;
`a.mat.Inverse(freedofs, inverse=sparsecholesky|umfpack)`.

One thread, timing, repeats and peak memory exactly as ngsolve_lame.py (meshing, RefineHP and
Curve not timed: `mesh_seconds`, `curve_seconds`).

Error: capstan measures the `paper` rows against its graded fem-qp10 reference, integrated by
Gauss quadrature over each run's own elements with the reference evaluated at the quadrature
points. The peer does the same with the roles kept: with `--error-points DIR` it writes, per
level, the quadrature points of its own curved elements (`IntegrationRule` of order 2p + 4 per
element, mapped by `MapToAllElements`), their weights (rule weight x |det J| of the curved
element map) and its solution there, as little-endian f64 rows (x, y, w, u_x, u_y) in
`DIR/ngsolve-pP-mM.f64`, named in the output's `error_points`; capstan maps each point back to
(x2, x3), evaluates the reference there and forms ||u_h - u_ref|| / ||u_ref|| with these
weights (src/commands/bench/peer_error.rs). Without `--error-points` the `error` is null.

Usage:
  .venv/bin/python bench/peers/ngsolve_paper.py --order 6 --levels 2,4,6,8
      [--inverse sparsecholesky] [--maxh 0.5] [--factor 0.125] [--error-points DIR]
      [--repeat-min 2 --repeat-max 5 --repeat-budget 1.0]
Prints one JSON object per line as ngsolve_lame.py (m: the RefineHP levels), with
`error_points` (the file, or null).
"""

import os

from common import (
    add_repeat_args,
    fastest_solve,
    lame_parameters,
    level_record,
    one_thread,
)

one_thread()

import argparse  # noqa: E402
import json  # noqa: E402
import time  # noqa: E402

import ngsolve  # noqa: E402
import numpy as np  # noqa: E402
from netgen.geom2d import SplineGeometry  # noqa: E402
from ngsolve import (  # noqa: E402
    ET,
    VOL,
    BilinearForm,
    CF,
    Det,
    Grad,
    GridFunction,
    InnerProduct,
    IntegrationRule,
    LinearForm,
    Mesh,
    Sym,
    VectorH1,
    div,
    ds,
    dx,
    x,
    y,
)
from ngsolve.fem import specialcf  # noqa: E402


ngsolve.SetNumThreads(1)

INNER, OUTER = 2.0, 3.0


def paper_mesh(maxh, levels, factor, order, corner_maxh=1e99):
    """(mesh, mesh seconds, curve seconds): the half annulus, refined toward its corners."""
    t0 = time.perf_counter()
    geo = SplineGeometry()
    r, s = INNER, OUTER
    points = [(r, 0), (s, 0), (s, s), (0, s), (-s, s), (-s, 0), (-r, 0), (-r, r), (0, r), (r, r)]
    corners = {0, 1, 5, 6}
    p = [
        geo.AppendPoint(
            px,
            py,
            hpref=1 if k in corners else 0,
            maxh=corner_maxh if k in corners else 1e99,
        )
        for k, (px, py) in enumerate(points)
    ]
    geo.Append(["line", p[0], p[1]], bc="end_max")
    geo.Append(["spline3", p[1], p[2], p[3]], bc="outer")
    geo.Append(["spline3", p[3], p[4], p[5]], bc="outer")
    geo.Append(["line", p[5], p[6]], bc="end_min")
    geo.Append(["spline3", p[6], p[7], p[8]], bc="contact")
    geo.Append(["spline3", p[8], p[9], p[0]], bc="contact")
    mesh = Mesh(geo.GenerateMesh(maxh=maxh))
    if levels > 0:
        mesh.RefineHP(levels, factor)
    t1 = time.perf_counter()
    mesh.Curve(order)
    t2 = time.perf_counter()
    return mesh, t1 - t0, t2 - t1


def solve(mesh, order, lam, mu, tau0, tau_max, inverse):
    """The timed part: (solution, dofs, global dofs, [setup, assemble, solve] seconds)."""
    start = time.perf_counter()
    fes = VectorH1(mesh, order=order, dirichlet="contact")
    u, v = fes.TnT()
    free = fes.FreeDofs(True)

    def eps(w):
        return Sym(Grad(w))

    a = BilinearForm(fes, symmetric=True, condense=True)
    a += (2.0 * mu * InnerProduct(eps(u), eps(v)) + lam * div(u) * div(v)) * dx
    f = LinearForm(fes)
    f += -tau_max * v[1] * ds("end_max") - tau0 * v[1] * ds("end_min")
    t_setup = time.perf_counter()
    a.Assemble()
    f.Assemble()
    t_assemble = time.perf_counter()
    gfu = GridFunction(fes)
    ainv = a.mat.Inverse(free, inverse=inverse)
    f.vec.data += a.harmonic_extension_trans * f.vec
    gfu.vec.data = ainv * f.vec
    gfu.vec.data += a.harmonic_extension * gfu.vec
    gfu.vec.data += a.inner_solve * f.vec
    end = time.perf_counter()
    return gfu, fes.ndof, free.NumSet(), [t_setup - start, t_assemble - t_setup, end - t_assemble]


def quadrature_points(mesh, gfu, order):
    """Rows (x, y, w, u_x, u_y) at the points of an order-`order` rule on every element."""
    rules = {ET.TRIG: IntegrationRule(ET.TRIG, order), ET.QUAD: IntegrationRule(ET.QUAD, order)}
    mips = mesh.MapToAllElements(rules, VOL)
    weights = np.concatenate(
        [np.asarray(rules[el.type].weights) for el in mesh.Elements(VOL)]
    )
    det = np.abs(Det(specialcf.JacobianMatrix(2))(mips).ravel())
    values = gfu(mips).reshape(-1, 2)
    return np.column_stack(
        [x(mips).ravel(), y(mips).ravel(), weights * det, values[:, 0], values[:, 1]]
    )


def run_level(a, m, lam, mu):
    corner_maxh = a.corner_maxh / m if m > 0 else 1e99
    mesh, t_mesh, t_curve = paper_mesh(a.maxh, m, a.factor, a.order, corner_maxh)
    best, runs = fastest_solve(
        a, lambda: solve(mesh, a.order, lam, mu, a.tau0, a.tau_max, a.inverse)
    )
    points = None
    if a.error_points:
        rows = quadrature_points(mesh, best[0], 2 * a.order + 4)
        points = os.path.join(a.error_points, f"ngsolve-p{a.order}-m{m}.f64")
        rows.astype("<f8").tofile(points)
    record = level_record(a, m, mesh, best, runs, (t_mesh, t_curve), ngsolve.__version__)
    record.update(maxh=a.maxh, factor=a.factor, error=None, error_points=points)
    record.update(corner_maxh=corner_maxh if m > 0 else None)
    return record


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--order", type=int, default=6)
    ap.add_argument("--levels", default="2,4,6", help="RefineHP levels per run")
    ap.add_argument(
        "--inverse", choices=["sparsecholesky", "umfpack"], default="sparsecholesky"
    )
    ap.add_argument("--maxh", type=float, default=0.5, help="mesh size before RefineHP")
    ap.add_argument("--factor", type=float, default=0.125, help="RefineHP factor")
    ap.add_argument(
        "--corner-maxh",
        type=float,
        default=0.5,
        help="level m > 0: mesh size corner_maxh / m at the four corners",
    )
    ap.add_argument("--error-points", default=None, help="directory for the points files")
    ap.add_argument("--young", type=float, default=1e3)
    ap.add_argument("--poisson", type=float, default=0.25)
    ap.add_argument("--tau0", type=float, default=1.0)
    ap.add_argument("--tau-max", type=float, default=2.0)
    add_repeat_args(ap)
    a = ap.parse_args()
    lam, mu = lame_parameters(a.young, a.poisson)
    mesh, _, _ = paper_mesh(a.maxh, 1, a.factor, a.order)  # warm-up
    solve(mesh, a.order, lam, mu, a.tau0, a.tau_max, a.inverse)
    for m in [int(s) for s in a.levels.split(",")]:
        print(json.dumps(run_level(a, m, lam, mu)), flush=True)


if __name__ == "__main__":
    main()
