//! The relaxation iterations of the paper's linear baseline: Jacobi and Gauss–Seidel (SOR),
//! one solver type with the sweep chosen at compile time, one driving loop
//! ([`crate::iterative_params::RowMatrix::iterate`]).

use crate::error::SolverError;
use crate::iterative_params::{IterativeParams, RowMatrix};
use crate::linear_registration::{BackendKind, Parameter, RegisteredLinearSolver};
use crate::linear_solver::LinearSolver;
use crate::scalar::SolverScalar;
use crate::sparsity_pattern::SparsityPattern;

/// A relaxation iteration for `A x = b`: Jacobi (`GAUSS_SEIDEL = false`, alias [`Jacobi`]) or
/// forward Gauss–Seidel / SOR (`true`, alias [`GaussSeidel`]), generic over the scalar.
///
/// `analyse` builds a row-ordered copy of the pattern; `factor` copies the values and
/// inverts the diagonal; `solve_in_place` iterates from `x_0 = 0` until
/// `|b - A x_k|_2 <= tolerance |b|_2` or `max_iterations` sweeps.
#[derive(Clone, Debug)]
pub struct Relaxation<F, const GAUSS_SEIDEL: bool> {
    params: IterativeParams,
    matrix: RowMatrix<F>,
    last_iterations: Option<usize>,
}

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
pub type Jacobi<F = f64> = Relaxation<F, false>;

/// Forward Gauss–Seidel iteration (successive over-relaxation when `relaxation != 1`),
/// generic over the scalar.
///
/// Like [`crate::Jacobi`] but each row uses the newest values of the unknowns before it, which
/// roughly halves the iteration count on model problems and also converges for symmetric
/// positive definite matrices. One sweep visits the rows in index order.
///
/// # Math
/// ```text
/// for i = 0 .. n-1:
///     x_i <- (1 - w) x_i + w (b_i - sum_{j != i} a_ij x_j) / a_ii
/// stop when |b - A x_k|_2 <= tolerance * |b|_2,  x_0 = 0
/// ```
///
/// # Errors
/// As [`crate::Jacobi`].
///
/// # Example
/// ```
/// use capstan_solvers::{GaussSeidel, Jacobi, LinearSolver, SparsityPattern};
/// let (pattern, _) = SparsityPattern::from_entries(2, 2, &[(0, 0), (1, 0), (0, 1), (1, 1)]).unwrap();
/// let values = [4.0, 1.0, 1.0, 4.0];
/// let mut gs = GaussSeidel::default();
/// let mut jacobi = Jacobi::default();
/// let mut x = [vec![5.0, 5.0], vec![5.0, 5.0]];
/// for (s, x) in [&mut gs as &mut dyn LinearSolver<f64>, &mut jacobi].into_iter().zip(&mut x) {
///     s.analyse(&pattern).unwrap();
///     s.factor(&values).unwrap();
///     s.solve_in_place(x).unwrap();
/// }
/// assert!(gs.last_iterations().unwrap() < jacobi.last_iterations().unwrap());
/// ```
pub type GaussSeidel<F = f64> = Relaxation<F, true>;

impl<F: SolverScalar, const GAUSS_SEIDEL: bool> Relaxation<F, GAUSS_SEIDEL> {
    /// A solver with the given settings.
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

/// The settings both stationary iterations read (`IterativeParams`).
const ITERATIVE_PARAMETERS: &[Parameter] = &[
    Parameter {
        key: "iterative.tolerance",
        default: "1e-10",
        allowed: "(0, 1)",
    },
    Parameter {
        key: "iterative.max_iterations",
        default: "10000",
        allowed: "[1, inf)",
    },
    Parameter {
        key: "iterative.relaxation",
        default: "1",
        allowed: "(0, 2)",
    },
];

/// The `jacobi` entry of [`crate::linear_registry`].
pub(crate) const JACOBI_REGISTRATION: RegisteredLinearSolver = RegisteredLinearSolver {
    name: "jacobi",
    summary: "(damped) Jacobi sweeps, the paper's iterative baseline: diagonally dominant matrices",
    parameters: ITERATIVE_PARAMETERS,
    kind: BackendKind::Stationary,
    build: |s, _| Ok(Box::new(Jacobi::<f64>::new(s.iterative)?)),
};

/// The `gauss-seidel` entry of [`crate::linear_registry`].
pub(crate) const GAUSS_SEIDEL_REGISTRATION: RegisteredLinearSolver = RegisteredLinearSolver {
    name: "gauss-seidel",
    summary: "Gauss-Seidel (SOR) sweeps: symmetric positive definite or diagonally dominant matrices",
    parameters: ITERATIVE_PARAMETERS,
    kind: BackendKind::Stationary,
    build: |s, _| Ok(Box::new(GaussSeidel::<f64>::new(s.iterative)?)),
};

impl<F: SolverScalar, const GAUSS_SEIDEL: bool> Default for Relaxation<F, GAUSS_SEIDEL> {
    /// Default [`IterativeParams`].
    fn default() -> Self {
        Self {
            params: IterativeParams::default(),
            matrix: RowMatrix::empty(),
            last_iterations: None,
        }
    }
}

impl<F: SolverScalar, const GAUSS_SEIDEL: bool> LinearSolver<F> for Relaxation<F, GAUSS_SEIDEL> {
    fn analyse(&mut self, pattern: &SparsityPattern) -> Result<(), SolverError> {
        self.last_iterations = None;
        self.matrix.analyse(pattern)
    }

    fn factor(&mut self, values: &[F]) -> Result<(), SolverError> {
        self.matrix.factor(values)
    }

    fn solve_in_place(&mut self, rhs: &mut [F]) -> Result<(), SolverError> {
        let w = F::from_f64(self.params.relaxation);
        let result = self.matrix.iterate(&self.params, rhs, |m, x, b, r| {
            if GAUSS_SEIDEL {
                for i in 0..m.n {
                    // `factor` succeeded, so every row has its diagonal
                    let d = m.diag_pos[i].expect("diagonal checked in factor");
                    let (start, end) = (m.row_ptr[i], m.row_ptr[i + 1]);
                    let mut s = b[i];
                    // Old values above the diagonal first, then the new values below it, nearest
                    // (just updated) last: this keeps the row-to-row dependency chain short.
                    for (a, &j) in m.values[d + 1..end].iter().zip(&m.col_idx[d + 1..end]) {
                        s = s - *a * x[j];
                    }
                    for (a, &j) in m.values[start..d].iter().zip(&m.col_idx[start..d]).rev() {
                        s = s - *a * x[j];
                    }
                    x[i] = (F::one() - w) * x[i] + w * s * m.inv_diag[i];
                }
            } else {
                for ((xi, ri), di) in x.iter_mut().zip(r).zip(&m.inv_diag) {
                    *xi = *xi + w * *ri * *di;
                }
            }
        });
        let (k, outcome) = match result {
            Ok(k) => (k, Ok(())),
            Err((k, e)) => (k, Err(e)),
        };
        self.last_iterations = Some(k);
        outcome
    }

    fn last_iterations(&self) -> Option<usize> {
        self.last_iterations
    }
}
