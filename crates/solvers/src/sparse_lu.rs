//! faer sparse LU with the symbolic analysis reused across factorisations.

use faer::sparse::linalg::lu::{
    LuRef, LuSymbolicParams, NumericLu, SymbolicLu, factorize_symbolic_lu,
};
use faer::sparse::linalg::{LuError, SupernodalThreshold};

use crate::direct_params::{DirectParams, check_and_refine, empty_line, scratch};
use crate::error::SolverError;
use crate::linear_solver::{LinearSolver, check_many_len, check_rhs, check_square, check_values};
use crate::sparsity_pattern::SparsityPattern;

/// Sparse LU with partial pivoting (faer): for general (unsymmetric) systems.
///
/// `analyse` computes the COLAMD column ordering and the (supernodal) symbolic structure once
/// (`faer::sparse::linalg::lu::SymbolicLu`); every `factor` reuses it and the numeric storage.
/// Parallelism follows `faer::get_global_parallelism()` (set it to `Par::Seq` inside parallel
/// sweeps).
///
/// # Math
/// ```text
/// P A Q = L U     Q: fill-reducing column order (symbolic, once)
///                 P: row pivoting (numeric, per factor)
/// x = Q U^-1 L^-1 P b
/// ```
/// Every solution is checked as described in [`DirectParams`].
///
/// # Errors
/// [`SolverError::Singular`] for an empty row or column (checked before faer sees the values),
/// a structurally singular pattern, or a solution that is non-finite or fails the residual
/// check; the common errors of [`LinearSolver`].
///
/// # Example
/// ```
/// use capstan_solvers::{LinearSolver, SparseLu, SparsityPattern, SolverError};
/// let (pattern, _) = SparsityPattern::from_entries(2, 2, &[(0, 0), (1, 0), (0, 1), (1, 1)]).unwrap();
/// let mut lu = SparseLu::default();
/// lu.analyse(&pattern).unwrap();
/// lu.factor(&[0.0, 1.0, 2.0, 0.0]).unwrap(); // [[0, 2], [1, 0]]: needs pivoting
/// let mut x = vec![4.0, 3.0];
/// lu.solve_in_place(&mut x).unwrap();
/// assert_eq!(x, vec![3.0, 2.0]);
/// // a singular matrix is an error, never NaN
/// lu.factor(&[1.0, 1.0, 1.0, 1.0]).unwrap();
/// let mut x = vec![1.0, 2.0];
/// assert!(matches!(lu.solve_in_place(&mut x), Err(SolverError::Singular { .. })));
/// ```
#[derive(Debug, Default)]
pub struct SparseLu {
    params: DirectParams,
    pattern: Option<SparsityPattern>,
    symbolic: Option<SymbolicLu<usize>>,
    numeric: NumericLu<usize, f64>,
    values: Vec<f64>,
    factored: bool,
    factorisations: usize,
}

impl SparseLu {
    /// A solver with the given solution-check settings.
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] if `params` is out of range.
    pub fn new(params: DirectParams) -> Result<Self, SolverError> {
        params.validate()?;
        Ok(Self {
            params,
            ..Default::default()
        })
    }

    /// Numeric factorisations done since construction.
    pub fn factorisations(&self) -> usize {
        self.factorisations
    }

    /// The analysed pattern, if any.
    pub fn pattern(&self) -> Option<&SparsityPattern> {
        self.pattern.as_ref()
    }

    fn raw_solve(
        symbolic: &SymbolicLu<usize>,
        numeric: &NumericLu<usize, f64>,
        rhs: &mut [f64],
        n: usize,
        ncols: usize,
    ) -> Result<(), SolverError> {
        let par = faer::get_global_parallelism();
        let mut mem = scratch(symbolic.solve_in_place_scratch::<f64>(ncols, par))?;
        let stack = faer::dyn_stack::MemStack::new(&mut mem);
        let mat = faer::MatMut::from_column_major_slice_mut(rhs, n, ncols);
        LuRef::new_unchecked(symbolic, numeric).solve_in_place_with_conj(
            faer::Conj::No,
            mat,
            par,
            stack,
        );
        Ok(())
    }

    /// Solve of `ncols >= 1` columns with the solution check; `rhs` is column-major.
    pub(crate) fn checked_solve(&self, rhs: &mut [f64], ncols: usize) -> Result<(), SolverError> {
        let (Some(pattern), Some(symbolic), true) =
            (self.pattern.as_ref(), self.symbolic.as_ref(), self.factored)
        else {
            return Err(SolverError::CallOrder {
                called: "solve_in_place",
                requires: "factor",
            });
        };
        let n = pattern.nrows();
        if let Some(index) = crate::scalar::first_non_finite(rhs) {
            return Err(SolverError::NonFinite {
                quantity: "right-hand side",
                index: index % n.max(1),
                iteration: None,
            });
        }
        if n == 0 {
            return Ok(());
        }
        let b = rhs.to_vec();
        Self::raw_solve(symbolic, &self.numeric, rhs, n, ncols)?;
        let mut work = vec![0.0; n];
        for (x, b) in rhs.chunks_exact_mut(n).zip(b.chunks_exact(n)) {
            let numeric = &self.numeric;
            let mut failure = None;
            check_and_refine(&self.params, pattern, &self.values, b, x, &mut work, |r| {
                if let Err(e) = Self::raw_solve(symbolic, numeric, r, n, 1) {
                    failure = Some(e);
                }
            })?;
            if let Some(e) = failure {
                return Err(e);
            }
        }
        Ok(())
    }
}

impl LinearSolver<f64> for SparseLu {
    fn analyse(&mut self, pattern: &SparsityPattern) -> Result<(), SolverError> {
        check_square(pattern)?;
        self.factored = false;
        self.pattern = None;
        self.symbolic = None;
        // Always the supernodal kernel: on 5-point patterns faer's automatic choice picks the
        // simplicial kernel up to ~4000 unknowns, where it measured 2-3x slower (n = 4096:
        // 27 ms vs 8.6 ms per numeric factorisation, one core), and below ~100 unknowns the
        // difference is under a microsecond. It also keeps clear of the simplicial kernel's
        // zero-pivot panic (faer issue 232).
        let params = LuSymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        };
        self.symbolic = Some(factorize_symbolic_lu(pattern.as_faer_symbolic(), params)?);
        self.pattern = Some(pattern.clone());
        self.values = vec![0.0; pattern.nnz()];
        Ok(())
    }

    fn factor(&mut self, values: &[f64]) -> Result<(), SolverError> {
        let (Some(pattern), Some(symbolic)) = (self.pattern.as_ref(), self.symbolic.as_ref())
        else {
            return Err(SolverError::CallOrder {
                called: "factor",
                requires: "analyse",
            });
        };
        self.factored = false;
        check_values(pattern, values)?;
        if let Some(line) = empty_line(pattern, values) {
            return Err(SolverError::Singular { pivot: Some(line) });
        }
        self.values.copy_from_slice(values);
        if pattern.nrows() > 0 {
            let par = faer::get_global_parallelism();
            let mut mem =
                scratch(symbolic.factorize_numeric_lu_scratch::<f64>(par, Default::default()))?;
            let stack = faer::dyn_stack::MemStack::new(&mut mem);
            symbolic
                .factorize_numeric_lu(
                    &mut self.numeric,
                    pattern.as_faer(&self.values),
                    par,
                    stack,
                    Default::default(),
                )
                .map_err(|e| match e {
                    LuError::SymbolicSingular { index } => SolverError::Singular {
                        // `index` is a step of the column-permuted elimination
                        pivot: Some(symbolic.col_perm().arrays().0[index]),
                    },
                    LuError::Generic(e) => SolverError::Backend(e),
                })?;
        }
        self.factored = true;
        self.factorisations += 1;
        Ok(())
    }

    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<(), SolverError> {
        let n = self.pattern.as_ref().map_or(0, |p| p.nrows());
        check_rhs(rhs, n)?;
        self.checked_solve(rhs, 1)
    }

    fn last_iterations(&self) -> Option<usize> {
        None
    }

    fn solve_many_in_place(&mut self, rhs: &mut [f64], ncols: usize) -> Result<(), SolverError> {
        let n = self.pattern.as_ref().map_or(0, |p| p.nrows());
        let rows = check_many_len(rhs.len(), ncols)?;
        if ncols == 0 {
            return Ok(());
        }
        if rows != n {
            return Err(SolverError::DimensionMismatch {
                quantity: "rhs",
                expected: n * ncols,
                found: rhs.len(),
            });
        }
        self.checked_solve(rhs, ncols)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tridiagonal(n: usize) -> (SparsityPattern, Vec<f64>) {
        let mut entries = Vec::new();
        let mut vals = Vec::new();
        for i in 0..n {
            entries.push((i, i));
            vals.push(4.0);
            if i + 1 < n {
                entries.push((i + 1, i));
                vals.push(-1.0);
                entries.push((i, i + 1));
                vals.push(-2.0);
            }
        }
        let (p, slots) = SparsityPattern::from_entries(n, n, &entries).unwrap();
        let mut values = vec![0.0; p.nnz()];
        for (k, v) in vals.into_iter().enumerate() {
            values[slots[k]] += v;
        }
        (p, values)
    }

    #[test]
    fn solve_many_equals_default_column_loop() {
        let (p, values) = tridiagonal(30);
        let mut lu = SparseLu::default();
        lu.analyse(&p).unwrap();
        lu.factor(&values).unwrap();
        let rhs: Vec<f64> = (0..90).map(|k| (k as f64 * 0.37).sin()).collect();
        let mut blocked = rhs.clone();
        lu.solve_many_in_place(&mut blocked, 3).unwrap();
        let mut looped = rhs.clone();
        for c in looped.chunks_exact_mut(30) {
            lu.solve_in_place(c).unwrap();
        }
        for (a, b) in blocked.iter().zip(&looped) {
            assert!((a - b).abs() <= 1e-14 * (1.0 + b.abs())); // same factors: round-off only
        }
    }

    #[test]
    fn call_order_is_enforced() {
        let mut lu = SparseLu::default();
        assert!(matches!(
            lu.factor(&[1.0]),
            Err(SolverError::CallOrder {
                called: "factor",
                ..
            })
        ));
        let (p, values) = tridiagonal(3);
        lu.analyse(&p).unwrap();
        assert!(matches!(
            lu.solve_in_place(&mut [1.0, 2.0, 3.0]),
            Err(SolverError::CallOrder { .. })
        ));
        assert!(matches!(
            lu.factor(&values[1..]),
            Err(SolverError::DimensionMismatch { .. })
        ));
    }

    #[test]
    fn zero_dimension_is_trivial() {
        let (p, _) = SparsityPattern::from_entries(0, 0, &[]).unwrap();
        let mut lu = SparseLu::default();
        lu.analyse(&p).unwrap();
        lu.factor(&[]).unwrap();
        lu.solve_in_place(&mut []).unwrap();
    }

    #[test]
    fn rectangular_pattern_is_rejected() {
        let (p, _) = SparsityPattern::from_entries(2, 3, &[(0, 0)]).unwrap();
        assert!(matches!(
            SparseLu::default().analyse(&p),
            Err(SolverError::NotSquare { nrows: 2, ncols: 3 })
        ));
    }
}
