//! A linear backend built outside this crate (PETSc, behind the facade's `petsc` feature),
//! named and constructed by a plain function so that settings holding it stay `Copy`.

use crate::error::SolverError;
use crate::linear_solver::LinearSolver;

/// The constructor of an external linear backend.
pub type ExternalLinearBuild = fn() -> Result<Box<dyn LinearSolver<f64> + Send>, SolverError>;

/// A linear backend from another crate: its name (as in `solver.linear`) and a constructor.
///
/// The constructor takes no arguments: an external engine reads its settings from its own
/// global state (PETSc: the options database filled from `solver.petsc_options`). Two values
/// are equal when their names are.
///
/// # Example
/// ```
/// use capstan_solvers::{ExternalLinear, LinearBackend, LinearSolver, SolverError};
/// fn lu() -> Result<Box<dyn LinearSolver<f64> + Send>, SolverError> {
///     LinearBackend::Lu.build(&Default::default())
/// }
/// let external = ExternalLinear { name: "lu-again", build: lu };
/// let solver = (external.build)().unwrap();
/// assert_eq!(solver.last_iterations(), None);
/// assert_eq!(format!("{external:?}"), "ExternalLinear(\"lu-again\")");
/// ```
#[derive(Clone, Copy)]
pub struct ExternalLinear {
    /// The backend's name (`"petsc"`).
    pub name: &'static str,
    /// Builds a fresh solver (called once per Newton solve and once for a starting guess).
    pub build: ExternalLinearBuild,
}

impl PartialEq for ExternalLinear {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
    }
}

impl core::fmt::Debug for ExternalLinear {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_tuple("ExternalLinear").field(&self.name).finish()
    }
}
