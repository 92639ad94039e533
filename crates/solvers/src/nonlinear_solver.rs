//! The nonlinear-solver capability and its report.

use crate::error::SolverError;
use crate::observer::Observer;
use crate::problem::Jacobian;
use crate::scalar::SolverScalar;

/// A solver for `r(u) = 0` that owns the iteration loop.
pub trait NonlinearSolver<F: SolverScalar> {
    /// Solves `problem.residual(u) = 0` starting from `u`, which holds the solution on success
    /// (and the last accepted iterate on failure). Progress goes to `observer`.
    ///
    /// # Errors
    /// [`SolverError::NotConverged`] at the iteration cap, [`SolverError::Diverged`],
    /// [`SolverError::Stagnated`], [`SolverError::NonFinite`] for a NaN/inf residual, Jacobian
    /// or step, [`SolverError::Singular`] and other linear-solver failures,
    /// [`SolverError::Problem`] when the problem's evaluation fails,
    /// [`SolverError::DimensionMismatch`] if `u` does not match the pattern.
    fn solve<P: Jacobian<F> + ?Sized>(
        &mut self,
        problem: &P,
        u: &mut [F],
        observer: &mut dyn Observer<F>,
    ) -> Result<SolveReport<F>, SolverError>;
}

/// What a successful nonlinear solve did.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct SolveReport<F> {
    /// Nonlinear iterations (accepted steps).
    pub iterations: usize,
    /// `|r(u_k)|_2` for `k = 0 ..= iterations`.
    pub residuals: Vec<F>,
    /// Numeric factorisations (or iterative-solver preparations) of the Jacobian.
    pub factorisations: usize,
    /// Inner linear iterations summed over all steps (0 for direct backends).
    pub linear_iterations: usize,
}

impl<F: SolverScalar> SolveReport<F> {
    /// A report from its parts (for solvers written in other crates).
    pub fn new(
        iterations: usize,
        residuals: Vec<F>,
        factorisations: usize,
        linear_iterations: usize,
    ) -> Self {
        Self {
            iterations,
            residuals,
            factorisations,
            linear_iterations,
        }
    }

    /// The last residual norm, `None` if the history is empty.
    pub fn final_residual(&self) -> Option<F> {
        self.residuals.last().copied()
    }
}
