//! The elasticity crate's error type.

use capstan_geometry::GeometryError;
use capstan_solvers::SolverError;

/// Everything that can go wrong while building or solving an elasticity problem.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ElasticityError {
    /// A parameter (material, grid, boundary data) is outside its allowed range.
    #[error("`{field}` = {value} is outside {allowed}")]
    InvalidParameter {
        /// The parameter, named as in a scene file (`body.young`, `grid.n2`, ...).
        field: &'static str,
        /// The offending value.
        value: f64,
        /// The allowed range.
        allowed: &'static str,
    },
    /// The chart is not invariant in `x1`, so the plane-strain reduction does not apply.
    #[error(
        "the plane-strain reduction needs an x1-invariant chart (a prism): {what} at (x1, x2, x3) = ({:.6}, {:.6}, {:.6})",
        at[0], at[1], at[2]
    )]
    NotPlaneStrain {
        /// Which geometric quantity fails to vanish.
        what: &'static str,
        /// Where.
        at: [f64; 3],
    },
    /// Boundary conditions that cannot be combined (e.g. periodic on one `x2` side only).
    #[error("inconsistent boundary conditions: {what}")]
    InconsistentBoundary {
        /// What is wrong.
        what: &'static str,
    },
    /// A vector has the wrong length.
    #[error("`{quantity}` has length {found}, expected {expected}")]
    DimensionMismatch {
        /// The vector.
        quantity: &'static str,
        /// Expected length.
        expected: usize,
        /// Actual length.
        found: usize,
    },
    /// A boundary or forcing function returned a non-finite value.
    #[error("non-finite {what} at (x2, x3) = ({:.6}, {:.6})", at[0], at[1])]
    NonFinite {
        /// Which datum.
        what: &'static str,
        /// Where.
        at: [f64; 2],
    },
    /// The geometry could not be evaluated.
    #[error(transparent)]
    Geometry(#[from] GeometryError),
    /// A linear or nonlinear solver failed.
    #[error(transparent)]
    Solver(#[from] SolverError),
    /// `discretisation.method` names no registered discretisation.
    #[error(
        "`discretisation.method` = \"{name}\" is not a registered discretisation; expected one of {known}"
    )]
    UnknownDiscretisation {
        /// The name asked for.
        name: String,
        /// The registered names, comma-separated.
        known: String,
    },
    /// A discretisation of that name is registered already.
    #[error("a discretisation named \"{name}\" is registered already")]
    DuplicateDiscretisation {
        /// The name.
        name: &'static str,
    },
}

impl ElasticityError {
    /// `Ok` if `found == expected`, else [`ElasticityError::DimensionMismatch`] for `quantity`.
    ///
    /// # Errors
    /// The mismatch.
    pub fn check_length(quantity: &'static str, expected: usize, found: usize) -> Result<(), Self> {
        if expected == found {
            Ok(())
        } else {
            Err(Self::DimensionMismatch {
                quantity,
                expected,
                found,
            })
        }
    }
}
