//! Choosing a nonlinear solver by value.

use crate::error::SolverError;
use crate::jacobi_newton::JacobiNewton;
use crate::newton::{Newton, NewtonParams, solve_with_newton};

/// The nonlinear methods, by name: `newton`, `jacobi-newton`.
///
/// # Example
/// ```
/// use capstan_solvers::{NonlinearMethod, NonlinearSolver, SilentObserver, samples::CubicReaction};
/// let method: NonlinearMethod = "jacobi-newton".parse().unwrap();
/// assert_eq!(method.to_string(), "jacobi-newton");
/// let problem = CubicReaction::new(8);
/// let mut u = vec![0.0; 8];
/// let mut solver = method.build(Default::default()).unwrap();
/// solver.solve(&problem, &mut u, &mut SilentObserver).unwrap();
/// assert!((u[3] - problem.exact_solution()[3]).abs() < 1e-9);
/// ```
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "kebab-case")]
pub enum NonlinearMethod {
    /// [`Newton`] with the backend of `NewtonParams::linear`.
    #[default]
    Newton,
    /// [`JacobiNewton`].
    JacobiNewton,
}

named_variants!(NonlinearMethod {
    Newton => "newton",
    JacobiNewton => "jacobi-newton",
});

impl NonlinearMethod {
    /// Builds the solver.
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] if a setting is out of range.
    pub fn build(self, params: NewtonParams) -> Result<AnyNonlinearSolver, SolverError> {
        Ok(match self {
            Self::Newton => AnyNonlinearSolver::Newton(Newton::new(params)?),
            Self::JacobiNewton => AnyNonlinearSolver::JacobiNewton(JacobiNewton::new(params)?),
        })
    }
}

crate::named::named_enum!(NonlinearMethod, "nonlinear method");

/// A nonlinear solver chosen at run time ([`NonlinearSolver::solve`](crate::NonlinearSolver::solve) is generic, so the
/// choice is an enum rather than a trait object).
#[derive(Debug)]
#[non_exhaustive]
pub enum AnyNonlinearSolver {
    /// Newton's method.
    Newton(Newton),
    /// Jacobi–Newton.
    JacobiNewton(JacobiNewton),
}

solve_with_newton!(AnyNonlinearSolver, |solver| match solver {
    AnyNonlinearSolver::Newton(s) => s,
    AnyNonlinearSolver::JacobiNewton(s) => s.newton_mut(),
});
