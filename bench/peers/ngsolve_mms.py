#!/usr/bin/env python3
"""Peer benchmark: capstan's manufactured solution on the ellipse b/a = 2 (problem `mms`)
solved with NGSolve.

Problem (capstan's `PrismMms::ellipse(2, TractionContact)` with the `TrigonometricField`, as
`capstan bench work-precision` problem `mms`): the body X(x2, x3) = C(x2) + x3 N(x2) over the
ellipse C(t) = (a sin t, b cos t), a = 1, b = 2, with N the outward unit normal, x2 in
[-1.2, 1.0], x3 in [0, 0.5]; plane strain, E = 10, nu = 0.3; the exact displacement is
U = v^2 g_2 + v^3 g_3 (g_2 = dX/dx2, g_3 = N) with the contravariant components

    v^2 = 0.05 sin(1.3 x2 + 0.2) (1 + x3/2 + x3^2/4)
    v^3 = 0.1 sin(1.2 x3) (1 + cos(0.8 x2)/2);

U is prescribed on the two ends x2 = -1.2, 1.0 (Dirichlet) and the body force and the
tractions on x3 = 0 and x3 = 0.5 are those of U. The load is given in its weak form,
l(v) = int sigma(U) : grad v dx, which for every v vanishing on the Dirichlet ends equals
int f . v dx + int_{x3 = 0, h} t . v ds with f = -div sigma(U) and t = sigma(U) n (integration
by parts), so the discrete problem is the same as with capstan's strong forcing and tractions;
only first derivatives of U are needed (sympy derives dU/dx2, dU/dx3 and the Jacobian J =
[g_2 g_3]; grad U = [dU/dx2 dU/dx3] J^-1).

Mesh: the parameter rectangle meshed by netgen (`SplineGeometry.AddRectangle`, unstructured
triangles, maxh = 0.5 / m for level m), then `mesh.SetDeformation` by the order-p
interpolant of X(x2, x3) - (x2, x3): curved (isoparametric) triangles of the body, the
geometry exact to order p as `mesh.Curve(p)` makes it for spline geometries. The parameter
coordinates (x2, x3) are a linear GridFunction of the undeformed mesh, so the exact U is
evaluated at the parameter point of every integration point. Space `VectorH1(order=p,
dirichlet="left|right")`, the Dirichlet values by `GridFunction.Set(U, BND)`; form
2 mu eps(u):eps(v) + lambda div u div v; static condensation; `a.mat.Inverse(freedofs,
inverse=sparsecholesky|umfpack)` as ngsolve.solvers.BVP does with non-zero Dirichlet data.

One thread, timing, repeats and peak memory as ngsolve_lame.py; NOT timed: meshing and the
deformation (`mesh_seconds`, `curve_seconds`), the error integration. Timed: the space, the
forms (load CoefficientFunction compiled by `Compile()`), the Dirichlet values, assembly,
factorisation and solve with the condensation steps. Error: ||u_h - U|| / ||U|| in L2 over the
curved mesh by `Integrate(..., order = 2p + 4)`, the same relative L2 norm as capstan's
(Gauss quadrature over its own elements of |U_h - U|, dA = sqrt(g) dx2 dx3).

Usage:
  .venv/bin/python bench/peers/ngsolve_mms.py --order 4 --levels 1,2,4,8
      [--inverse sparsecholesky] [--repeat-min 2 --repeat-max 5 --repeat-budget 1.0]
Prints one JSON object per line as ngsolve_lame.py.
"""

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
import sympy as sp  # noqa: E402
from netgen.geom2d import SplineGeometry  # noqa: E402
from ngsolve import (  # noqa: E402
    BND,
    BilinearForm,
    CF,
    Grad,
    GridFunction,
    InnerProduct,
    Integrate,
    LinearForm,
    Mesh,
    Projector,
    Sym,
    VectorH1,
    div,
    dx,
    x,
    y,
)


ngsolve.SetNumThreads(1)

A, B = 1.0, 2.0
THETA = (-1.2, 1.0)
THICKNESS = 0.5


def exact_expressions():
    """sympy: (X, U, dU/dx2, dU/dx3, g_2, g_3) as functions of the symbols (x2, x3)."""
    x2, x3 = sp.symbols("x2 x3")
    c = sp.Matrix([A * sp.sin(x2), B * sp.cos(x2)])
    normal = sp.Matrix([B * sp.sin(x2), A * sp.cos(x2)])
    normal = normal / sp.sqrt(normal.dot(normal))
    position = c + x3 * normal
    g2 = position.diff(x2)
    g3 = normal
    v2 = sp.Rational(1, 20) * sp.sin(sp.Rational(13, 10) * x2 + sp.Rational(1, 5)) * (
        1 + x3 / 2 + x3**2 / 4
    )
    v3 = sp.Rational(1, 10) * sp.sin(sp.Rational(6, 5) * x3) * (
        1 + sp.cos(sp.Rational(4, 5) * x2) / 2
    )
    u = v2 * g2 + v3 * g3
    return (x2, x3), position, u, u.diff(x2), u.diff(x3), g2, g3


def to_cf(symbols, exprs, xi):
    """The sympy expressions as CoefficientFunctions of the parameter GridFunction xi."""
    funcs = {"sin": ngsolve.sin, "cos": ngsolve.cos, "sqrt": ngsolve.sqrt}
    f = sp.lambdify(symbols, exprs, modules=[funcs], cse=True)
    return f(xi[0], xi[1])


def mms_mesh(m, order, expr):
    """(mesh, xi, U, grad U, mesh seconds, deformation seconds)."""
    symbols, position, u, du2, du3, g2, g3 = expr
    t0 = time.perf_counter()
    geo = SplineGeometry()
    geo.AddRectangle(
        (THETA[0], 0.0), (THETA[1], THICKNESS), bcs=["bottom", "right", "top", "left"]
    )
    mesh = Mesh(geo.GenerateMesh(maxh=THICKNESS / m))
    t1 = time.perf_counter()
    xi = GridFunction(VectorH1(mesh, order=1))
    xi.Set(CF((x, y)))
    px, py = to_cf(symbols, [position[0], position[1]], (x, y))
    deformation = GridFunction(VectorH1(mesh, order=order))
    deformation.Set(CF((px - x, py - y)))
    mesh.SetDeformation(deformation)
    t2 = time.perf_counter()
    ux, uy, a2x, a2y, a3x, a3y, g2x, g2y, g3x, g3y = to_cf(
        symbols,
        [u[0], u[1], du2[0], du2[1], du3[0], du3[1], g2[0], g2[1], g3[0], g3[1]],
        xi,
    )
    exact = CF((ux, uy))
    # grad U = [dU/dx2 dU/dx3] J^-1, J = [g_2 g_3] (columns)
    det = g2x * g3y - g3x * g2y
    jinv = [[g3y / det, -g3x / det], [-g2y / det, g2x / det]]
    du = [[a2x, a3x], [a2y, a3y]]
    grad = CF(
        tuple(
            du[i][0] * jinv[0][j] + du[i][1] * jinv[1][j] for i in range(2) for j in range(2)
        ),
        dims=(2, 2),
    )
    return mesh, exact, grad, t1 - t0, t2 - t1, deformation


def solve(mesh, order, lam, mu, exact, grad, inverse):
    """The timed part: (solution, dofs, global dofs, [setup, assemble, solve] seconds)."""
    start = time.perf_counter()
    fes = VectorH1(mesh, order=order, dirichlet="left|right")
    u, v = fes.TnT()
    free = fes.FreeDofs(True)

    def eps(w):
        return Sym(Grad(w))

    a = BilinearForm(fes, symmetric=True, condense=True)
    a += (2.0 * mu * InnerProduct(eps(u), eps(v)) + lam * div(u) * div(v)) * dx
    eps_u = 0.5 * (grad + grad.trans)
    sigma = (2.0 * mu * eps_u + lam * (grad[0, 0] + grad[1, 1]) * ngsolve.Id(2)).Compile()
    f = LinearForm(fes)
    f += InnerProduct(sigma, Grad(v)) * dx
    gfu = GridFunction(fes)
    gfu.Set(exact, BND)
    t_setup = time.perf_counter()
    a.Assemble()
    f.Assemble()
    t_assemble = time.perf_counter()
    r = f.vec.CreateVector()
    r.data = f.vec
    r.data += a.harmonic_extension_trans * r
    inner = fes.FreeDofs(False) & ~fes.FreeDofs(True)
    Projector(inner, False).Project(gfu.vec)
    ainv = a.mat.Inverse(free, inverse=inverse)
    r.data -= a.mat * gfu.vec
    gfu.vec.data += ainv * r
    gfu.vec.data += a.harmonic_extension * gfu.vec
    gfu.vec.data += a.inner_solve * r
    end = time.perf_counter()
    return gfu, fes.ndof, free.NumSet(), [t_setup - start, t_assemble - t_setup, end - t_assemble]


def relative_error(mesh, gfu, exact, order):
    e = gfu - exact
    num = Integrate(InnerProduct(e, e), mesh, order=2 * order + 4)
    den = Integrate(InnerProduct(exact, exact), mesh, order=2 * order + 4)
    return (num / den) ** 0.5


def run_level(a, m, lam, mu, expr):
    mesh, exact, grad, t_mesh, t_curve, _deformation = mms_mesh(m, a.order, expr)
    best, runs = fastest_solve(
        a, lambda: solve(mesh, a.order, lam, mu, exact, grad, a.inverse)
    )
    error = relative_error(mesh, best[0], exact, a.order)
    record = level_record(a, m, mesh, best, runs, (t_mesh, t_curve), ngsolve.__version__)
    record.update(maxh=THICKNESS / m, error=float(error))
    return record


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--order", type=int, default=4)
    ap.add_argument("--levels", default="1,2,4", help="m per level: maxh = 0.5 / m")
    ap.add_argument(
        "--inverse", choices=["sparsecholesky", "umfpack"], default="sparsecholesky"
    )
    add_repeat_args(ap)
    a = ap.parse_args()
    lam, mu = lame_parameters(10.0, 0.3)
    expr = exact_expressions()
    mesh, exact, grad, _, _, _d = mms_mesh(1, a.order, expr)  # warm-up
    solve(mesh, a.order, lam, mu, exact, grad, a.inverse)
    for m in [int(s) for s in a.levels.split(",")]:
        print(json.dumps(run_level(a, m, lam, mu, expr)), flush=True)


if __name__ == "__main__":
    main()
