//! Settings shared by the direct (factorising) backends, and their solution check.

use crate::error::SolverError;
use crate::lu_kind::LuKind;
use crate::ordering::ColumnOrdering;

/// Settings of the direct backends ([`crate::SparseLu`], [`crate::SparseCholesky`]).
///
/// faer factorises a numerically singular matrix "successfully" and its solve then returns
/// huge or non-finite numbers. Every direct solve is therefore checked: the solution must be
/// finite and its residual small relative to the right-hand side; if not, up to
/// `refinement_steps` steps of iterative refinement are tried before the matrix is declared
/// singular.
///
/// # Math
/// ```text
/// accept x  iff  x finite  and  |b - A x|_inf <= residual_tolerance * |b|_inf
/// refinement:    d = A^-1 (b - A x),  x <- x + d
/// ```
/// A backward-stable factorisation gives `|b - A x| / |b| <~ cond(A) * eps`, so the default
/// `1e-8` accepts condition numbers up to about `1e7`.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DirectParams {
    /// Largest accepted `|b - A x|_inf / |b|_inf` (in `(0, 1)`).
    pub residual_tolerance: f64,
    /// Iterative-refinement steps tried when the check fails (0 disables refinement).
    pub refinement_steps: usize,
    /// Cholesky only: largest accepted `|a_ij - a_ji| / max |a|` (in `[0, 1)`).
    pub symmetry_tolerance: f64,
    /// Fill-reducing ordering computed by `analyse` (default: the backend's own: AMD on
    /// `A + A^T` for the multifrontal LU, COLAMD for the supernodal LU, AMD for Cholesky).
    pub ordering: ColumnOrdering,
    /// LU only: the factorisation kernel (default [`LuKind::Auto`], the multifrontal kernel).
    pub lu_kind: LuKind,
}

impl Default for DirectParams {
    fn default() -> Self {
        Self {
            residual_tolerance: 1e-8,
            refinement_steps: 2,
            symmetry_tolerance: 1e-10,
            ordering: ColumnOrdering::Auto,
            lu_kind: LuKind::Auto,
        }
    }
}

impl DirectParams {
    /// Checks every field.
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), SolverError> {
        SolverError::check_fraction("residual_tolerance", self.residual_tolerance)?;
        if !(self.symmetry_tolerance >= 0.0 && self.symmetry_tolerance < 1.0) {
            return Err(SolverError::invalid(
                "symmetry_tolerance",
                self.symmetry_tolerance,
                "[0, 1)",
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_params_are_valid_and_bad_ones_rejected() {
        DirectParams::default().validate().unwrap();
        let bad = DirectParams {
            residual_tolerance: 0.0,
            ..Default::default()
        };
        assert!(matches!(
            bad.validate(),
            Err(SolverError::InvalidParameter {
                field: "residual_tolerance",
                ..
            })
        ));
        let bad = DirectParams {
            symmetry_tolerance: f64::NAN,
            ..Default::default()
        };
        assert!(bad.validate().is_err());
    }
}
