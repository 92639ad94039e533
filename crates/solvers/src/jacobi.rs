//! The (weighted) Jacobi iteration: the paper's linear baseline.

use crate::error::SolverError;
use crate::iterative_params::{IterativeParams, RowMatrix};
use crate::linear_solver::LinearSolver;
use crate::scalar::SolverScalar;
use crate::sparsity_pattern::SparsityPattern;

/// Jacobi iteration for `A x = b`, generic over the scalar.
///
/// Converges for strictly (or irreducibly) diagonally dominant matrices; slowly on
/// discretised elliptic problems (the iteration count grows like `h^-2`), which is why it is
/// the baseline and not the default. `analyse` builds a row-ordered copy of the pattern;
/// `factor` copies the values and inverts the diagonal; `solve_in_place` iterates from
/// `x_0 = 0`.
///
/// # Math
/// ```text
/// x_{k+1} = x_k + w D^-1 (b - A x_k),   D = diag(A),  w = relaxation
/// stop when |b - A x_k|_2 <= tolerance * |b|_2
/// ```
///
/// # Errors
/// [`SolverError::Singular`] for a zero diagonal entry (at `factor`);
/// [`SolverError::NotConverged`] with the relative residual when the cap is reached or the
/// iteration overflows; the common errors of [`LinearSolver`].
///
/// # Example
/// ```
/// use capstan_solvers::{IterativeParams, Jacobi, LinearSolver, SparsityPattern};
/// let (pattern, _) = SparsityPattern::from_entries(2, 2, &[(0, 0), (1, 0), (0, 1), (1, 1)]).unwrap();
/// let mut jacobi = Jacobi::new(IterativeParams { tolerance: 1e-12, ..Default::default() }).unwrap();
/// jacobi.analyse(&pattern).unwrap();
/// jacobi.factor(&[4.0_f32, 1.0, 1.0, 4.0]).unwrap();
/// let mut x = vec![5.0_f32, 5.0];
/// jacobi.solve_in_place(&mut x).unwrap();
/// assert!((x[0] - 1.0).abs() < 1e-6 && (x[1] - 1.0).abs() < 1e-6);
/// assert!(jacobi.last_iterations().unwrap() > 1);
/// ```
#[derive(Clone, Debug)]
pub struct Jacobi<F = f64> {
    params: IterativeParams,
    matrix: RowMatrix<F>,
    last_iterations: Option<usize>,
}

impl<F: SolverScalar> Jacobi<F> {
    /// A Jacobi solver with the given settings.
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] if `params` is out of range.
    pub fn new(params: IterativeParams) -> Result<Self, SolverError> {
        params.validate()?;
        Ok(Self {
            params,
            matrix: RowMatrix::empty(),
            last_iterations: None,
        })
    }

    /// The settings in use.
    pub fn params(&self) -> &IterativeParams {
        &self.params
    }
}

impl<F: SolverScalar> Default for Jacobi<F> {
    /// Default [`IterativeParams`].
    fn default() -> Self {
        Self {
            params: IterativeParams::default(),
            matrix: RowMatrix::empty(),
            last_iterations: None,
        }
    }
}

impl<F: SolverScalar> LinearSolver<F> for Jacobi<F> {
    fn analyse(&mut self, pattern: &SparsityPattern) -> Result<(), SolverError> {
        self.last_iterations = None;
        self.matrix.analyse(pattern)
    }

    fn factor(&mut self, values: &[F]) -> Result<(), SolverError> {
        self.matrix.factor(values)
    }

    fn solve_in_place(&mut self, rhs: &mut [F]) -> Result<(), SolverError> {
        let w = F::from_f64(self.params.relaxation);
        let result = self.matrix.iterate(&self.params, rhs, |m, x, _b, r| {
            for ((xi, ri), di) in x.iter_mut().zip(r).zip(&m.inv_diag) {
                *xi = *xi + w * *ri * *di;
            }
        });
        match result {
            Ok(k) => {
                self.last_iterations = Some(k);
                Ok(())
            }
            Err((k, e)) => {
                self.last_iterations = Some(k);
                Err(e)
            }
        }
    }

    fn last_iterations(&self) -> Option<usize> {
        self.last_iterations
    }
}
