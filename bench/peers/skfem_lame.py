#!/usr/bin/env python3
"""Peer benchmark: the Lamé thick cylinder of capstan solved with scikit-fem.

Problem (the same as `capstan bench work-precision`, problem `lame`): a full annulus
R <= r <= R + h in plane strain, E, nu, internal pressure p, free outside; rigid motions
stopped by u_y = 0 at (R, 0) and (-R, 0) and u_x = 0 at (0, R) (exact: the solution is
radial). Mesh: the structured (theta, r) grid of capstan, n2 = 4 m cells around, m cells
through the thickness, mapped exactly onto the annulus (Q2: isoparametric MeshQuad2 with
mid-edge and centre nodes placed on the curved geometry). Solver: scikit-fem's `solve`
(scipy.sparse.linalg.spsolve, SuperLU), after `condense`.

Timed (time.perf_counter, after the imports): mesh, basis, assembly of K and f, condensation
and solve, i.e. everything from the problem data to the solution, as capstan times its own
runs. The error is the relative L2 error of the displacement, ||u_h - u|| / ||u|| over the
annulus, by Gauss quadrature of order 2k + 4 (not timed). Peak memory: the growth of VmHWM
during the run after resetting it through /proc/self/clear_refs (Linux), in MiB.

Repeats (the rule of capstan's own runs): every level is run at least --repeat-min times, then
until --repeat-budget seconds of run time have been spent or --repeat-max runs made; the fastest
run (total time) is reported, with its stage split (defaults 2, 5, 1.0 s).

Usage:
  .venv/bin/python bench/peers/skfem_lame.py --order 2 --levels 4,8,16 [--radius 1 ...]
      [--repeat-min 2 --repeat-max 5 --repeat-budget 1.0]
Prints one JSON object per line: {"method", "backend", "order", "m", "n2", "n3", "dofs", "setup_seconds",
"assemble_seconds", "solve_seconds", "seconds", "error", "peak_mib"} (setup: mesh and bases;
solve: condensation and spsolve).
"""

import argparse
import json
import time

import numpy as np
from skfem import (
    Basis,
    ElementQuad1,
    ElementQuad2,
    ElementVector,
    FacetBasis,
    Functional,
    LinearForm,
    MeshQuad,
    MeshQuad2,
    asm,
    condense,
    solve,
)
from skfem.helpers import dot
from skfem.models.elasticity import lame_parameters, linear_elasticity

from common import add_lame_args, fastest, reset_peak, vm_kib


def annulus_mesh(order, m, radius, thickness):
    n2, n3 = 4 * m, m + 1
    theta = 2.0 * np.pi * np.arange(n2) / n2
    r = radius + thickness * np.arange(n3) / (n3 - 1)
    tt, rr = np.meshgrid(theta, r, indexing="ij")  # node (i, j) -> i * n3 + j
    p = np.vstack([(rr * np.cos(tt)).ravel(), (rr * np.sin(tt)).ravel()])
    i, j = np.meshgrid(np.arange(n2), np.arange(n3 - 1), indexing="ij")
    i, j = i.ravel(), j.ravel()
    ip = (i + 1) % n2
    # counter-clockwise in (x, y): (theta, r) -> (theta, r + dr) is outward, theta increases CCW
    t = np.vstack([i * n3 + j, ip * n3 + j, ip * n3 + j + 1, i * n3 + j + 1])
    mesh = MeshQuad(p, t)
    if order == 1:
        return mesh
    m2 = MeshQuad2.from_mesh(mesh)
    d = m2.doflocs.copy()
    nv, nf = mesh.p.shape[1], mesh.facets.shape[1]
    radii = np.sqrt((mesh.p**2).sum(axis=0))
    target = np.concatenate(
        [radii, radii[mesh.facets].mean(axis=0), radii[mesh.t].mean(axis=0)]
    )
    scale = target / np.sqrt((d**2).sum(axis=0))
    d[:, nv:] *= scale[nv:]  # straight midpoints -> on the arcs (exact parametric midpoints)
    assert d.shape[1] == nv + nf + mesh.t.shape[1]
    return MeshQuad2(d, m2.t)


def run(order, m, radius, thickness, young, poisson, pressure):
    lam, mu = lame_parameters(young, poisson)
    r1, r2 = radius, radius + thickness
    b_coef = pressure / (2.0 * mu * (1.0 / r1**2 - 1.0 / r2**2))
    a_coef = mu * b_coef / ((lam + mu) * r2**2)

    reset_peak()
    base = vm_kib("VmRSS")
    start = time.perf_counter()
    mesh = annulus_mesh(order, m, radius, thickness)
    element = ElementVector(ElementQuad1() if order == 1 else ElementQuad2())
    basis = Basis(mesh, element, intorder=2 * order)
    inner = mesh.facets_satisfying(
        lambda x: np.sqrt(x[0] ** 2 + x[1] ** 2) < radius + 1e-9 * thickness
    )
    fbasis = FacetBasis(mesh, element, facets=inner, intorder=2 * order)
    t_setup = time.perf_counter()
    K = asm(linear_elasticity(lam, mu), basis)

    @LinearForm
    def load(v, w):
        return -pressure * dot(w.n, v)  # traction p e_r, outward normal n = -e_r

    f = asm(load, fbasis)
    t_assemble = time.perf_counter()
    n2, n3 = 4 * m, m + 1
    nodal = basis.nodal_dofs  # [component][vertex]
    pins = np.array([nodal[1][0], nodal[1][(n2 // 2) * n3], nodal[0][(n2 // 4) * n3]])
    u = solve(*condense(K, f, D=pins))
    end = time.perf_counter()
    seconds = end - start
    peak_mib = max(vm_kib("VmHWM") - base, 0) / 1024.0

    ebasis = Basis(mesh, element, intorder=2 * order + 4)
    uh = ebasis.interpolate(u)

    @Functional
    def err2(w):
        x, y = w.x
        r = np.sqrt(x**2 + y**2)
        ur = a_coef * r + b_coef / r
        return (w["uh"][0] - ur * x / r) ** 2 + (w["uh"][1] - ur * y / r) ** 2

    @Functional
    def norm2(w):
        x, y = w.x
        r = np.sqrt(x**2 + y**2)
        return (a_coef * r + b_coef / r) ** 2

    error = np.sqrt(err2.assemble(ebasis, uh=uh) / norm2.assemble(ebasis))
    return {
        "method": f"skfem-q{order}",
        "backend": "scipy-superlu",
        "order": order,
        "m": m,
        "n2": n2,
        "n3": n3,
        "dofs": int(basis.N),
        "setup_seconds": t_setup - start,
        "assemble_seconds": t_assemble - t_setup,
        "solve_seconds": end - t_assemble,
        "seconds": seconds,
        "error": float(error),
        "peak_mib": peak_mib,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--order", type=int, choices=[1, 2], default=2)
    ap.add_argument("--levels", default="4,8,16")
    add_lame_args(ap)
    a = ap.parse_args()
    run(a.order, 2, a.radius, a.thickness, a.young, a.poisson, a.pressure)  # warm-up
    for m in [int(s) for s in a.levels.split(",")]:
        best, runs = fastest(
            a,
            lambda: run(a.order, m, a.radius, a.thickness, a.young, a.poisson, a.pressure),
            lambda r: r["seconds"],
        )
        best["repeats"] = runs
        print(json.dumps(best), flush=True)


if __name__ == "__main__":
    main()
