//! Choosing a linear backend by value (scene files, command lines).

use crate::direct_params::DirectParams;
use crate::error::SolverError;
use crate::iterative_params::IterativeParams;
use crate::linear_solver::LinearSolver;
use crate::relaxation::GaussSeidel;
use crate::relaxation::Jacobi;
use crate::sparse_cholesky::SparseCholesky;
use crate::sparse_lu::SparseLu;

/// The linear backends, by name: `lu`, `cholesky`, `jacobi`, `gauss-seidel`.
///
/// The same spelling is used by serde, [`FromStr`](core::str::FromStr) and [`Display`](core::fmt::Display).
///
/// # Example
/// ```
/// use capstan_solvers::LinearBackend;
/// let b: LinearBackend = "gauss-seidel".parse().unwrap();
/// assert_eq!(b, LinearBackend::GaussSeidel);
/// assert_eq!(b.to_string(), "gauss-seidel");
/// assert!("superlu".parse::<LinearBackend>().is_err());
/// let solver = LinearBackend::Lu.build(&Default::default()).unwrap();
/// assert_eq!(solver.last_iterations(), None); // direct backend
/// ```
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
#[serde(rename_all = "kebab-case")]
pub enum LinearBackend {
    /// [`SparseLu`]: general matrices.
    #[default]
    Lu,
    /// [`SparseCholesky`]: symmetric positive definite matrices.
    Cholesky,
    /// [`Jacobi`]: the paper's iterative baseline.
    Jacobi,
    /// [`GaussSeidel`].
    GaussSeidel,
}

named_variants!(LinearBackend {
    Lu => "lu",
    Cholesky => "cholesky",
    Jacobi => "jacobi",
    GaussSeidel => "gauss-seidel",
});

impl LinearBackend {
    /// Whether the backend factorises (direct) rather than iterates.
    pub fn is_direct(self) -> bool {
        matches!(self, Self::Lu | Self::Cholesky)
    }

    /// Builds the backend with default direct settings; `iterative` configures Jacobi and
    /// Gauss–Seidel and is ignored by the direct backends.
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] if the settings of the chosen backend are out of range.
    pub fn build(
        self,
        iterative: &IterativeParams,
    ) -> Result<Box<dyn LinearSolver<f64> + Send>, SolverError> {
        self.build_with(iterative, &DirectParams::default())
    }

    /// Builds the backend with explicit settings for both families.
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] if the settings of the chosen backend are out of range.
    pub fn build_with(
        self,
        iterative: &IterativeParams,
        direct: &DirectParams,
    ) -> Result<Box<dyn LinearSolver<f64> + Send>, SolverError> {
        Ok(match self {
            Self::Lu => Box::new(SparseLu::new(*direct)?),
            Self::Cholesky => Box::new(SparseCholesky::new(*direct)?),
            Self::Jacobi => Box::new(Jacobi::<f64>::new(*iterative)?),
            Self::GaussSeidel => Box::new(GaussSeidel::<f64>::new(*iterative)?),
        })
    }
}

crate::named::named_enum!(LinearBackend, "linear backend");

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn build_rejects_bad_iterative_params_only_for_iterative_backends() {
        let bad = IterativeParams {
            tolerance: -1.0,
            ..Default::default()
        };
        assert!(LinearBackend::Lu.build(&bad).is_ok());
        assert!(matches!(
            LinearBackend::Jacobi.build(&bad),
            Err(SolverError::InvalidParameter {
                field: "tolerance",
                ..
            })
        ));
    }
}
