//! The load continuation around a full-system Newton solve, shared by the assembled
//! ([`crate::contact::FullSystemSolver`]) and the matrix-free
//! ([`crate::contact::MatrixFreeNewton`]) solvers: Newton at the full loads from the stuck
//! start, and if that fails, the loads ramped up from zero with adaptive steps.

use capstan_friction::FrictionLaw;
use capstan_solvers::{Observer, Progress, SolveReport, SolveStage, SolverError};

use crate::contact::boundary_solver::ContactSettings;
use crate::contact::error::ContactError;
use crate::contact::loads::EndLoads;
use crate::contact::model::ContactModel;
use crate::contact::operator::ContactOperator;
use crate::contact::solution::{ContactSolution, SolveStats};

/// A full-system Newton solver as the continuation drives it.
pub(crate) trait LoadSteps<D, L: FrictionLaw<f64>> {
    /// The contact model.
    fn model(&self) -> &ContactModel<D, L>;

    /// The continuation settings.
    fn continuation(&self) -> ContactSettings;

    /// The stuck solution for `loads` (its work into `stats`).
    ///
    /// # Errors
    /// A failed linear solve.
    fn stuck_start(
        &self,
        loads: EndLoads,
        stats: &mut SolveStats,
    ) -> Result<Vec<f64>, ContactError>;

    /// One Newton solve for `loads` from `v`, its work into `stats`; the final residual norm.
    ///
    /// # Errors
    /// The Newton solve's failure.
    fn newton(
        &self,
        loads: EndLoads,
        v: &mut [f64],
        stats: &mut SolveStats,
        observer: &mut dyn Observer<f64>,
    ) -> Result<f64, SolverError>;
}

/// A Newton solve's work into `stats`; its final residual norm. A failed solve counts the
/// iterations its error names (an inner failure reporting `NotConverged` is not counted).
///
/// # Errors
/// The solve's own error.
pub(crate) fn tally(
    result: Result<SolveReport<f64>, SolverError>,
    stats: &mut SolveStats,
) -> Result<f64, SolverError> {
    match result {
        Ok(report) => {
            stats.newton_iterations += report.iterations;
            stats.factorisations += report.factorisations;
            stats.linear_iterations += report.linear_iterations;
            Ok(report.residuals.last().copied().unwrap_or(0.0))
        }
        Err(e) => {
            stats.newton_iterations += match &e {
                SolverError::Stagnated { iterations, .. } => *iterations,
                SolverError::Diverged { iteration, .. } => *iteration,
                _ => 0,
            };
            Err(e)
        }
    }
}

/// Whether the model is unilateral and every contact node has separated at `v`.
pub(crate) fn all_separated<D, L: FrictionLaw<f64>>(
    model: &ContactModel<D, L>,
    loads: EndLoads,
    v: &[f64],
) -> bool {
    model.unilateral().is_some_and(|u| {
        let rhs = model.rhs(loads);
        !u.contact_set(v, &rhs).iter().any(|&c| c)
    })
}

/// [`ContactError::LiftedOff`] for the loads.
fn lifted_off<D, L: FrictionLaw<f64>>(model: &ContactModel<D, L>, loads: EndLoads) -> ContactError {
    ContactError::LiftedOff {
        ratio: loads.tension_ratio(),
        nodes: model.unilateral().map_or(0, |u| u.rows.len()),
    }
}

/// [`ContactError::LiftedOff`] if every contact node has separated at `v` ([`all_separated`]).
///
/// # Errors
/// That one.
pub(crate) fn check_lift_off<D, L: FrictionLaw<f64>>(
    model: &ContactModel<D, L>,
    loads: EndLoads,
    v: &[f64],
) -> Result<(), ContactError> {
    if all_separated(model, loads, v) {
        return Err(lifted_off(model, loads));
    }
    Ok(())
}

/// Solves for `loads` by Newton from `v` (the stuck start for the loads); if that fails, by
/// load continuation: `lambda` from 0 to 1 in steps that grow by 1.5 after a converged step
/// and halve after a failed one, each step's Newton from the last converged solution scaled to
/// the new load (from the stuck start for the first), every converged step reported as a
/// [`SolveStage::Continuation`] event.
///
/// # Math
/// ```text
/// R(v; lambda loads) = 0,  v_start(lambda') = (lambda' / lambda) v(lambda)    (R linear in the loads
///                                                                         but for the friction)
/// ```
///
/// # Errors
/// An interrupted solve or a spent iterative budget (at once: a smaller load step does not
/// make the linear solves cheaper); [`ContactError::LiftedOff`] when the last attempt ended
/// with the body off the obstacle; [`ContactError::NotConverged`] when the load step falls
/// below `min_load_step` or the steps run out, [`ContactError::LoadStepFailed`] instead when
/// the last failed step's solve had no residual (a singular Jacobian: its error, not `inf`).
pub(crate) fn solve_continued<D: ContactOperator, L: FrictionLaw<f64>, S: LoadSteps<D, L>>(
    steps: &S,
    loads: EndLoads,
    mut v: Vec<f64>,
    mut stats: SolveStats,
    observer: &mut dyn Observer<f64>,
) -> Result<ContactSolution, ContactError> {
    let model = steps.model();
    let first = steps.newton(loads, &mut v, &mut stats, observer);
    if let Err(e @ (SolverError::Interrupted { .. } | SolverError::BudgetSpent { .. })) = first {
        return Err(e.into());
    }
    if first.is_err() {
        let c = steps.continuation();
        let mut lambda = 0.0;
        let mut current = vec![0.0; v.len()];
        let mut step = c.initial_load_step;
        stats.continuation_steps = 0;
        let mut last = f64::INFINITY;
        // the last failed step when its solve failed without a residual: (load factor, why)
        let mut failure: Option<(f64, SolverError)> = None;
        let mut separated = all_separated(model, loads, &v);
        while lambda < 1.0 && stats.continuation_steps < c.max_continuation_steps {
            stats.continuation_steps += 1;
            let next = (lambda + step).min(1.0);
            let mut trial: Vec<f64> = if lambda > 0.0 {
                current.iter().map(|x| x * next / lambda).collect()
            } else {
                steps.stuck_start(loads.scaled(next), &mut stats)?
            };
            match steps.newton(loads.scaled(next), &mut trial, &mut stats, observer) {
                Ok(residual) => {
                    observer.iteration(&Progress::new(
                        SolveStage::Continuation,
                        stats.continuation_steps,
                        residual,
                        next - lambda,
                    ));
                    lambda = next;
                    current = trial;
                    step = (step * 1.5).min(1.0);
                }
                Err(e @ (SolverError::Interrupted { .. } | SolverError::BudgetSpent { .. })) => {
                    return Err(e.into());
                }
                Err(e) => {
                    separated = all_separated(model, loads.scaled(next), &trial);
                    (last, failure) = match e {
                        SolverError::Stagnated { residual, .. }
                        | SolverError::NotConverged { residual, .. }
                        | SolverError::Diverged { residual, .. } => (residual, None),
                        e => (f64::INFINITY, Some((next, e))),
                    };
                    step *= 0.5;
                    if step < c.min_load_step {
                        break;
                    }
                }
            }
        }
        if lambda < 1.0 {
            if separated {
                // the last attempt ended with the body off the obstacle
                return Err(lifted_off(model, loads));
            }
            if let Some((attempted, source)) = failure {
                // no residual to report: the solver's own failure (a singular Jacobian, ...)
                return Err(ContactError::LoadStepFailed {
                    iterations: stats.newton_iterations,
                    load_factor: lambda,
                    attempted,
                    source,
                });
            }
            return Err(ContactError::NotConverged {
                iterations: stats.newton_iterations,
                residual: last,
                load_factor: lambda,
            });
        }
        v = current;
    }
    check_lift_off(model, loads, &v)?;
    Ok(ContactSolution::new(model, loads, v, stats)?)
}
