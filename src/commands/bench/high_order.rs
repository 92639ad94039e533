//! The `fem-qp` rows of `capstan bench work-precision`: tensor-product elements of order
//! `p = 2 ... 10` (GLL nodes, static condensation, sparse Cholesky of the skeleton system).
//!
//! Grids: `k` elements through the thickness and `4k` (`lame`, `paper`) or `2k` (`mms`)
//! around, i.e. the problem's level `m = k p`, `k = 1, 2, 3, 4, 6, 8, 12, 16, 24, 32`
//! ([`LADDER`]) within [`MAX_DOFS`]. On `mms` also the series `fem-qpP-x2`: one element
//! through the thickness and `e2 = 2, 3, 4, 5, 6, 8, ...` along `x2` ([`X2_LADDER`]), the
//! refinement where `mms`'s error is (its error does not change when the elements through
//! the thickness are doubled, from `p = 5` on). On `paper` also the graded series
//! `fem-qpP-graded`: `n` geometric layers (ratio [`SIGMA`]) at each end of `x2` and `x3`
//! around `6 x 1` middle elements ([`Grading`]), `n` growing along the series, orders up to
//! [`PAPER_REFINED_MAX_ORDER`]; the paper's
//! reference is the graded `p = 10`, `n = 12` solve ([`paper_reference`]). Time: build
//! (geometry at the quadrature points, loads), condensation and skeleton assembly, and
//! analyse, factor, solve and interior recovery. Error: as for Q1/Q2, Gauss quadrature
//! (`p + 2` points per direction) of the element polynomial against the exact field (`lame`,
//! `mms`) or the reference's element polynomial (`paper`) over the run's elements.

use std::time::Instant;

use capstan_elasticity::LinearSystem;
use capstan_elasticity::finite_element::high_order::CondensedSystem;
use capstan_elasticity::finite_element::high_order::corner_mesh::CornerCondensed;
use capstan_elasticity::finite_element::{
    CornerRefinedNavier, Grading, HighOrderNavier, QpSettings, VolumetricIntegration,
};
use capstan_elasticity::samples::PaperEllipse;
use capstan_elasticity::solvers::SparseCholesky;
use capstan_elasticity::studies::{SampleChart, mms_parts, paper_parts};
use capstan_elasticity::verification::GridLevel;
use capstan_elasticity::{Discretisation, ElasticityError};

use super::run::{reset_peak, status_kib};
use super::{PaperReferenceReport, Problem, REPEAT_RULE, Reference, Run};
use crate::error::CliError;

/// The orders of the bench (uniform series of every problem).
pub(super) const ORDERS: core::ops::RangeInclusive<usize> = 2..=10;

/// The highest order of `paper`'s graded and corner-refined series: its reference is the
/// graded `p = 10` solve, so those series stop two orders below it.
pub(super) const PAPER_REFINED_MAX_ORDER: usize = 8;

/// Elements through the thickness along a uniform series: about `sqrt(2)` apart, so that the
/// time to a target, interpolated log-log between the two runs that bracket it, is not an
/// artefact of a doubling ladder (at `p = 8` one doubling of `k` takes the `mms` error from
/// 1e-5 to 2e-8).
const LADDER: [usize; 10] = [1, 2, 3, 4, 6, 8, 12, 16, 24, 32];

/// The ladder of `--quick`.
const QUICK_LADDER: [usize; 3] = [1, 2, 4];

/// Elements along `x2` of the `fem-qpP-x2` series on `mms` (one element through the
/// thickness): no two successive rungs more than a factor 1.5 apart from `e2 = 4` on. It
/// stops at 32: by then every order has reached the floor of its single element through
/// the thickness (`p = 5`: 1.4e-8 from `e2 = 10`, `p = 6`: 9.8e-10 from `e2 = 12`).
const X2_LADDER: [usize; 12] = [2, 3, 4, 5, 6, 8, 10, 12, 16, 20, 24, 32];

/// The `fem-qpP-x2` ladder of `--quick`.
const QUICK_X2_LADDER: [usize; 3] = [2, 3, 4];

/// Largest system of a `fem-qp` row (unknowns), about the size of the finest Q2 rows.
const MAX_DOFS: usize = 140_000;

/// Elements through the thickness per run ([`LADDER`], `--quick` [`QUICK_LADDER`]) within
/// [`MAX_DOFS`].
pub(super) fn element_levels(problem: Problem, p: usize, quick: bool) -> Vec<usize> {
    let ks: &[usize] = if quick { &QUICK_LADDER } else { &LADDER };
    ks.iter()
        .copied()
        .filter(|&k| {
            let l = problem.level(k * p);
            2 * l.n2 * l.n3 <= MAX_DOFS
        })
        .collect()
}

/// The `fem-qpP-x2` series' elements along `x2` (`mms` only; [`X2_LADDER`], `--quick`
/// [`QUICK_X2_LADDER`]) within [`MAX_DOFS`].
pub(super) fn x2_levels(p: usize, quick: bool) -> Vec<usize> {
    let e2s: &[usize] = if quick { &QUICK_X2_LADDER } else { &X2_LADDER };
    e2s.iter()
        .copied()
        .filter(|&e2| {
            let l = x2_level(p, e2);
            2 * l.n2 * l.n3 <= MAX_DOFS
        })
        .collect()
}

/// `e2 x 1` elements of order `p`: `(p e2 + 1) x (p + 1)` nodes.
fn x2_level(p: usize, e2: usize) -> GridLevel {
    GridLevel {
        n2: e2 * p + 1,
        n3: p + 1,
    }
}

/// Grading ratio of the graded `paper` runs. With a fixed order the layer elements converge
/// like `rho^-p`, `rho` growing with `sigma`; `0.15` (the hp-optimum for `p` growing with the
/// layers) stalls near `1e-6` at `p = 8` (docs/high-order.md).
pub const SIGMA: f64 = 0.4;

/// Geometric layers per end along the graded series.
const LAYERS: [usize; 8] = [1, 2, 3, 4, 6, 8, 10, 12];

/// The mesh of one `fem-qp` run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum QpMesh {
    /// `k` uniform elements through the thickness (the problem's level `m = k p`).
    Uniform(usize),
    /// `paper` only: `n` geometric layers at each end around `6 x 1` middle elements.
    Graded(usize),
    /// `mms` only: `e2` uniform elements along `x2`, one through the thickness.
    AlongX2(usize),
}

/// The graded series' layer counts of order `p` within [`MAX_DOFS`].
pub(super) fn graded_layers(p: usize, quick: bool) -> Vec<usize> {
    let layers = if quick { &LAYERS[..3] } else { &LAYERS[..] };
    layers
        .iter()
        .copied()
        .filter(|&n| {
            let l = graded_level(p, n);
            2 * l.n2 * l.n3 <= MAX_DOFS
        })
        .collect()
}

/// `(2n + 6) x (2n + 1)` elements of order `p`.
fn graded_level(p: usize, n: usize) -> GridLevel {
    GridLevel {
        n2: (2 * n + 6) * p + 1,
        n3: (2 * n + 1) * p + 1,
    }
}

/// The operator of one run.
fn build(
    problem: Problem,
    p: usize,
    mesh: QpMesh,
) -> Result<HighOrderNavier<SampleChart>, ElasticityError> {
    match mesh {
        QpMesh::Uniform(k) => problem
            .parts(k * p)?
            .high_order(p, VolumetricIntegration::Full),
        QpMesh::Graded(n) => paper_parts(&PaperEllipse::default(), graded_level(p, n))?
            .high_order_with(QpSettings {
                grading: Grading::geometric(SIGMA, n)?,
                ..QpSettings::order(p)
            }),
        QpMesh::AlongX2(e2) => mms_parts(&super::mms(), x2_level(p, e2))?
            .0
            .high_order(p, VolumetricIntegration::Full),
    }
}

/// The paper problem's reference (operator, solution) and how it was checked.
pub struct PaperReference {
    /// The reference operator (graded, `p = 10`, 12 layers; quick: `p = 8`, 8 layers).
    pub op: HighOrderNavier<SampleChart>,
    /// Its solution.
    pub v: Vec<f64>,
    /// Name, unknowns and self-convergence, as the report gives them.
    pub summary: PaperReferenceReport,
}

/// Solves the graded paper problem with `(p, n)`, `(p - 1, n - 1)`, `(p - 2, n - 2)` and
/// measures the successive changes.
///
/// # Errors
/// Elasticity and solver errors.
pub fn paper_reference(quick: bool) -> Result<PaperReference, CliError> {
    let (p, n) = if quick { (8, 8) } else { (10, 12) };
    let solve = |p: usize, n: usize| -> Result<_, CliError> {
        let op = build(Problem::Paper, p, QpMesh::Graded(n))?;
        let v = op.solve(&mut SparseCholesky::default())?;
        Ok((op, v))
    };
    let distance = |(a, va): &(HighOrderNavier<SampleChart>, Vec<f64>),
                    (b, vb): &(HighOrderNavier<SampleChart>, Vec<f64>)|
     -> Result<f64, CliError> {
        let e = a.displacement_errors(va, &|x| b.displacement_at(vb, x))?;
        Ok(e.l2 / e.l2_exact)
    };
    let (older, previous, reference) = (solve(p - 2, n - 2)?, solve(p - 1, n - 1)?, solve(p, n)?);
    let change = distance(&previous, &reference)?;
    let previous_change = distance(&older, &previous)?;
    let (op, v) = reference;
    let summary = PaperReferenceReport {
        method: format!("fem-qp{p}-graded, {n} layers, sigma {SIGMA}"),
        dofs: op.dof_count(),
        change,
        previous_change,
    };
    Ok(PaperReference { op, v, summary })
}

/// One `fem-qp` run of order `p` on `mesh`, the fastest of [`REPEAT_RULE`].
pub(super) fn run_qp(
    problem: Problem,
    mesh: QpMesh,
    p: usize,
    reference: Reference<'_>,
    use_vmhwm: bool,
) -> Result<Run, CliError> {
    REPEAT_RULE.fastest(|| {
        let (op, t) = timed_condensed(use_vmhwm, reference, || Ok(build(problem, p, mesh)?))?;
        let grid = op.grid();
        let name = capstan_elasticity::finite_element::high_order::order_name(p);
        let method = match mesh {
            QpMesh::Uniform(_) => name.to_owned(),
            QpMesh::Graded(_) => format!("{name}-graded"),
            QpMesh::AlongX2(_) => format!("{name}-x2"),
        };
        Ok(t.run(problem, method, [grid.n2(), grid.n3()], op.dof_count()))
    })
}

/// An operator the bench solves by static condensation: the tensor-grid Qp
/// ([`HighOrderNavier`]) and the corner mesh ([`CornerRefinedNavier`]).
pub(super) trait CondensedSolve {
    /// The condensed skeleton system and the element factors.
    type Condensed;
    /// Condenses the element interiors.
    fn condense(&self) -> Result<Self::Condensed, ElasticityError>;
    /// The skeleton system of `condensed`.
    fn skeleton(condensed: &Self::Condensed) -> &LinearSystem;
    /// Every node's displacement from the skeleton solution `u`.
    fn recover(&self, condensed: &Self::Condensed, u: &[f64]) -> Result<Vec<f64>, ElasticityError>;
    /// Unknowns of the whole system.
    fn dofs(&self) -> usize;
    /// `||v - reference|| / ||reference||` in L2 over the operator's elements.
    fn relative_error(&self, v: &[f64], reference: Reference<'_>) -> Result<f64, ElasticityError>;
}

impl CondensedSolve for HighOrderNavier<SampleChart> {
    type Condensed = CondensedSystem;
    fn condense(&self) -> Result<CondensedSystem, ElasticityError> {
        self.condensed_system()
    }
    fn skeleton(condensed: &CondensedSystem) -> &LinearSystem {
        &condensed.system
    }
    fn recover(&self, condensed: &CondensedSystem, u: &[f64]) -> Result<Vec<f64>, ElasticityError> {
        HighOrderNavier::recover(self, condensed, u)
    }
    fn dofs(&self) -> usize {
        self.dof_count()
    }
    fn relative_error(&self, v: &[f64], reference: Reference<'_>) -> Result<f64, ElasticityError> {
        let e = self.displacement_errors(v, reference)?;
        Ok(e.l2 / e.l2_exact)
    }
}

impl CondensedSolve for CornerRefinedNavier<SampleChart> {
    type Condensed = CornerCondensed;
    fn condense(&self) -> Result<CornerCondensed, ElasticityError> {
        self.condensed_system()
    }
    fn skeleton(condensed: &CornerCondensed) -> &LinearSystem {
        &condensed.system
    }
    fn recover(&self, condensed: &CornerCondensed, u: &[f64]) -> Result<Vec<f64>, ElasticityError> {
        CornerRefinedNavier::recover(self, condensed, u)
    }
    fn dofs(&self) -> usize {
        self.dof_count()
    }
    fn relative_error(&self, v: &[f64], reference: Reference<'_>) -> Result<f64, ElasticityError> {
        let e = self.displacement_errors(v, reference)?;
        Ok(e.l2 / e.l2_exact)
    }
}

/// The times (s), peak memory (MiB) and error of one condensed run.
pub(super) struct CondensedTimes {
    /// Building the operator.
    pub setup: f64,
    /// Condensation and skeleton assembly.
    pub assemble: f64,
    /// Analyse, factor, solve and interior recovery.
    pub solve: f64,
    /// All three.
    pub total: f64,
    /// Growth of VmHWM over the run, or the estimate `12 nnz + 40 dofs` bytes.
    pub peak_mib: f64,
    /// Relative L2 error against `reference`.
    pub error: f64,
}

impl CondensedTimes {
    /// The bench row of this run on `problem` (`n`: the row's `n2`, `n3`; backend
    /// `cholesky`, the threads of the current rayon pool).
    pub(super) fn run(self, problem: Problem, method: String, n: [usize; 2], dofs: usize) -> Run {
        Run {
            problem: problem.name(),
            method,
            backend: "cholesky".to_owned(),
            n2: n[0],
            n3: n[1],
            dofs,
            threads: rayon::current_num_threads(),
            setup_seconds: self.setup,
            assemble_seconds: self.assemble,
            solve_seconds: self.solve,
            seconds: self.total,
            error: self.error,
            peak_mib: self.peak_mib,
        }
    }
}

/// One run: `build` (timed as setup), condense, solve the skeleton by sparse Cholesky and
/// recover the interiors (timed), then the error against `reference` (not timed).
pub(super) fn timed_condensed<O: CondensedSolve>(
    use_vmhwm: bool,
    reference: Reference<'_>,
    build: impl FnOnce() -> Result<O, CliError>,
) -> Result<(O, CondensedTimes), CliError> {
    if use_vmhwm {
        reset_peak();
    }
    let base = status_kib("VmRSS:").unwrap_or(0.0);
    let start = Instant::now();
    let op = build()?;
    let setup = start.elapsed().as_secs_f64();
    let t = Instant::now();
    let condensed = op.condense()?;
    let assemble = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let skeleton = O::skeleton(&condensed);
    let u = skeleton.solve(&mut SparseCholesky::default())?;
    let v = op.recover(&condensed, &u)?;
    let solve = t.elapsed().as_secs_f64();
    let total = start.elapsed().as_secs_f64();
    let peak_mib = if use_vmhwm {
        (status_kib("VmHWM:").unwrap_or(0.0) - base).max(0.0) / 1024.0
    } else {
        (12.0 * skeleton.pattern.nnz() as f64 + 40.0 * op.dofs() as f64) / 1_048_576.0
    };
    let error = op.relative_error(&v, reference)?;
    Ok((
        op,
        CondensedTimes {
            setup,
            assemble,
            solve,
            total,
            peak_mib,
            error,
        },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The uniform ladder: `k = 1, 2, 3, 4, 6, 8, 12, 16, 24, 32` cut at [`MAX_DOFS`], no two
    /// successive runs more than a factor 1.5 apart in `k` (so at most ~2.25x in unknowns),
    /// every run within the budget and a whole number of elements of the problem's grid.
    #[test]
    fn uniform_ladder_is_fine_and_within_the_budget() {
        for problem in [Problem::Lame, Problem::Mms, Problem::Paper] {
            for p in ORDERS {
                let ks = element_levels(problem, p, false);
                assert_eq!(ks[..4], [1, 2, 3, 4], "{} p {p}", problem.name());
                assert!(ks.len() >= 6, "{} p {p}: {ks:?}", problem.name());
                for w in ks.windows(2) {
                    assert!(w[1] > w[0] && 2 * w[1] <= 3 * w[0].max(2), "{ks:?}");
                }
                for &k in &ks {
                    let l = problem.level(k * p);
                    assert!(2 * l.n2 * l.n3 <= MAX_DOFS);
                    assert!(problem.parts(k * p).is_ok());
                }
                // the next rung of the ladder is over the budget
                if let Some(&next) = LADDER.iter().find(|&&k| k > *ks.last().unwrap()) {
                    let l = problem.level(next * p);
                    assert!(2 * l.n2 * l.n3 > MAX_DOFS, "{} p {p}", problem.name());
                }
            }
            assert_eq!(element_levels(problem, 8, true), [1, 2, 4]);
        }
    }

    /// The `fem-qpP-x2` ladder of `mms`: starts at the uniform series' first run (`2 x 1`
    /// elements, the same grid), successive rungs at most 1.5x apart from `e2 = 4` on, every
    /// run within the budget and buildable, the next rung over it.
    #[test]
    fn x2_ladder_is_fine_and_within_the_budget() {
        for p in ORDERS {
            let e2s = x2_levels(p, false);
            assert_eq!(e2s[..4], [2, 3, 4, 5], "p {p}");
            assert_eq!(x2_level(p, 2), Problem::Mms.level(p), "p {p}");
            for w in e2s.windows(2) {
                assert!(w[1] > w[0] && 2 * w[1] <= 3 * w[0].max(4), "{e2s:?}");
            }
            for &e2 in &e2s {
                let l = x2_level(p, e2);
                assert!(2 * l.n2 * l.n3 <= MAX_DOFS);
                let op = build(Problem::Mms, p, QpMesh::AlongX2(e2)).unwrap();
                assert_eq!(op.element_counts(), [e2, 1]);
            }
            if let Some(&next) = X2_LADDER.iter().find(|&&e| e > *e2s.last().unwrap()) {
                let l = x2_level(p, next);
                assert!(2 * l.n2 * l.n3 > MAX_DOFS, "p {p}");
            }
        }
        assert_eq!(x2_levels(8, true), [2, 3, 4]);
    }
}
