//! The crate's single error type.

/// Everything that can go wrong in a linear or nonlinear solve.
///
/// Variants carry what a caller needs to react: the offending field and its allowed range,
/// the iteration and residual at failure, the pivot or index at fault. A solver never returns
/// NaN: a non-finite quantity becomes [`SolverError::NonFinite`] or [`SolverError::Singular`].
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SolverError {
    /// A setting is outside its allowed range.
    #[error("`{field}` = {value} is outside {allowed}")]
    InvalidParameter {
        /// Name of the setting, e.g. `"tolerance"`.
        field: &'static str,
        /// The rejected value (integers are converted to `f64`).
        value: f64,
        /// The allowed range in words, e.g. `"(0, 1)"`.
        allowed: &'static str,
    },
    /// A name (backend, method) that is not one of the known spellings.
    #[error("unknown {kind} `{name}`: expected one of {allowed}")]
    UnknownName {
        /// What was being named, e.g. `"linear backend"`.
        kind: &'static str,
        /// The name that was given.
        name: String,
        /// The accepted spellings.
        allowed: String,
    },
    /// A registration under a name that is taken.
    #[error("a {kind} named `{name}` is registered already")]
    DuplicateName {
        /// What was being registered, e.g. `"linear backend"`.
        kind: &'static str,
        /// The name.
        name: &'static str,
    },
    /// Newton's residual grew beyond the divergence limit.
    #[error("Newton diverged at iteration {iteration}: residual {residual:.3e}")]
    Diverged {
        /// Iteration at which the limit was exceeded.
        iteration: usize,
        /// Residual norm `|r|` at that iteration.
        residual: f64,
    },
    /// The nonlinear iteration cannot make progress: the line search found no decrease, or the
    /// step is below round-off of the iterate.
    #[error("stagnated after {iterations} iterations at residual {residual:.3e}")]
    Stagnated {
        /// Iterations completed.
        iterations: usize,
        /// Residual norm `|r|` when progress stopped.
        residual: f64,
    },
    /// An iteration cap was reached before the tolerance (linear iterative backends report the
    /// relative residual `|b - A x| / |b|`, nonlinear solvers the residual norm `|r|`).
    #[error("not converged after {iterations} iterations: residual {residual:.3e}")]
    NotConverged {
        /// Iterations performed.
        iterations: usize,
        /// Residual at the last iterate (relative for linear, absolute for nonlinear solvers).
        residual: f64,
    },
    /// A Krylov solve spent its work budget (the setting `field`, e.g.
    /// `krylov.max_iterations`) before reaching its relative-residual tolerance.
    #[error(
        "`{field}` = {iterations} iterations spent: relative residual {residual:.3e} above the tolerance {tolerance:.1e}"
    )]
    BudgetSpent {
        /// The setting that bounds the work.
        field: &'static str,
        /// Iterations performed (the budget).
        iterations: usize,
        /// Relative residual `|b - A x| / |b|` at the last iterate.
        residual: f64,
        /// The relative-residual tolerance asked for.
        tolerance: f64,
    },
    /// The observer asked the solve to stop ([`crate::Observer::interrupted`]).
    #[error("interrupted after iteration {iteration}")]
    Interrupted {
        /// Iterations completed before the stop.
        iteration: usize,
    },
    /// The matrix is (numerically) singular.
    #[error("matrix is singular{}", pivot_note(.pivot))]
    Singular {
        /// The column (in the caller's numbering) without a usable pivot, when it is known:
        /// an empty row or column, a zero diagonal for the iterative backends. `None` when the
        /// singularity was detected from a non-finite or inconsistent solution.
        pivot: Option<usize>,
    },
    /// Cholesky met a non-positive pivot: the matrix is not symmetric positive definite.
    #[error("matrix is not positive definite (pivot {pivot} <= 0)")]
    NotPositiveDefinite {
        /// Column (caller's numbering) whose pivot was not positive.
        pivot: usize,
    },
    /// A backend for symmetric matrices received values with `a_ij != a_ji`.
    #[error("matrix is not symmetric: entry ({row}, {col}) differs from its transpose")]
    NotSymmetric {
        /// Row of the first asymmetric entry found.
        row: usize,
        /// Column of the first asymmetric entry found.
        col: usize,
    },
    /// A NaN or infinity in an input or a computed quantity.
    #[error("non-finite {quantity} at index {index}{}", iteration_note(.iteration))]
    NonFinite {
        /// What was non-finite: `"matrix value"`, `"right-hand side"`, `"residual"`,
        /// `"jacobian"`, `"solution"`, `"step"`.
        quantity: &'static str,
        /// Index of the first non-finite entry.
        index: usize,
        /// Nonlinear iteration, when it happened inside one.
        iteration: Option<usize>,
    },
    /// An entry given to the pattern builder lies outside the matrix.
    #[error("entry ({row}, {col}) is outside a {nrows} x {ncols} matrix")]
    EntryOutOfBounds {
        /// Row of the entry.
        row: usize,
        /// Column of the entry.
        col: usize,
        /// Rows of the matrix.
        nrows: usize,
        /// Columns of the matrix.
        ncols: usize,
    },
    /// A square matrix was required.
    #[error("matrix is {nrows} x {ncols}, a square matrix is required")]
    NotSquare {
        /// Rows of the matrix.
        nrows: usize,
        /// Columns of the matrix.
        ncols: usize,
    },
    /// A slice has the wrong length.
    #[error("`{quantity}` has length {found}, expected {expected}")]
    DimensionMismatch {
        /// Which slice, e.g. `"values"`, `"rhs"`.
        quantity: &'static str,
        /// Expected length.
        expected: usize,
        /// Length received.
        found: usize,
    },
    /// Methods were called out of order, e.g. `solve_in_place` before `factor`.
    #[error("`{called}` needs `{requires}` first")]
    CallOrder {
        /// Method that was called.
        called: &'static str,
        /// Method that has to succeed before it.
        requires: &'static str,
    },
    /// The problem's residual or Jacobian evaluation failed; the cause is the source.
    #[error("problem evaluation failed in `{stage}`")]
    Problem {
        /// `"residual"` or `"jacobian"`.
        stage: &'static str,
        /// The problem's own error.
        #[source]
        source: Box<dyn std::error::Error + Send + Sync + 'static>,
    },
    /// An external linear backend (PETSc) failed; the cause is the source.
    #[error("{backend} failed: {source}")]
    External {
        /// The backend's name (`"petsc"`).
        backend: &'static str,
        /// The backend's own error.
        #[source]
        source: Box<dyn std::error::Error + Send + Sync + 'static>,
    },
    /// faer could not complete an operation (out of memory, index overflow).
    #[error("sparse backend failure: {0}")]
    Backend(#[from] faer::sparse::FaerError),
}

fn pivot_note(pivot: &Option<usize>) -> String {
    match pivot {
        Some(p) => format!(" (no usable pivot in column {p})"),
        None => " (non-finite or inconsistent solution)".to_owned(),
    }
}

fn iteration_note(iteration: &Option<usize>) -> String {
    match iteration {
        Some(k) => format!(" in iteration {k}"),
        None => String::new(),
    }
}

impl SolverError {
    /// Wraps a problem's own error as [`SolverError::Problem`].
    pub fn problem<E: std::error::Error + Send + Sync + 'static>(
        stage: &'static str,
        e: E,
    ) -> Self {
        Self::Problem {
            stage,
            source: Box::new(e),
        }
    }

    /// [`SolverError::InvalidParameter`]: `field` = `value` is outside `allowed`.
    pub(crate) fn invalid(field: &'static str, value: f64, allowed: &'static str) -> Self {
        Self::InvalidParameter {
            field,
            value,
            allowed,
        }
    }

    /// Checks a relative tolerance or fraction: `value` in the open interval `(0, 1)`.
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] naming `field` otherwise (NaN included).
    pub(crate) fn check_fraction(field: &'static str, value: f64) -> Result<(), Self> {
        if value > 0.0 && value < 1.0 {
            Ok(())
        } else {
            Err(Self::invalid(field, value, "(0, 1)"))
        }
    }

    /// Checks a count or budget: `count >= 1`.
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] naming `field` for `0`.
    pub(crate) fn check_count(field: &'static str, count: usize) -> Result<(), Self> {
        if count == 0 {
            Err(Self::invalid(field, 0.0, "[1, inf)"))
        } else {
            Ok(())
        }
    }

    /// [`SolverError::CallOrder`]: `called` needs `requires` first.
    pub(crate) fn call_order(called: &'static str, requires: &'static str) -> Self {
        Self::CallOrder { called, requires }
    }
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
    fn singular_message_names_pivot_when_known() {
        let e = SolverError::Singular { pivot: Some(3) };
        assert_eq!(
            e.to_string(),
            "matrix is singular (no usable pivot in column 3)"
        );
        let e = SolverError::Singular { pivot: None };
        assert!(e.to_string().contains("non-finite"));
    }

    #[test]
    fn non_finite_message_mentions_iteration() {
        let e = SolverError::NonFinite {
            quantity: "residual",
            index: 2,
            iteration: Some(4),
        };
        assert_eq!(
            e.to_string(),
            "non-finite residual at index 2 in iteration 4"
        );
    }

    #[test]
    fn error_is_send_sync() {
        fn check<T: Send + Sync + 'static>() {}
        check::<SolverError>();
    }
}
