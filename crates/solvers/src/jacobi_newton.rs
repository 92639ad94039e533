//! Jacobi–Newton: the paper's baseline nonlinear solver.

use crate::error::SolverError;
use crate::newton::{Newton, NewtonParams, solve_with_newton};
use crate::observer::SolveStage;
use crate::relaxation::Jacobi;

/// Newton's outer iteration with Jacobi inner iterations for each linear system: the
/// "iterative-Jacobi finite-difference method with Newton's method" of the paper (§ 3).
///
/// The inner Jacobi iteration stops at its own relative tolerance `params.iterative.tolerance`
/// (so the Newton step is inexact and convergence is at best linear with a rate of about that
/// tolerance once it dominates); `params.linear` is ignored. Jacobi needs a diagonally
/// dominant Jacobian; otherwise the inner iteration fails with
/// [`SolverError::NotConverged`].
///
/// # Math
/// ```text
/// J(u_k) du_k ~= -r(u_k)   by   du <- du + D^-1 (-r - J du),  D = diag J,  du_0 = 0
/// u_{k+1} = u_k + alpha_k du_k
/// ```
///
/// # Errors
/// See [`NonlinearSolver::solve`](crate::NonlinearSolver::solve); inner failures are passed through.
///
/// # Example
/// ```
/// use capstan_solvers::{JacobiNewton, NonlinearSolver, SilentObserver, samples::CubicReaction};
/// let problem = CubicReaction::new(10);
/// let mut u = vec![0.0; 10];
/// let report = JacobiNewton::new(Default::default()).unwrap()
///     .solve(&problem, &mut u, &mut SilentObserver).unwrap();
/// assert!(report.linear_iterations > report.iterations);
/// assert!((u[4] - problem.exact_solution()[4]).abs() < 1e-9);
/// ```
#[derive(Debug)]
pub struct JacobiNewton {
    newton: Newton,
}

impl JacobiNewton {
    /// Jacobi–Newton with the outer settings of `params` and inner settings
    /// `params.iterative`.
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] if a setting is out of range.
    pub fn new(params: NewtonParams) -> Result<Self, SolverError> {
        let inner = Jacobi::<f64>::new(params.iterative)?;
        let mut newton = Newton::with_linear_solver(params, Box::new(inner))?;
        newton.stage = SolveStage::JacobiNewton;
        Ok(Self { newton })
    }

    /// The settings in use.
    pub fn params(&self) -> &NewtonParams {
        self.newton.params()
    }

    /// The Newton iteration over the Jacobi backend that does the solves.
    pub(crate) fn newton_mut(&mut self) -> &mut Newton {
        &mut self.newton
    }
}

solve_with_newton!(JacobiNewton, |solver| &mut solver.newton);
