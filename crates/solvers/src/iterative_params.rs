//! Settings and shared machinery of the stationary iterative backends (Jacobi, Gauss–Seidel).

use crate::error::SolverError;
use crate::linear_solver::{check_rhs, check_square};
use crate::scalar::{SolverScalar, norm2};
use crate::sparsity_pattern::SparsityPattern;

/// Settings of [`crate::Jacobi`] and [`crate::GaussSeidel`].
///
/// # Math
/// ```text
/// stop when |b - A x_k|_2 <= tolerance * |b|_2        (x_0 = 0)
/// Jacobi:        x_{k+1} = x_k + relaxation D^-1 (b - A x_k)
/// Gauss–Seidel:  row by row, x_i <- (1 - w) x_i + w (b_i - sum_{j != i} a_ij x_j) / a_ii
///                with the newest x_j (w = relaxation; w > 1 is SOR)
/// ```
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct IterativeParams {
    /// Relative residual `|b - A x| / |b|` at which to stop, in `(0, 1)`.
    pub tolerance: f64,
    /// Iteration cap (at least 1); reaching it is [`SolverError::NotConverged`].
    pub max_iterations: usize,
    /// Relaxation weight `w` in `(0, 2)`: damping for Jacobi (`w < 1`), SOR for Gauss–Seidel.
    pub relaxation: f64,
}

impl Default for IterativeParams {
    fn default() -> Self {
        Self {
            tolerance: 1e-10,
            max_iterations: 10_000,
            relaxation: 1.0,
        }
    }
}

impl IterativeParams {
    /// Checks every field.
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), SolverError> {
        SolverError::check_fraction("tolerance", self.tolerance)?;
        SolverError::check_count("max_iterations", self.max_iterations)?;
        if !(self.relaxation > 0.0 && self.relaxation < 2.0) {
            return Err(SolverError::invalid(
                "relaxation",
                self.relaxation,
                "(0, 2)",
            ));
        }
        Ok(())
    }
}

/// Row-oriented copy of the matrix shared by the iterative backends.
#[derive(Clone, Debug)]
pub(crate) struct RowMatrix<F> {
    pub(crate) n: usize,
    pub(crate) row_ptr: Vec<usize>,
    pub(crate) col_idx: Vec<usize>,
    /// CSC slot of each row-ordered entry.
    row_slot: Vec<usize>,
    pub(crate) values: Vec<F>,
    /// `1 / a_ii`.
    pub(crate) inv_diag: Vec<F>,
    /// Position of `a_ii` in row `i` (`None`: structurally zero diagonal).
    pub(crate) diag_pos: Vec<Option<usize>>,
    pub(crate) analysed: bool,
    pub(crate) factored: bool,
}

impl<F: SolverScalar> RowMatrix<F> {
    /// Nothing analysed yet.
    pub(crate) fn empty() -> Self {
        Self {
            n: 0,
            row_ptr: Vec::new(),
            col_idx: Vec::new(),
            row_slot: Vec::new(),
            values: Vec::new(),
            inv_diag: Vec::new(),
            diag_pos: Vec::new(),
            analysed: false,
            factored: false,
        }
    }

    pub(crate) fn analyse(&mut self, pattern: &SparsityPattern) -> Result<(), SolverError> {
        let n = check_square(pattern)?;
        let (row_ptr, col_idx, row_slot) = pattern.row_layout();
        let diag_pos = (0..n)
            .map(|i| (row_ptr[i]..row_ptr[i + 1]).find(|&p| col_idx[p] == i))
            .collect();
        *self = Self {
            diag_pos,
            n,
            values: vec![F::zero(); col_idx.len()],
            inv_diag: vec![F::zero(); n],
            row_ptr,
            col_idx,
            row_slot,
            analysed: true,
            factored: false,
        };
        Ok(())
    }

    /// Copies `values` (CSC order) into row order and inverts the diagonal.
    pub(crate) fn factor(&mut self, values: &[F]) -> Result<(), SolverError> {
        if !self.analysed {
            return Err(SolverError::call_order("factor", "analyse"));
        }
        self.factored = false;
        crate::linear_solver::check_value_count(values, self.row_slot.len())?;
        for (p, &s) in self.row_slot.iter().enumerate() {
            self.values[p] = values[s];
        }
        for i in 0..self.n {
            let diag = self.diag_pos[i].map_or(F::zero(), |p| self.values[p]);
            if diag == F::zero() {
                return Err(SolverError::Singular { pivot: Some(i) });
            }
            self.inv_diag[i] = F::one() / diag;
        }
        self.factored = true;
        Ok(())
    }

    /// `r = b - A x`, returns `|r|_2`.
    pub(crate) fn residual(&self, x: &[F], b: &[F], r: &mut [F]) -> F {
        for (i, ri) in r.iter_mut().enumerate() {
            let range = self.row_ptr[i]..self.row_ptr[i + 1];
            let mut s = b[i];
            for (a, &j) in self.values[range.clone()].iter().zip(&self.col_idx[range]) {
                s = s - *a * x[j];
            }
            *ri = s;
        }
        norm2(r)
    }

    /// The common driver: `sweep(matrix, x, r)` updates `x` given the current residual `r`.
    /// Returns the iterations; on success `rhs` holds the solution.
    pub(crate) fn iterate(
        &self,
        params: &IterativeParams,
        rhs: &mut [F],
        mut sweep: impl FnMut(&Self, &mut [F], &[F], &[F]),
    ) -> Result<usize, (usize, SolverError)> {
        if !self.factored {
            return Err((0, SolverError::call_order("solve_in_place", "factor")));
        }
        check_rhs(rhs, self.n).map_err(|e| (0, e))?;
        let b = rhs.to_vec();
        let bn = norm2(&b);
        rhs.iter_mut().for_each(|v| *v = F::zero());
        if bn == F::zero() {
            return Ok(0);
        }
        let tol = F::from_f64(params.tolerance) * bn;
        let mut r = b.clone();
        let mut rn = bn;
        let mut k = 0;
        loop {
            if rn <= tol {
                return Ok(k);
            }
            if k == params.max_iterations || !rn.is_finite() {
                let residual = if rn.is_finite() {
                    (rn / bn).as_f64()
                } else {
                    f64::INFINITY
                };
                return Err((
                    k,
                    SolverError::NotConverged {
                        iterations: k,
                        residual,
                    },
                ));
            }
            sweep(self, rhs, &b, &r);
            rn = self.residual(rhs, &b, &mut r);
            k += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validate_names_each_field() {
        IterativeParams::default().validate().unwrap();
        let field = |p: IterativeParams| match p.validate() {
            Err(SolverError::InvalidParameter { field, .. }) => field,
            other => panic!("expected InvalidParameter, got {other:?}"),
        };
        let d = IterativeParams::default();
        assert_eq!(
            field(IterativeParams {
                tolerance: 1.5,
                ..d
            }),
            "tolerance"
        );
        assert_eq!(
            field(IterativeParams {
                max_iterations: 0,
                ..d
            }),
            "max_iterations"
        );
        assert_eq!(
            field(IterativeParams {
                relaxation: 2.0,
                ..d
            }),
            "relaxation"
        );
    }

    #[test]
    fn zero_diagonal_is_singular() {
        let (p, _) = SparsityPattern::from_entries(2, 2, &[(0, 0), (1, 0), (0, 1)]).unwrap();
        let mut m = RowMatrix::<f64>::empty();
        m.analyse(&p).unwrap();
        assert!(matches!(
            m.factor(&[1.0, 1.0, 1.0]),
            Err(SolverError::Singular { pivot: Some(1) })
        ));
    }
}
