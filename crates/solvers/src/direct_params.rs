//! Settings shared by the direct (factorising) backends, and their solution check.

use crate::error::SolverError;
use crate::lu_kind::LuKind;
use crate::ordering::ColumnOrdering;
use crate::sparsity_pattern::SparsityPattern;

/// Settings of the direct backends ([`crate::SparseLu`], [`crate::SparseCholesky`],
/// [`crate::CondensedSolver`]).
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
        if !(self.residual_tolerance > 0.0 && self.residual_tolerance < 1.0) {
            return Err(SolverError::InvalidParameter {
                field: "residual_tolerance",
                value: self.residual_tolerance,
                allowed: "(0, 1)",
            });
        }
        if !(self.symmetry_tolerance >= 0.0 && self.symmetry_tolerance < 1.0) {
            return Err(SolverError::InvalidParameter {
                field: "symmetry_tolerance",
                value: self.symmetry_tolerance,
                allowed: "[0, 1)",
            });
        }
        Ok(())
    }
}

pub(crate) fn inf_norm(x: &[f64]) -> f64 {
    x.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
}

/// Checks (and refines) a solution `x` of `A x = b` produced by `solve`, which overwrites its
/// argument `r` with `A^-1 r`. `work` has length `n`.
pub(crate) fn check_and_refine(
    params: &DirectParams,
    pattern: &SparsityPattern,
    values: &[f64],
    b: &[f64],
    x: &mut [f64],
    work: &mut [f64],
    mut solve: impl FnMut(&mut [f64]),
) -> Result<(), SolverError> {
    let bn = inf_norm(b);
    for step in 0..=params.refinement_steps {
        if crate::scalar::first_non_finite(x).is_some() {
            return Err(SolverError::Singular { pivot: None });
        }
        pattern.residual_into(values, x, b, work);
        let rn = inf_norm(work);
        if rn <= params.residual_tolerance * bn {
            return Ok(());
        }
        if !rn.is_finite() || step == params.refinement_steps {
            return Err(SolverError::Singular { pivot: None });
        }
        solve(work);
        for (xi, di) in x.iter_mut().zip(work.iter()) {
            *xi += di;
        }
    }
    Err(SolverError::Singular { pivot: None })
}

/// Column `col` (caller's numbering) without any nonzero value, or row without one: a
/// structurally singular matrix that must not reach faer (it may panic on an exact zero pivot,
/// faer issue 232).
pub(crate) fn empty_line(pattern: &SparsityPattern, values: &[f64]) -> Option<usize> {
    let n = pattern.nrows();
    let mut row_has = vec![false; n];
    let col_ptr = pattern.col_ptr();
    let row_idx = pattern.row_idx();
    let mut empty_col = None;
    for j in 0..pattern.ncols() {
        let mut any = false;
        for s in col_ptr[j]..col_ptr[j + 1] {
            if values[s] != 0.0 {
                any = true;
                row_has[row_idx[s]] = true;
            }
        }
        if !any && empty_col.is_none() {
            empty_col = Some(j);
        }
    }
    empty_col.or_else(|| row_has.iter().position(|h| !h))
}

/// A scratch buffer for faer, with allocation failure as a typed error.
pub(crate) fn scratch(
    req: faer::dyn_stack::StackReq,
) -> Result<faer::dyn_stack::MemBuffer, SolverError> {
    faer::dyn_stack::MemBuffer::try_new(req)
        .map_err(|_| SolverError::Backend(faer::sparse::FaerError::OutOfMemory))
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

    #[test]
    fn empty_line_finds_zero_column_and_zero_row() {
        let (p, _) = SparsityPattern::from_entries(2, 2, &[(0, 0), (0, 1), (1, 1)]).unwrap();
        assert_eq!(empty_line(&p, &[1.0, 0.0, 0.0]), Some(1)); // column 1 all zero
        assert_eq!(empty_line(&p, &[1.0, 1.0, 0.0]), Some(1)); // row 1 all zero
        assert_eq!(empty_line(&p, &[1.0, 0.0, 1.0]), None);
    }

    #[test]
    fn refinement_fixes_a_perturbed_solution() {
        let (p, _) = SparsityPattern::from_entries(1, 1, &[(0, 0)]).unwrap();
        let values = [2.0];
        let b = [4.0];
        let mut x = [1.9]; // a "solve" that is 5% off
        let mut work = [0.0];
        let params = DirectParams::default();
        check_and_refine(&params, &p, &values, &b, &mut x, &mut work, |r| r[0] /= 2.0).unwrap();
        assert_eq!(x[0], 2.0);
        let mut x = [f64::NAN];
        let err = check_and_refine(&params, &p, &values, &b, &mut x, &mut work, |_| {});
        assert!(matches!(err, Err(SolverError::Singular { pivot: None })));
    }
}
