//! The reference problems of [`crate::samples`] for any discretisation, and the
//! finite-element convergence studies of the `capstan verify` registry.

use std::sync::Arc;

use super::parts::ProblemParts;
use super::samples::{
    LameCylinder, ManufacturedField, MmsBoundaries, PaperEllipse, PrismMms, TrigonometricExact,
};
use crate::discretisation::Discretisation;
use crate::error::ElasticityError;
use crate::finite_element::{
    DisplacementErrors, ElementOrder, HighOrderNavier, VolumetricIntegration,
};
use crate::verification::{GridLevel, Study, StudyPoint};

/// The manufactured-solution problem of [`PrismMms`] (same field, forcing and boundary sets
/// as [`PrismMms::operator`]) on an `n2 x n3` grid, with its exact solution.
///
/// # Errors
/// Grid or geometry errors.
pub fn mms_parts(
    mms: &PrismMms,
    level: GridLevel,
) -> Result<(ProblemParts, Arc<TrigonometricExact>), ElasticityError> {
    mms.parts(level)
}

/// The Lamé cylinder of [`LameCylinder`] on a periodic `n2 x n3` grid, with `v^2 = 0` pinned
/// on `x3 = 0` at `x2 = 0, pi/2, pi` (needs `n2` divisible by 4). The three pins stop both
/// rigid translations and the rotation, so the matrix is nonsingular (and, for the finite
/// elements, positive definite) rather than nearly singular; they are exact because the
/// solution has `v^2 = 0` everywhere. ([`LameCylinder::operator`] pins the rotation only.)
///
/// # Errors
/// [`ElasticityError::InvalidParameter`] for `n2` not divisible by 4; grid or geometry errors.
pub fn lame_parts(lame: &LameCylinder, level: GridLevel) -> Result<ProblemParts, ElasticityError> {
    if !level.n2.is_multiple_of(4) {
        return Err(ElasticityError::InvalidParameter {
            field: "grid.n2",
            value: level.n2 as f64,
            allowed: "multiples of 4 (pins at x2 = 0, pi/2, pi)",
        });
    }
    lame.parts_pinned(level, &[0, level.n2 / 4, level.n2 / 2])
}

/// The paper's linear stand-in of [`PaperEllipse`] (same conditions as
/// [`PaperEllipse::operator`]) on an `n2 x n3` grid.
///
/// # Errors
/// Grid or geometry errors.
pub fn paper_parts(
    paper: &PaperEllipse,
    level: GridLevel,
) -> Result<ProblemParts, ElasticityError> {
    paper.parts(level)
}

/// A reference problem with a known solution for the finite-element studies.
#[derive(Debug, Clone)]
pub enum FemProblem {
    /// A manufactured solution on a prism.
    Mms(PrismMms),
    /// The Lamé cylinder (exact).
    Lame(LameCylinder),
}

/// A finite-element convergence study: the problem of a finite-difference study, same grids,
/// with Q1 or Q2 elements (orders 1 and 2 of [`HighOrderNavier`],
/// [`HighOrderNavier::with_element`]). The L2 error is the RMS over the parameter rectangle of the
/// Cartesian displacement error of the finite-element interpolant, integrated by a
/// `(k + 2)`-point Gauss rule per direction; the max error is over the nodes.
#[derive(Debug, Clone)]
pub struct FemStudy {
    /// The problem.
    pub problem: FemProblem,
    /// The element.
    pub order: ElementOrder,
    /// How the volumetric part of the stiffness is integrated (default `full`).
    pub volumetric: VolumetricIntegration,
}

impl FemStudy {
    /// The study of `problem` with `order` (full integration).
    pub fn new(problem: FemProblem, order: ElementOrder) -> Self {
        Self {
            problem,
            order,
            volumetric: VolumetricIntegration::Full,
        }
    }

    /// The same study with the volumetric part integrated as `volumetric` says.
    pub fn with_volumetric(self, volumetric: VolumetricIntegration) -> Self {
        Self { volumetric, ..self }
    }

    /// Solves on one grid (sparse Cholesky) and returns `dx3` and every error norm of
    /// [`HighOrderNavier::displacement_errors`] (the relative L2 error is
    /// `l2 / l2_exact`).
    ///
    /// # Errors
    /// Any error of building or solving the problem.
    pub fn errors(&self, level: GridLevel) -> Result<(f64, DisplacementErrors), ElasticityError> {
        let (op, errors) = match &self.problem {
            FemProblem::Mms(m) => {
                let (parts, exact) = mms_parts(m, level)?;
                let op = HighOrderNavier::with_element(parts, self.order, self.volumetric)?;
                let v = solve_backward_stable(&op)?;
                let f = |x: [f64; 2]| exact.field.displacement(x).value;
                let e = op.displacement_errors(&v, &f)?;
                (op, e)
            }
            FemProblem::Lame(l) => {
                let parts = lame_parts(l, level)?;
                let op = HighOrderNavier::with_element(parts, self.order, self.volumetric)?;
                let v = solve_backward_stable(&op)?;
                let field = l.field();
                let f = |x: [f64; 2]| field.displacement(x).value;
                let e = op.displacement_errors(&v, &f)?;
                (op, e)
            }
        };
        Ok((op.grid().dx3(), errors))
    }

    fn inner(&self) -> &dyn Study {
        match &self.problem {
            FemProblem::Mms(m) => m,
            FemProblem::Lame(l) => l,
        }
    }
}

impl Study for FemStudy {
    fn name(&self) -> String {
        self.inner().name()
    }
    fn geometry(&self) -> String {
        self.inner().geometry()
    }
    fn discretisation(&self) -> &'static str {
        match (self.order, self.volumetric) {
            (order, VolumetricIntegration::Full) => order.method_name(),
            (ElementOrder::Q1, VolumetricIntegration::Reduced) => "fem-q1-sri",
            (ElementOrder::Q2, VolumetricIntegration::Reduced) => "fem-q2-sri",
        }
    }
    fn levels(&self) -> Vec<GridLevel> {
        self.inner().levels()
    }
    fn expected_order(&self) -> f64 {
        (self.order.degree() + 1) as f64
    }
    fn run_level(&self, level: GridLevel) -> Result<StudyPoint, ElasticityError> {
        let (h, errors) = self.errors(level)?;
        Ok(StudyPoint {
            level,
            h,
            max_error: errors.max,
            l2_error: errors.rms,
        })
    }
}

/// Largest accepted normwise backward error of a study's solve (see
/// [`solve_backward_stable`]).
const BACKWARD_ERROR_TOLERANCE: f64 = 1e-12;

/// Solves by sparse Cholesky and accepts the solution by its normwise backward error
/// `|b - A x|_inf / (|A|_inf |x|_inf + |b|_inf) <= 1e-12`.
///
/// The direct backends' default check, `|b - A x|_inf <= 1e-8 |b|_inf`, assumes
/// `|A| |x| ~ |b|`. As `nu -> 1/2` the solution is nearly divergence-free, so `|A x| = |b|` is
/// smaller than `|A| |x|` by about `lambda / mu`, and the rounding of the residual itself
/// (`~ eps |A| |x|`) exceeds `1e-8 |b|` at `nu = 0.4999999` (`lambda / mu = 5e6`) although the
/// factorisation is backward stable. The backward error measures what a direct solve can
/// guarantee at any `lambda`.
fn solve_backward_stable<D: Discretisation>(op: &D) -> Result<Vec<f64>, ElasticityError> {
    let system = op.system()?;
    let mut solver = capstan_solvers::SparseCholesky::new(capstan_solvers::DirectParams {
        residual_tolerance: 0.5, // checked below, by the backward error
        refinement_steps: 1,
        ..Default::default()
    })?;
    let x = system.solve(&mut solver)?;
    let n = x.len();
    let (mut ax, mut row_abs) = (vec![0.0; n], vec![0.0; n]);
    for ((r, c), a) in system.pattern.entries().zip(&system.values) {
        ax[r] += a * x[c];
        row_abs[r] += a.abs();
    }
    let inf = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let residual = ax
        .iter()
        .zip(&system.rhs)
        .fold(0.0f64, |m, (a, b)| m.max((b - a).abs()));
    let scale = inf(&row_abs) * inf(&x) + inf(&system.rhs);
    // a NaN residual fails too
    if residual.is_nan() || residual > BACKWARD_ERROR_TOLERANCE * scale {
        return Err(capstan_solvers::SolverError::Singular { pivot: None }.into());
    }
    Ok(x)
}

/// The finite-element studies of the registry: every finite-difference study with Q1 and Q2.
pub fn fem_studies() -> Vec<Box<dyn Study>> {
    let problems = [
        FemProblem::Mms(PrismMms::ellipse(0.5, MmsBoundaries::TractionContact)),
        FemProblem::Mms(PrismMms::ellipse(2.0, MmsBoundaries::BilateralContact)),
        FemProblem::Mms(PrismMms::expression_prism(MmsBoundaries::TractionContact)),
        FemProblem::Mms(PrismMms::expression_prism(MmsBoundaries::BilateralContact)),
        FemProblem::Lame(LameCylinder::default()),
    ];
    let mut out: Vec<Box<dyn Study>> = Vec::new();
    for order in [ElementOrder::Q1, ElementOrder::Q2] {
        for p in &problems {
            out.push(Box::new(FemStudy::new(p.clone(), order)));
        }
    }
    out
}
