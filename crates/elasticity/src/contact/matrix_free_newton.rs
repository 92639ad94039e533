//! The full-system Newton of a matrix-free model: inexact Newton–Krylov (Eisenstat–Walker
//! forcing), each step GMRES on `A + F` (the matrix-free bulk and the face's friction
//! Jacobian) preconditioned by the V-cycle on the matrix-free levels.

use capstan_friction::FrictionLaw;
use capstan_solvers::{
    CsrMatrix, EisenstatWalker, InexactNewtonParams, KrylovMethod, KrylovParams, KrylovReport,
    LineSearch, NewtonKrylovProblem, Observer, Progress, SilentObserver, SolveStage, SolverError,
    inexact_newton, krylov_solve_operator,
};

use crate::contact::boundary_solver::ContactSettings;
use crate::contact::error::ContactError;
use crate::contact::load_continuation::{LoadSteps, solve_continued, tally};
use crate::contact::loads::EndLoads;
use crate::contact::model::ContactModel;
use crate::contact::operator::{ContactOperator, MatrixFreeBulk};
use crate::contact::solution::{ContactSolution, SolveStats};
use crate::error::ElasticityError;

/// Settings of [`MatrixFreeNewton`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MatrixFreeSettings {
    /// Tolerance (`|R|_2 <= tolerance max(1, |b|_2)`), Newton steps per load step, load
    /// continuation (shared with the other contact solvers).
    pub continuation: ContactSettings,
    /// The Krylov method of every step (GMRES; its `tolerance` is the stuck start's, the
    /// Newton steps take the forcing terms), `max_iterations` per step.
    pub krylov: KrylovParams,
    /// The forcing terms of the inexact Newton steps.
    pub forcing: EisenstatWalker,
    /// Krylov iterations summed over one Newton solve (a load step).
    pub max_linear_iterations: usize,
}

impl Default for MatrixFreeSettings {
    fn default() -> Self {
        Self {
            continuation: ContactSettings::default(),
            krylov: KrylovParams {
                method: KrylovMethod::Gmres,
                tolerance: 1e-8,
                max_iterations: 500,
                restart: 40,
            },
            forcing: EisenstatWalker::default(),
            max_linear_iterations: 20_000,
        }
    }
}

/// One Newton solve's problem: the model's residual under fixed loads and its Jacobian
/// `A + F` by its action.
struct Step<'m, D, L: FrictionLaw<f64>> {
    model: &'m ContactModel<D, L>,
    bulk: &'m (dyn MatrixFreeBulk + Send + Sync),
    rhs: Vec<f64>,
    values: Vec<f64>,
    /// The smoothers' eigenvalue estimates of the first Newton step, reused by the later
    /// steps of the same solve (the face term changes little of the spectrum of
    /// `D^-1 (A + F)`; a power iteration per step costs as much as a few Krylov iterations).
    estimates: Option<Vec<f64>>,
}

impl<D, L: FrictionLaw<f64>> Step<'_, D, L> {
    /// GMRES on `A + F` with the V-cycle of `A + F`.
    fn solve_with(
        &mut self,
        face: CsrMatrix,
        b: &[f64],
        d: &mut [f64],
        params: &KrylovParams,
        observer: &mut dyn Observer<f64>,
    ) -> Result<KrylovReport, SolverError> {
        let step = self.bulk.step_operator(face.clone());
        let mut pre = self
            .bulk
            .preconditioner(
                std::sync::Arc::clone(&step),
                &face,
                self.estimates.as_deref(),
            )
            .map_err(|e| SolverError::problem("preconditioner", e))?;
        if self.estimates.is_none() {
            self.estimates = Some(pre.estimates());
        }
        krylov_solve_operator(step.as_ref(), b, d, &mut pre, params, observer)
    }
}

impl<D, L: FrictionLaw<f64>> NewtonKrylovProblem for Step<'_, D, L> {
    fn residual(&mut self, u: &[f64], r: &mut [f64]) -> Result<(), SolverError> {
        self.model.residual_into(&self.rhs, u, r)?;
        Ok(())
    }

    fn solve_step(
        &mut self,
        u: &[f64],
        b: &[f64],
        d: &mut [f64],
        params: &KrylovParams,
        observer: &mut dyn Observer<f64>,
    ) -> Result<KrylovReport, SolverError> {
        self.model
            .jacobian_with(&self.rhs, u, &mut self.values, None);
        let face = CsrMatrix::from_pattern(&self.model.extended().pattern, &self.values)?;
        self.solve_with(face, b, d, params, observer)
    }
}

/// Inexact Newton–Krylov on the full residual of a matrix-free model
/// ([`ContactModel::is_matrix_free`], e.g. [`crate::solid::SolidBody::matrix_free_model`]),
/// with load continuation when the first attempt fails.
///
/// # Math
/// ```text
/// R(v)    = A v - b - sum_k w_k e_row_k t_k(v)             (A by its action, never assembled)
/// J(v)    = A + F(v),  F the friction Jacobian of the face (ContactModel::jacobian_into on
///           the face-only pattern)
/// step k: GMRES on J d = -R to |J d + R| <= eta_k |R|  (Eisenstat–Walker), preconditioned by
///         a V-cycle: fine level J by its action (Chebyshev–Jacobi on diag(A) + diag(F), its
///         interval up to 1.1 x 1.15 x the power estimate of lambda_max: MATRIX_FREE_ESTIMATE_MARGIN),
///         coarse level A_c + P^T F P assembled (A_c the rediscretised Q1 operator); for
///         p >= 4 matrix-free p-levels A_l + F_l in between (F_{l+1} = P_l^T F_l P_l)
/// start:  the stuck solution (A + S) v = b, S = 1e4 max(|A_ii|, 1) on the tangential contact
///         entries (as the assembled full-system Newton), by the same GMRES
/// ```
/// The answer is the assembled full-system Newton's (same residual, same tolerance); only the
/// linear algebra differs.
pub struct MatrixFreeNewton<'a, D, L: FrictionLaw<f64>> {
    model: &'a ContactModel<D, L>,
    bulk: &'a (dyn MatrixFreeBulk + Send + Sync),
    settings: MatrixFreeSettings,
}

impl<D, L: FrictionLaw<f64>> core::fmt::Debug for MatrixFreeNewton<'_, D, L> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("MatrixFreeNewton")
            .field("settings", &self.settings)
            .finish_non_exhaustive()
    }
}

impl<'a, D: ContactOperator, L: FrictionLaw<f64>> MatrixFreeNewton<'a, D, L> {
    /// Checks the model and the settings.
    ///
    /// # Errors
    /// [`ContactError::Unsupported`] naming `solver.linear` for an assembled model, naming
    /// `contact.kind` for unilateral contact; invalid settings.
    pub fn new(
        model: &'a ContactModel<D, L>,
        settings: MatrixFreeSettings,
    ) -> Result<Self, ContactError> {
        settings.continuation.validate()?;
        settings.krylov.validate()?;
        settings.forcing.validate()?;
        if settings.max_linear_iterations == 0 {
            return Err(ContactError::from(ElasticityError::InvalidParameter {
                field: "solver.max_sweeps",
                value: 0.0,
                allowed: "[1, inf)",
            }));
        }
        let Some(bulk) = model.matrix_free_bulk() else {
            return Err(ContactError::Unsupported {
                field: "solver.linear",
                message: "the matrix-free Newton needs a matrix-free model (body.dimension = 3 with solver.linear = \"matrix-free-mg\")",
            });
        };
        if model.is_unilateral() {
            return Err(ContactError::Unsupported {
                field: "contact.kind",
                message: "unilateral contact is not solved matrix-free yet; use solver.linear = \"lu\" or \"multigrid\"",
            });
        }
        Ok(Self {
            model,
            bulk,
            settings,
        })
    }

    /// The stuck solution for `loads`: `(A + S) v = b` by GMRES and the V-cycle of `A + S`.
    fn stuck(&self, loads: EndLoads) -> Result<(Vec<f64>, usize), ContactError> {
        let model = self.model;
        let ext = model.extended();
        let diagonal = self.bulk.bulk().diagonal();
        let mut values = vec![0.0; ext.pattern.nnz()];
        for (&slot, &k) in ext.tangential_slot.iter().zip(model.active()) {
            let dof = model.contact_nodes()[k].tangential_dof;
            values[slot] += 1e4 * diagonal[dof].abs().max(1.0);
        }
        let face = CsrMatrix::from_pattern(&ext.pattern, &values)?;
        let mut step = Step {
            model,
            bulk: self.bulk,
            rhs: Vec::new(),
            values: Vec::new(),
            estimates: None,
        };
        let rhs = model.rhs(loads);
        let mut v = vec![0.0; model.dof_count()];
        let report = step.solve_with(
            face,
            &rhs,
            &mut v,
            &self.settings.krylov,
            &mut SilentObserver,
        )?;
        Ok((v, report.iterations))
    }

    /// Solves for the loads ([`MatrixFreeNewton::solve_observed`] with no observer).
    ///
    /// # Errors
    /// See [`MatrixFreeNewton::solve_observed`].
    pub fn solve(&self, loads: EndLoads) -> Result<ContactSolution, ContactError> {
        self.solve_observed(loads, &mut SilentObserver)
    }

    /// Solves for the loads from the stuck start, with load continuation (halving and
    /// growing the load step as the assembled full-system Newton) if Newton fails; every
    /// Newton iterate ([`SolveStage::Newton`]), Krylov iteration ([`SolveStage::Krylov`]) and
    /// converged load step ([`SolveStage::Continuation`]) goes to `observer`.
    ///
    /// # Errors
    /// Invalid loads; [`ContactError::NotConverged`] (or [`ContactError::LoadStepFailed`])
    /// when the continuation fails;
    /// [`SolverError::BudgetSpent`] (inside [`ContactError::Solver`]) naming
    /// `solver.max_sweeps` when the Krylov total of a Newton solve is spent, or
    /// `krylov.max_iterations` for the stuck start; an interrupted solve.
    pub fn solve_observed(
        &self,
        loads: EndLoads,
        observer: &mut dyn Observer<f64>,
    ) -> Result<ContactSolution, ContactError> {
        loads.check()?;
        let (v, start_iterations) = self.stuck(loads)?;
        let stats = SolveStats {
            method: "full-newton",
            newton_iterations: 0,
            continuation_steps: 1,
            residual: 0.0,
            linear_iterations: start_iterations,
            factorisations: 1,
        };
        solve_continued(self, loads, v, stats, observer)
    }
    /// Solves for the loads by Newton from `start` (e.g. a coarser grid's solution
    /// prolonged, [`crate::solid::SolidBody::solve_matrix_free_sequenced`]); if that Newton
    /// fails (or `start` is not finite), by [`MatrixFreeNewton::solve_observed`] from the
    /// stuck start, whose work is added. The answer is the same problem's: only the start
    /// differs.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `start` for a start of the wrong length;
    /// otherwise as [`MatrixFreeNewton::solve_observed`].
    pub fn solve_from_observed(
        &self,
        loads: EndLoads,
        start: &[f64],
        observer: &mut dyn Observer<f64>,
    ) -> Result<ContactSolution, ContactError> {
        loads.check()?;
        if start.len() != self.model.dof_count() {
            return Err(ContactError::from(ElasticityError::InvalidParameter {
                field: "start",
                value: start.len() as f64,
                allowed: "one value per unknown",
            }));
        }
        let mut stats = SolveStats {
            method: "full-newton",
            newton_iterations: 0,
            continuation_steps: 1,
            residual: 0.0,
            linear_iterations: 0,
            factorisations: 0,
        };
        let mut v = start.to_vec();
        if start.iter().all(|x| x.is_finite()) {
            match LoadSteps::newton(self, loads, &mut v, &mut stats, observer) {
                Ok(_) => {
                    return Ok(ContactSolution::new(self.model, loads, v, stats)?);
                }
                Err(e @ (SolverError::Interrupted { .. } | SolverError::BudgetSpent { .. })) => {
                    return Err(e.into());
                }
                Err(_) => {}
            }
        }
        let mut sol = self.solve_observed(loads, observer)?;
        sol.stats.newton_iterations += stats.newton_iterations;
        sol.stats.linear_iterations += stats.linear_iterations;
        Ok(sol)
    }
}

impl<D: ContactOperator, L: FrictionLaw<f64>> LoadSteps<D, L> for MatrixFreeNewton<'_, D, L> {
    fn model(&self) -> &ContactModel<D, L> {
        self.model
    }

    fn continuation(&self) -> ContactSettings {
        self.settings.continuation
    }

    fn stuck_start(
        &self,
        loads: EndLoads,
        stats: &mut SolveStats,
    ) -> Result<Vec<f64>, ContactError> {
        let (v, iterations) = self.stuck(loads)?;
        stats.linear_iterations += iterations;
        Ok(v)
    }

    fn newton(
        &self,
        loads: EndLoads,
        v: &mut [f64],
        stats: &mut SolveStats,
        observer: &mut dyn Observer<f64>,
    ) -> Result<f64, SolverError> {
        let rhs = self.model.rhs(loads);
        let b = rhs.iter().map(|x| x * x).sum::<f64>().sqrt();
        let params = InexactNewtonParams {
            max_iterations: self.settings.continuation.max_iterations,
            absolute_tolerance: self.settings.continuation.tolerance * b.max(1.0),
            max_linear_iterations: self.settings.max_linear_iterations,
            krylov: self.settings.krylov,
            forcing: self.settings.forcing,
            line_search: LineSearch::default(),
            divergence_limit: 1e8,
        };
        let mut step = Step {
            model: self.model,
            bulk: self.bulk,
            rhs,
            values: vec![0.0; self.model.extended().pattern.nnz()],
            estimates: None,
        };
        let mut counting = CountKrylov {
            inner: observer,
            iterations: 0,
        };
        let result = inexact_newton(&mut step, v, &params, &mut counting);
        if result.is_err() {
            stats.linear_iterations += counting.iterations;
        }
        tally(result, stats)
    }
}

/// Passes every event on, counting the Krylov iterations (for the statistics of a failed
/// Newton solve).
struct CountKrylov<'o> {
    inner: &'o mut dyn Observer<f64>,
    iterations: usize,
}

impl Observer<f64> for CountKrylov<'_> {
    fn iteration(&mut self, progress: &Progress<f64>) {
        if progress.stage == SolveStage::Krylov {
            self.iterations += 1;
        }
        self.inner.iteration(progress);
    }

    fn interrupted(&mut self) -> bool {
        self.inner.interrupted()
    }
}
