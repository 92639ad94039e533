//! The linear-solver capability: analyse a pattern once, factor many values, solve many
//! right-hand sides.

use crate::error::SolverError;
use crate::observer::Observer;
use crate::scalar::SolverScalar;
use crate::sparsity_pattern::SparsityPattern;

/// A sparse linear solver for `A x = b` with a fixed pattern and changing values.
///
/// The call sequence is `analyse` once per pattern, then `factor` for each new set of values
/// (in [`SparsityPattern`] slot order), then `solve_in_place` any number of times. Direct
/// backends do the symbolic work in `analyse` and the numeric factorisation in `factor`;
/// iterative backends store the values and do their work in `solve_in_place`.
///
/// # Errors
/// Out-of-order calls give [`SolverError::CallOrder`]; wrong lengths give
/// [`SolverError::DimensionMismatch`]; non-finite values or right-hand sides give
/// [`SolverError::NonFinite`]; a singular matrix gives [`SolverError::Singular`]. No backend
/// returns a non-finite solution.
///
/// # Example
/// ```
/// use capstan_solvers::{LinearBackend, SparsityPattern};
/// // [[4, 1], [1, 3]] x = [1, 2]
/// let (pattern, slots) =
///     SparsityPattern::from_entries(2, 2, &[(0, 0), (1, 0), (0, 1), (1, 1)]).unwrap();
/// let mut values = vec![0.0; pattern.nnz()];
/// for (k, v) in [4.0, 1.0, 1.0, 3.0].into_iter().enumerate() {
///     values[slots[k]] += v;
/// }
/// for backend in [LinearBackend::LU, LinearBackend::CHOLESKY, LinearBackend::GAUSS_SEIDEL] {
///     let mut solver = backend.build(&Default::default(), &()).unwrap();
///     solver.analyse(&pattern).unwrap();
///     solver.factor(&values).unwrap();
///     let mut x = vec![1.0, 2.0];
///     solver.solve_in_place(&mut x).unwrap();
///     assert!((x[0] - 1.0 / 11.0).abs() < 1e-8 && (x[1] - 7.0 / 11.0).abs() < 1e-8);
/// }
/// ```
pub trait LinearSolver<F: SolverScalar> {
    /// Symbolic analysis of `pattern` (ordering, fill structure); forgets any previous factors.
    ///
    /// # Errors
    /// [`SolverError::NotSquare`] for a rectangular pattern; backend-specific structural checks.
    fn analyse(&mut self, pattern: &SparsityPattern) -> Result<(), SolverError>;

    /// Numeric factorisation (or, for iterative backends, preparation) for `values` on the
    /// analysed pattern.
    ///
    /// # Errors
    /// [`SolverError::CallOrder`] before `analyse`; [`SolverError::DimensionMismatch`],
    /// [`SolverError::NonFinite`], [`SolverError::Singular`] and backend-specific failures.
    fn factor(&mut self, values: &[F]) -> Result<(), SolverError>;

    /// Overwrites `rhs` (`b`) with the solution `x` of `A x = b`.
    ///
    /// On error the contents of `rhs` are unspecified (but never returned as a solution).
    ///
    /// # Errors
    /// [`SolverError::CallOrder`] before `factor`; [`SolverError::DimensionMismatch`],
    /// [`SolverError::NonFinite`], [`SolverError::Singular`],
    /// [`SolverError::NotConverged`] for iterative backends.
    fn solve_in_place(&mut self, rhs: &mut [F]) -> Result<(), SolverError>;

    /// Iterations of the last `solve_in_place` for iterative backends; `None` for direct ones.
    fn last_iterations(&self) -> Option<usize>;

    /// [`LinearSolver::solve_in_place`] reporting its iterations to `observer`
    /// ([`crate::SolveStage::Krylov`] events). The default reports nothing and solves; an
    /// iterative backend whose iterations are observable (PETSc's KSP monitor) overrides it.
    ///
    /// # Errors
    /// As [`LinearSolver::solve_in_place`]; [`SolverError::Interrupted`] when the observer
    /// asks to stop.
    fn solve_in_place_observed(
        &mut self,
        rhs: &mut [F],
        observer: &mut dyn Observer<F>,
    ) -> Result<(), SolverError> {
        let _ = observer;
        self.solve_in_place(rhs)
    }

    /// Solves `A x = b` of a distributed solve on this process's rows only: on entry `rhs`
    /// holds rows `first .. first + rhs.len()` of `b`, on return the same rows of `x`; no
    /// process holds either vector whole. Collective (every process calls it, in the same
    /// order as every other collective call). Only a distributed backend (PETSc) can; the
    /// default refuses.
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] naming `solver.linear` for a backend that is not
    /// distributed; for one that is, [`SolverError::DimensionMismatch`] when the rows are not
    /// the ones it owns, and the errors of [`LinearSolver::solve_in_place`] (a non-finite
    /// entry of `b` on any process: [`SolverError::NonFinite`] on every process).
    fn solve_owned_in_place_observed(
        &mut self,
        first: usize,
        rhs: &mut [F],
        observer: &mut dyn Observer<F>,
    ) -> Result<(), SolverError> {
        let _ = (first, rhs, observer);
        Err(SolverError::InvalidParameter {
            field: "solver.linear",
            value: f64::NAN,
            allowed: "a distributed backend (`petsc`) for a solve on each process's rows",
        })
    }

    /// Solves for `ncols` right-hand sides stored column after column in `rhs`
    /// (column-major, length `n * ncols`).
    ///
    /// The default calls [`LinearSolver::solve_in_place`] on each column; direct backends
    /// override it with one blocked solve.
    ///
    /// # Errors
    /// As [`LinearSolver::solve_in_place`]; [`SolverError::DimensionMismatch`] if `rhs.len()`
    /// is not a multiple of `ncols`.
    fn solve_many_in_place(&mut self, rhs: &mut [F], ncols: usize) -> Result<(), SolverError> {
        let n = check_many_len(rhs.len(), ncols)?;
        if n == 0 {
            return Ok(());
        }
        for column in rhs.chunks_exact_mut(n) {
            self.solve_in_place(column)?;
        }
        Ok(())
    }
}

/// Rows per column of a column-major block of `ncols` right-hand sides.
pub(crate) fn check_many_len(len: usize, ncols: usize) -> Result<usize, SolverError> {
    if ncols == 0 {
        return if len == 0 {
            Ok(0)
        } else {
            Err(SolverError::DimensionMismatch {
                quantity: "rhs",
                expected: 0,
                found: len,
            })
        };
    }
    if !len.is_multiple_of(ncols) {
        return Err(SolverError::DimensionMismatch {
            quantity: "rhs",
            expected: (len / ncols + 1) * ncols,
            found: len,
        });
    }
    Ok(len / ncols)
}

impl<F: SolverScalar, S: LinearSolver<F> + ?Sized> LinearSolver<F> for Box<S> {
    fn analyse(&mut self, pattern: &SparsityPattern) -> Result<(), SolverError> {
        (**self).analyse(pattern)
    }
    fn factor(&mut self, values: &[F]) -> Result<(), SolverError> {
        (**self).factor(values)
    }
    fn solve_in_place(&mut self, rhs: &mut [F]) -> Result<(), SolverError> {
        (**self).solve_in_place(rhs)
    }
    fn last_iterations(&self) -> Option<usize> {
        (**self).last_iterations()
    }
    fn solve_in_place_observed(
        &mut self,
        rhs: &mut [F],
        observer: &mut dyn Observer<F>,
    ) -> Result<(), SolverError> {
        (**self).solve_in_place_observed(rhs, observer)
    }
    fn solve_many_in_place(&mut self, rhs: &mut [F], ncols: usize) -> Result<(), SolverError> {
        (**self).solve_many_in_place(rhs, ncols)
    }
    fn solve_owned_in_place_observed(
        &mut self,
        first: usize,
        rhs: &mut [F],
        observer: &mut dyn Observer<F>,
    ) -> Result<(), SolverError> {
        (**self).solve_owned_in_place_observed(first, rhs, observer)
    }
}

/// Checks a right-hand side: length and finiteness.
pub(crate) fn check_rhs<F: SolverScalar>(rhs: &[F], n: usize) -> Result<(), SolverError> {
    if rhs.len() != n {
        return Err(SolverError::DimensionMismatch {
            quantity: "rhs",
            expected: n,
            found: rhs.len(),
        });
    }
    crate::scalar::check_finite("right-hand side", rhs)
}

/// Checks matrix values against a value layout of `expected` entries: length and finiteness.
pub(crate) fn check_value_count<F: SolverScalar>(
    values: &[F],
    expected: usize,
) -> Result<(), SolverError> {
    if values.len() != expected {
        return Err(SolverError::DimensionMismatch {
            quantity: "values",
            expected,
            found: values.len(),
        });
    }
    crate::scalar::check_finite("matrix value", values)
}

/// Checks matrix values: length and finiteness.
pub(crate) fn check_values<F: SolverScalar>(
    pattern: &SparsityPattern,
    values: &[F],
) -> Result<(), SolverError> {
    pattern.check_values_len(values.len())?;
    crate::scalar::check_finite("matrix value", values)
}

/// Checks that the pattern is square and returns its dimension.
pub(crate) fn check_square(pattern: &SparsityPattern) -> Result<usize, SolverError> {
    if !pattern.is_square() {
        return Err(SolverError::NotSquare {
            nrows: pattern.nrows(),
            ncols: pattern.ncols(),
        });
    }
    Ok(pattern.nrows())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn check_many_len_splits_columns() {
        assert_eq!(check_many_len(12, 3).unwrap(), 4);
        assert_eq!(check_many_len(0, 0).unwrap(), 0);
        assert!(check_many_len(10, 3).is_err());
        assert!(check_many_len(1, 0).is_err());
    }
}
