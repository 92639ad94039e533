//! Linear operators known only by their action: the matrix-free interface of the Krylov
//! methods and the operator multigrid.

use crate::csr_matrix::CsrMatrix;

/// A square linear operator `A` known by its action `y = A x` and its diagonal (no entries
/// stored: a matrix-free finite-element operator, or an assembled [`CsrMatrix`]).
///
/// # Math
/// ```text
/// apply:     y = A x
/// diagonal:  d_i = A_ii = e_i^T A e_i
/// residual:  r = b - A x
/// ```
pub trait LinearOperator: Sync {
    /// Number of rows (and columns).
    fn dimension(&self) -> usize;

    /// Overwrites `y` with `A x`.
    ///
    /// # Panics
    /// If `x` or `y` does not have [`LinearOperator::dimension`] entries.
    fn apply(&self, x: &[f64], y: &mut [f64]);

    /// The diagonal `A_ii`.
    fn diagonal(&self) -> Vec<f64>;

    /// Overwrites `r` with `b - A x`.
    ///
    /// # Panics
    /// If a slice has the wrong length.
    fn residual(&self, x: &[f64], b: &[f64], r: &mut [f64]) {
        self.apply(x, r);
        r.iter_mut().zip(b).for_each(|(ri, bi)| *ri = bi - *ri);
    }
}

impl LinearOperator for CsrMatrix {
    fn dimension(&self) -> usize {
        self.nrows()
    }

    fn apply(&self, x: &[f64], y: &mut [f64]) {
        self.mul_vec(x, y);
    }

    fn diagonal(&self) -> Vec<f64> {
        CsrMatrix::diagonal(self)
    }

    fn residual(&self, x: &[f64], b: &[f64], r: &mut [f64]) {
        CsrMatrix::residual(self, x, b, r);
    }
}
