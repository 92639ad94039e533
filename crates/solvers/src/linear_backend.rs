//! Choosing a linear backend by value (scene files, command lines, settings structs): a handle
//! to a registered entry ([`crate::linear_registry`]).

use core::fmt;
use core::hash::{Hash, Hasher};

use crate::error::SolverError;
use crate::linear_registration::{
    BackendKind, BoxedLinearSolver, LinearContext, LinearSettings, RegisteredLinearSolver,
};
use crate::linear_registry;

/// A registered linear backend, by name: the built-ins `lu`, `cholesky`, `jacobi`,
/// `gauss-seidel`, `multigrid`, and whatever [`linear_registry::register`] added.
///
/// A small `Copy` handle, so settings structs that hold one stay `Copy`. The same spelling is
/// used by serde, [`FromStr`](core::str::FromStr) and [`Display`](fmt::Display); two handles
/// are equal when their names are.
///
/// # Example
/// ```
/// use capstan_solvers::LinearBackend;
/// let b: LinearBackend = "gauss-seidel".parse().unwrap();
/// assert_eq!(b, LinearBackend::GAUSS_SEIDEL);
/// assert_eq!(b.to_string(), "gauss-seidel");
/// assert!("superlu".parse::<LinearBackend>().is_err());
/// let solver = LinearBackend::LU.build(&Default::default(), &()).unwrap();
/// assert_eq!(solver.last_iterations(), None); // direct backend
/// ```
#[derive(Clone, Copy)]
pub struct LinearBackend(&'static RegisteredLinearSolver);

impl LinearBackend {
    /// [`crate::SparseLu`]: general matrices (the default).
    pub const LU: Self = Self(&linear_registry::LU_REGISTRATION);
    /// [`crate::SparseCholesky`]: symmetric positive definite matrices.
    pub const CHOLESKY: Self = Self(&crate::sparse_cholesky::REGISTRATION);
    /// [`crate::Jacobi`]: the paper's iterative baseline.
    pub const JACOBI: Self = Self(&crate::relaxation::JACOBI_REGISTRATION);
    /// [`crate::GaussSeidel`].
    pub const GAUSS_SEIDEL: Self = Self(&crate::relaxation::GAUSS_SEIDEL_REGISTRATION);
    /// [`crate::KrylovSolver`] preconditioned by a V-cycle on the caller's hierarchy
    /// ([`LinearContext::prolongations`]).
    pub const MULTIGRID: Self = Self(&crate::krylov_solver::REGISTRATION);
    /// The matrix-free Newton–Krylov of the 3-D body (`matrix-free-mg`,
    /// [`BackendKind::MatrixFree`]).
    pub const MATRIX_FREE_MG: Self = Self(&crate::operator_multigrid::MATRIX_FREE_REGISTRATION);

    /// The handle of a registered entry.
    pub fn of(entry: &'static RegisteredLinearSolver) -> Self {
        Self(entry)
    }

    /// Every registered backend ([`linear_registry::registry`]).
    pub fn all() -> Vec<Self> {
        linear_registry::registry().into_iter().map(Self).collect()
    }

    /// The backend registered as `name`, `None` if there is none.
    pub fn from_name(name: &str) -> Option<Self> {
        linear_registry::find(name).map(Self)
    }

    /// The name as used in files.
    pub fn name(self) -> &'static str {
        self.0.name
    }

    /// The registered entry (summary, parameters, builder).
    pub fn registration(self) -> &'static RegisteredLinearSolver {
        self.0
    }

    /// Whether the backend factorises (direct) rather than iterates.
    pub fn is_direct(self) -> bool {
        self.0.kind == BackendKind::Direct
    }

    /// How it solves ([`BackendKind`]).
    pub fn kind(self) -> BackendKind {
        self.0.kind
    }

    /// Builds the backend from `settings` for matrices described by `context` (`&()` for
    /// nothing known).
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] if a setting the backend reads is out of range, or
    /// the context lacks what it needs (`multigrid` without a hierarchy).
    pub fn build(
        self,
        settings: &LinearSettings,
        context: &dyn LinearContext,
    ) -> Result<BoxedLinearSolver, SolverError> {
        (self.0.build)(settings, context)
    }
}

impl Default for LinearBackend {
    fn default() -> Self {
        Self::LU
    }
}

impl PartialEq for LinearBackend {
    fn eq(&self, other: &Self) -> bool {
        self.name() == other.name()
    }
}

impl Eq for LinearBackend {}

impl Hash for LinearBackend {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.name().hash(state);
    }
}

impl fmt::Debug for LinearBackend {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "LinearBackend({:?})", self.name())
    }
}

impl fmt::Display for LinearBackend {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl core::str::FromStr for LinearBackend {
    type Err = SolverError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::from_name(s).ok_or_else(|| SolverError::UnknownName {
            kind: "linear backend",
            name: s.to_owned(),
            allowed: linear_registry::names(),
        })
    }
}

impl serde::Serialize for LinearBackend {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

impl<'de> serde::Deserialize<'de> for LinearBackend {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let name = String::deserialize(deserializer)?;
        name.parse().map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::iterative_params::IterativeParams;

    #[test]
    fn build_rejects_bad_iterative_params_only_for_iterative_backends() {
        let bad = LinearSettings {
            iterative: IterativeParams {
                tolerance: -1.0,
                ..Default::default()
            },
            ..Default::default()
        };
        assert!(LinearBackend::LU.build(&bad, &()).is_ok());
        assert!(matches!(
            LinearBackend::JACOBI.build(&bad, &()),
            Err(SolverError::InvalidParameter {
                field: "tolerance",
                ..
            })
        ));
    }

    #[test]
    fn multigrid_needs_a_hierarchy_from_the_context() {
        assert!(matches!(
            LinearBackend::MULTIGRID.build(&LinearSettings::default(), &()),
            Err(SolverError::InvalidParameter {
                field: "linear",
                ..
            })
        ));
    }

    #[test]
    fn names_round_trip_through_display_fromstr_and_serde() {
        for b in LinearBackend::all() {
            assert_eq!(b.to_string().parse::<LinearBackend>().unwrap(), b);
            let json = serde_json::to_string(&b).unwrap();
            assert_eq!(json, format!("\"{}\"", b.name()));
            assert_eq!(serde_json::from_str::<LinearBackend>(&json).unwrap(), b);
        }
        let err = "Gauss-Seidel".parse::<LinearBackend>().unwrap_err();
        assert!(err.to_string().contains("gauss-seidel"));
        assert!(serde_json::from_str::<LinearBackend>("\"broyden\"").is_err());
    }
}
