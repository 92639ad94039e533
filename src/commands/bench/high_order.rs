//! The `fem-qp` rows of `capstan bench work-precision`: tensor-product elements of order
//! `p = 2 ... 8` (GLL nodes, static condensation, sparse Cholesky of the skeleton system).
//!
//! Grids: `k` elements through the thickness and `4k` (`lame`, `paper`) or `2k` (`mms`)
//! around, i.e. the problem's level `m = k p`. Time: build (geometry at the quadrature
//! points, loads), condensation + skeleton assembly, and analyse + factor + solve + interior
//! recovery. Error: as for Q1/Q2 (`lame`, `mms`: Gauss quadrature of the interpolant against
//! the exact field); on `paper` the element polynomial sampled at the nodes of a
//! `65 x 17` sub-grid of the Q2 reference, trapezoid rule with `sqrt(g)`.

use std::time::Instant;

use capstan_elasticity::finite_element::{HighOrderNavier, SampleChart, VolumetricIntegration};
use capstan_elasticity::solvers::SparseCholesky;
use capstan_elasticity::{Discretisation, ShellGeometry};

use super::{Problem, REPEAT_RULE, Reference, Run, reset_peak, status_kib};
use crate::error::CliError;

/// The orders of the bench.
pub(super) const ORDERS: core::ops::RangeInclusive<usize> = 2..=8;

/// Largest system of a `fem-qp` row (unknowns), about the size of the finest Q2 rows.
const MAX_DOFS: usize = 140_000;

/// Elements through the thickness per run.
pub(super) fn element_levels(problem: Problem, p: usize, quick: bool) -> Vec<usize> {
    let ks: &[usize] = if quick {
        &[1, 2, 4]
    } else {
        &[1, 2, 4, 8, 16, 32]
    };
    ks.iter()
        .copied()
        .filter(|&k| {
            let l = problem.level(k * p);
            2 * l.n2 * l.n3 <= MAX_DOFS
        })
        .collect()
}

/// Relative L2 error of `v` against the reference's nodes on a `65 x 17` sub-grid.
fn sampled_error(
    op: &HighOrderNavier<SampleChart>,
    v: &[f64],
    (n2r, n3r, vr): &(usize, usize, Vec<f64>),
) -> Result<f64, CliError> {
    let g = *op.grid();
    let [t0, t1] = g.theta();
    let (m2, m3) = (64, 16);
    let (s2, s3) = ((n2r - 1) / m2, (n3r - 1) / m3);
    let (mut num, mut den) = (0.0, 0.0);
    for i in 0..=m2 {
        for j in 0..=m3 {
            let x = [
                t0 + (t1 - t0) * i as f64 / m2 as f64,
                g.thickness() * j as f64 / m3 as f64,
            ];
            let kr = i * s2 * n3r + j * s3;
            let u = [vr[2 * kr], vr[2 * kr + 1]];
            let uh = op.displacement_at(v, x);
            let p = op.chart().shell_point([0.0, x[0], x[1]])?;
            let m = &p.metric;
            let n2 = |a: [f64; 2]| {
                m[1][1] * a[0] * a[0] + 2.0 * m[1][2] * a[0] * a[1] + m[2][2] * a[1] * a[1]
            };
            let w2 = if i == 0 || i == m2 { 0.5 } else { 1.0 };
            let w3 = if j == 0 || j == m3 { 0.5 } else { 1.0 };
            let w = w2 * w3 * p.sqrt_g;
            num += w * n2([uh[0] - u[0], uh[1] - u[1]]);
            den += w * n2(u);
        }
    }
    Ok((num / den).sqrt())
}

/// One `fem-qp` run of order `p` with `k` elements through the thickness, the fastest of
/// [`REPEAT_RULE`].
pub(super) fn run_qp(
    problem: Problem,
    k: usize,
    p: usize,
    reference: &Reference<'_>,
    use_vmhwm: bool,
) -> Result<Run, CliError> {
    REPEAT_RULE.fastest(|| {
        let parts = problem.parts(k * p)?;
        if use_vmhwm {
            reset_peak();
        }
        let base = status_kib("VmRSS:").unwrap_or(0.0);
        let start = Instant::now();
        let op = parts.high_order(p, VolumetricIntegration::Full)?;
        let t_setup = start.elapsed().as_secs_f64();
        let t = Instant::now();
        let condensed = op.condensed_system()?;
        let t_assemble = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let u = condensed.system.solve(&mut SparseCholesky::default())?;
        let v = op.recover(&condensed, &u)?;
        let t_solve = t.elapsed().as_secs_f64();
        let total = start.elapsed().as_secs_f64();
        let peak_mib = if use_vmhwm {
            (status_kib("VmHWM:").unwrap_or(0.0) - base).max(0.0) / 1024.0
        } else {
            (12.0 * condensed.system.pattern.nnz() as f64 + 40.0 * op.dof_count() as f64)
                / 1_048_576.0
        };
        let error = match reference {
            Reference::Exact(f) => {
                let e = op.displacement_errors(&v, *f)?;
                e.l2 / e.l2_exact
            }
            Reference::Nodal(r) => sampled_error(&op, &v, r)?,
        };
        let grid = op.grid();
        Ok(Run {
            problem: problem.name(),
            method: capstan_elasticity::finite_element::high_order::order_name(p).to_owned(),
            backend: "cholesky".to_owned(),
            n2: grid.n2(),
            n3: grid.n3(),
            dofs: op.dof_count(),
            threads: rayon::current_num_threads(),
            setup_seconds: t_setup,
            assemble_seconds: t_assemble,
            solve_seconds: t_solve,
            seconds: total,
            error,
            peak_mib,
        })
    })
}
