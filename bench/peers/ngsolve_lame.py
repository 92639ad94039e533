#!/usr/bin/env python3
"""Peer benchmark: the Lamé thick cylinder of capstan solved with NGSolve.

Problem (the same as `capstan bench work-precision`, problem `lame`, and as skfem_lame.py): a
full annulus R <= r <= R + h in plane strain, E, nu, internal pressure p, free outside; rigid
motions stopped by u_y = 0 at (R, 0) and (-R, 0) and u_x = 0 at (0, R) (exact: the solution is
radial, so these three pinned components vanish in it).

Mesh: netgen.geom2d, two `SplineGeometry.AddCircle` boundaries (each circle is four rational
quadratic arcs with end points at the angles 0, pi/2, pi, 3 pi/2, so the three pinned points are
mesh vertices), unstructured triangles with maxh = h / m for each level m, then
`mesh.Curve(order)` (curved elements of the discretisation's order). Space: `VectorH1(order=p)`;
form: 2 mu eps(u):eps(v) + lambda div u div v (plane strain, lambda and mu as scikit-fem's
`lame_parameters`); load: the traction p e_r on the inner circle; pins: the three vertex dofs
removed from the free dofs (exact Dirichlet conditions, as scikit-fem's `condense`).
Solver: `BilinearForm(symmetric=True, condense=...)`, `a.mat.Inverse(freedofs,
inverse=sparsecholesky|umfpack)`; with static condensation (default) the element-interior
bubbles are eliminated during assembly and recovered after the solve
(`harmonic_extension_trans`, `inner_solve`, `harmonic_extension`).

One thread: OMP_NUM_THREADS, OPENBLAS_NUM_THREADS and MKL_NUM_THREADS are set to 1 before
NGSolve is imported, `ngsolve.SetNumThreads(1)`, and no `TaskManager` is entered.

Timed (time.perf_counter, after the imports, the meshing and a warm-up solve): the space
(`VectorH1`, free dofs, pins), the forms, assembly of K and f, the factorisation (`Inverse`)
and the solve including the static-condensation steps, i.e. everything from the curved mesh
to the solution vector. NOT timed: `GenerateMesh` and `mesh.Curve(p)` (meshing; their times
are reported as `mesh_seconds` and `curve_seconds`), the error integration. The error is the
relative L2 error of the displacement, ||u_h - u|| / ||u|| over the curved mesh, by
`Integrate(..., order=2p + 4)` (not timed). Peak memory: the growth of VmHWM during the timed
run after resetting it through /proc/self/clear_refs (Linux), in MiB.

Repeats (the rule of capstan's own runs): every level is run at least --repeat-min times, then
until --repeat-budget seconds of run time have been spent or --repeat-max runs made; the
fastest run (total time) is reported, with its stage split (defaults 2, 5, 1.0 s). The mesh of
a level is generated and curved once and reused by its repeats.

Usage:
  .venv/bin/python bench/peers/ngsolve_lame.py --order 4 --levels 2,4,8
      [--inverse sparsecholesky] [--no-condense] [--radius 1 ...]
      [--repeat-min 2 --repeat-max 5 --repeat-budget 1.0]
Prints one JSON object per line: {"method", "backend", "order", "m", "maxh", "n2", "n3",
"elements", "vertices", "dofs", "global_dofs", "setup_seconds", "assemble_seconds",
"solve_seconds", "seconds", "mesh_seconds", "curve_seconds", "error", "peak_mib", "repeats",
"version"} (n2: triangles, n3: 0; dofs: all dofs of the space; global_dofs: the free dofs of
the factorised system; setup: space, pins and forms; assemble: K and f; solve: factorisation
and solve with the condensation steps).
"""

from common import (
    add_lame_args,
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
from netgen.geom2d import SplineGeometry  # noqa: E402
from ngsolve import (  # noqa: E402
    VERTEX,
    BilinearForm,
    CF,
    GridFunction,
    InnerProduct,
    Integrate,
    LinearForm,
    Mesh,
    NodeId,
    Sym,
    VectorH1,
    div,
    ds,
    dx,
    sqrt,
    x,
    y,
)
from ngsolve import Grad  # noqa: E402


ngsolve.SetNumThreads(1)


def annulus_mesh(m, order, radius, thickness):
    """Unstructured curved triangles of the annulus, maxh = thickness / m: (mesh, pins,
    mesh seconds, curve seconds). pins: the vertex numbers at (R, 0), (-R, 0), (0, R)."""
    t0 = time.perf_counter()
    geo = SplineGeometry()
    geo.AddCircle((0, 0), radius + thickness, leftdomain=1, rightdomain=0, bc="outer")
    geo.AddCircle((0, 0), radius, leftdomain=0, rightdomain=1, bc="inner")
    mesh = Mesh(geo.GenerateMesh(maxh=thickness / m))
    t1 = time.perf_counter()
    mesh.Curve(order)
    t2 = time.perf_counter()
    pins = []
    for px, py in [(radius, 0.0), (-radius, 0.0), (0.0, radius)]:
        v = min(
            mesh.vertices,
            key=lambda v: (v.point[0] - px) ** 2 + (v.point[1] - py) ** 2,
        )
        dist = ((v.point[0] - px) ** 2 + (v.point[1] - py) ** 2) ** 0.5
        assert dist < 1e-12 * radius, f"no vertex at ({px}, {py}): {dist}"
        pins.append(v.nr)
    return mesh, pins, t1 - t0, t2 - t1


def solve(mesh, pins, order, lam, mu, pressure, inverse, condense):
    """The timed part: (solution, dofs, global dofs, [setup, assemble, solve] seconds)."""
    start = time.perf_counter()
    fes = VectorH1(mesh, order=order)
    u, v = fes.TnT()
    free = fes.FreeDofs(condense)  # coupling dofs only with condensation
    # u_y at (R, 0) and (-R, 0), u_x at (0, R); a vertex carries (u_x, u_y)
    for vertex, component in zip(pins, [1, 1, 0]):
        dofs = fes.GetDofNrs(NodeId(VERTEX, vertex))
        assert len(dofs) == 2
        free.Clear(dofs[component])

    def eps(w):
        return Sym(Grad(w))

    a = BilinearForm(fes, symmetric=True, condense=condense)
    a += (2.0 * mu * InnerProduct(eps(u), eps(v)) + lam * div(u) * div(v)) * dx
    r = sqrt(x * x + y * y)
    f = LinearForm(fes)
    f += pressure * (x * v[0] + y * v[1]) / r * ds("inner")  # traction p e_r
    t_setup = time.perf_counter()
    a.Assemble()
    f.Assemble()
    t_assemble = time.perf_counter()
    gfu = GridFunction(fes)
    ainv = a.mat.Inverse(free, inverse=inverse)
    if condense:
        f.vec.data += a.harmonic_extension_trans * f.vec
        gfu.vec.data = ainv * f.vec
        gfu.vec.data += a.harmonic_extension * gfu.vec
        gfu.vec.data += a.inner_solve * f.vec
    else:
        gfu.vec.data = ainv * f.vec
    end = time.perf_counter()
    return (
        gfu,
        fes.ndof,
        free.NumSet(),
        [t_setup - start, t_assemble - t_setup, end - t_assemble],
    )


def relative_error(mesh, gfu, order, lam, mu, radius, thickness, pressure):
    r1, r2 = radius, radius + thickness
    b_coef = pressure / (2.0 * mu * (1.0 / r1**2 - 1.0 / r2**2))
    a_coef = mu * b_coef / ((lam + mu) * r2**2)
    r = sqrt(x * x + y * y)
    ur = a_coef * r + b_coef / r
    exact = CF((ur * x / r, ur * y / r))
    e = gfu - exact
    num = Integrate(InnerProduct(e, e), mesh, order=2 * order + 4)
    den = Integrate(ur * ur, mesh, order=2 * order + 4)
    return (num / den) ** 0.5


def run_level(a, m, lam, mu):
    mesh, pins, t_mesh, t_curve = annulus_mesh(m, a.order, a.radius, a.thickness)
    best, runs = fastest_solve(
        a,
        lambda: solve(mesh, pins, a.order, lam, mu, a.pressure, a.inverse, a.condense),
    )
    error = relative_error(
        mesh, best[0], a.order, lam, mu, a.radius, a.thickness, a.pressure
    )
    record = level_record(a, m, mesh, best, runs, (t_mesh, t_curve), ngsolve.__version__)
    backend = a.inverse + ("" if a.condense else "-full")
    record.update(backend=backend, maxh=a.thickness / m, error=float(error))
    return record


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--order", type=int, default=4)
    ap.add_argument(
        "--levels", default="1,2,4", help="m per level: maxh = thickness / m"
    )
    ap.add_argument(
        "--inverse", choices=["sparsecholesky", "umfpack"], default="sparsecholesky"
    )
    ap.add_argument(
        "--no-condense",
        dest="condense",
        action="store_false",
        help="factorise the full system (no static condensation of the bubbles)",
    )
    add_lame_args(ap)
    a = ap.parse_args()
    lam, mu = lame_parameters(a.young, a.poisson)
    mesh, pins, _, _ = annulus_mesh(2, a.order, a.radius, a.thickness)  # warm-up
    solve(mesh, pins, a.order, lam, mu, a.pressure, a.inverse, a.condense)
    for m in [int(s) for s in a.levels.split(",")]:
        print(json.dumps(run_level(a, m, lam, mu)), flush=True)


if __name__ == "__main__":
    main()
