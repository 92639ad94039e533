//! faer sparse LU with the symbolic analysis reused across factorisations.

use faer::dyn_stack::{MemStack, StackReq};
use faer::perm::PermRef;
use faer::sparse::linalg::LuError;
use faer::sparse::linalg::colamd;
use faer::sparse::linalg::lu::supernodal::{
    SupernodalLu, SymbolicSupernodalLu, factorize_supernodal_numeric_lu,
    factorize_supernodal_numeric_lu_scratch, factorize_supernodal_symbolic_lu,
    factorize_supernodal_symbolic_lu_scratch, solve_in_place_scratch,
};
use faer::sparse::linalg::qr::{
    col_etree, col_etree_scratch, column_counts_aat_scratch, column_counts_ata, postorder,
    postorder_scratch,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};

use crate::direct_params::DirectParams;
use crate::direct_solve::{
    RefineWork, analysed_values, check_and_refine, check_and_refine_block, check_no_empty_line,
    checked_solve, direct_solves, finite_rhs, to_column_major, to_row_major,
};
use crate::error::{SolverError, scratch};
use crate::linear_solver::{LinearSolver, check_square};
use crate::lu_kind::LuKind;
use crate::multifrontal_lu::solve::{BlockWork, SOLVE_BLOCK_WIDTH};
use crate::multifrontal_lu::{FrontFailure, FrontalFactors, FrontalStructure};
use crate::ordering::is_permutation;
use crate::sparsity_pattern::SparsityPattern;

/// Sparse LU with row pivoting: for general (unsymmetric) systems.
///
/// Two kernels ([`DirectParams::lu_kind`], see [`LuKind`]): a multifrontal LU on the
/// structure of `A + A^T` with threshold pivoting inside each front (the default), and faer's
/// supernodal LU with partial pivoting on the structure of `A^T A`. `analyse` computes the
/// ordering ([`DirectParams::ordering`]: by default AMD on `A + A^T` for the multifrontal
/// kernel and COLAMD for the supernodal one; a nested dissection of a structured grid; or a
/// permutation given with [`SparseLu::with_column_permutation`]) and the symbolic structure
/// once; every `factor` reuses it. When a front has no acceptable pivot, `factor` refactorises
/// with the supernodal kernel (its structure is analysed then, once). Parallelism follows
/// `faer::get_global_parallelism()` (set it to `Par::Seq` inside parallel sweeps).
///
/// # Math
/// ```text
/// P A Q = L U     Q: fill-reducing column order (symbolic, once)
///                 P: row pivoting (numeric, per factor)
/// x = Q U^-1 L^-1 P b
/// supernodal:    struct(L), struct(U^T) within struct(R),  R^T R = Q^T A^T A Q  (any P)
/// multifrontal:  struct(L), struct(U^T) within struct(C),  C^T C = Q^T (A + A^T) Q,
///                rows of Q (the symmetric order) permuted by P only inside a front's block,
///                |pivot| >= 0.01 max |entry of its column|
/// ```
/// Every solution is checked as described in [`DirectParams`].
///
/// # Errors
/// [`SolverError::Singular`] for an empty row or column (checked before faer sees the values),
/// a structurally singular pattern, a pivot column that vanishes exactly (multifrontal
/// kernel), or a solution that is non-finite or fails the residual check;
/// [`SolverError::InvalidParameter`] or [`SolverError::DimensionMismatch`] for an
/// ordering that does not fit the pattern; the common errors of [`LinearSolver`].
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
/// // a singular matrix is an error (from `factor` or from the checked solve), never NaN
/// let mut x = vec![1.0, 2.0];
/// let result = lu.factor(&[1.0, 1.0, 1.0, 1.0]).and_then(|()| lu.solve_in_place(&mut x));
/// assert!(matches!(result, Err(SolverError::Singular { .. })));
/// ```
#[derive(Debug, Default)]
pub struct SparseLu {
    params: DirectParams,
    column_permutation: Option<Vec<usize>>,
    pattern: Option<SparsityPattern>,
    /// The supernodal structure: analysed for [`LuKind::Supernodal`], or at the first fallback.
    symbolic: Option<Symbolic>,
    numeric: SupernodalLu<usize, f64>,
    row_perm_fwd: Vec<usize>,
    row_perm_inv: Vec<usize>,
    /// The multifrontal structure, for [`LuKind::Multifrontal`].
    frontal: Option<FrontalStructure>,
    frontal_factors: FrontalFactors,
    /// `A^T A` fill bound of the analysed order.
    fill_bound: Option<usize>,
    values: Vec<f64>,
    /// The kernel that made the current factors (`None`: not factored).
    factored: Option<LuKind>,
    factorisations: usize,
}

/// What `analyse` keeps: the column order and faer's supernodal structure.
#[derive(Debug)]
struct Symbolic {
    supernodal: SymbolicSupernodalLu<usize>,
    col_perm_fwd: Vec<usize>,
    col_perm_inv: Vec<usize>,
    structural_bound: usize,
}

impl Symbolic {
    fn col_perm(&self) -> PermRef<'_, usize> {
        PermRef::new_checked(
            &self.col_perm_fwd,
            &self.col_perm_inv,
            self.col_perm_fwd.len(),
        )
    }
}

impl SparseLu {
    /// A solver with the given solution-check and ordering settings.
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

    /// Uses `perm` as the column order (`perm[k]` = column eliminated `k`-th) instead of
    /// [`DirectParams::ordering`]; `analyse` checks it is a permutation of the columns.
    ///
    /// # Example
    /// ```
    /// use capstan_solvers::{LinearSolver, SparseLu, samples::Poisson2d};
    /// let system = Poisson2d::new(8).system();
    /// let reversed: Vec<usize> = (0..64).rev().collect();
    /// let mut lu = SparseLu::default().with_column_permutation(reversed);
    /// lu.analyse(&system.pattern).unwrap();
    /// lu.factor(&system.values).unwrap();
    /// let mut x = system.rhs.clone();
    /// lu.solve_in_place(&mut x).unwrap();
    /// assert!(system.residual_norm(&x) < 1e-14);
    /// ```
    pub fn with_column_permutation(mut self, perm: Vec<usize>) -> Self {
        self.column_permutation = Some(perm);
        self.symbolic = None;
        self.frontal = None;
        self.fill_bound = None;
        self.pattern = None;
        self.factored = None;
        self
    }

    /// The kernel that produced the current factors (`None` before a successful `factor`):
    /// [`LuKind::Multifrontal`], or [`LuKind::Supernodal`] when configured or after a
    /// fallback.
    pub fn last_kind(&self) -> Option<LuKind> {
        self.factored
    }

    /// Values stored in the factors by the multifrontal kernel (`L` and `U`, the diagonal
    /// once), if its structure is analysed: the exact size of its factor storage, to compare
    /// with [`SparseLu::structural_fill_bound`].
    pub fn multifrontal_factor_entries(&self) -> Option<usize> {
        self.frontal.as_ref().map(FrontalStructure::factor_entries)
    }

    /// Numeric factorisations done since construction.
    pub fn factorisations(&self) -> usize {
        self.factorisations
    }

    /// The analysed pattern, if any.
    pub fn pattern(&self) -> Option<&SparsityPattern> {
        self.pattern.as_ref()
    }

    /// The column order of the analysis (`perm[k]` = column eliminated `k`-th), if analysed.
    ///
    /// The multifrontal kernel orders rows and columns alike, so this is also its row order
    /// before pivoting.
    pub fn column_permutation(&self) -> Option<&[usize]> {
        match (&self.frontal, &self.symbolic) {
            (Some(frontal), _) => Some(frontal.permutation()),
            (None, Some(s)) => Some(s.col_perm_fwd.as_slice()),
            (None, None) => None,
        }
    }

    /// The static bound on the fill of the analysed column order, if analysed: `2 nnz(R) - n`,
    /// where `R` is the Cholesky factor of `Q^T A^T A Q`; `nnz(L) + nnz(U)` never exceeds it,
    /// whatever the pivoting. A measure for comparing orderings (the supernodal kernel stores
    /// dense panels on this structure, so the memory it uses is of this order).
    pub fn structural_fill_bound(&self) -> Option<usize> {
        self.fill_bound
    }

    fn raw_solve(
        symbolic: &Symbolic,
        numeric: &SupernodalLu<usize, f64>,
        row_perm: PermRef<'_, usize>,
        rhs: &mut [f64],
        n: usize,
        ncols: usize,
    ) -> Result<(), SolverError> {
        let par = faer::get_global_parallelism();
        let mut mem = scratch(solve_in_place_scratch::<usize, f64>(n, ncols, par))?;
        let stack = MemStack::new(&mut mem);
        let mat = faer::MatMut::from_column_major_slice_mut(rhs, n, ncols);
        numeric.solve_in_place_with_conj(
            row_perm,
            symbolic.col_perm(),
            faer::Conj::No,
            mat,
            par,
            stack,
        );
        Ok(())
    }

    /// Solve of `ncols >= 1` columns with the solution check; `rhs` is column-major.
    pub(crate) fn checked_solve(&self, rhs: &mut [f64], ncols: usize) -> Result<(), SolverError> {
        let (Some(pattern), Some(kind)) = (self.pattern.as_ref(), self.factored) else {
            return Err(SolverError::call_order("solve_in_place", "factor"));
        };
        let n = pattern.nrows();
        if !finite_rhs(rhs, n)? {
            return Ok(());
        }
        if kind == LuKind::Multifrontal {
            return self.checked_solve_multifrontal(pattern, rhs, ncols);
        }
        let Some(symbolic) = self.symbolic.as_ref() else {
            return Err(SolverError::call_order("solve_in_place", "factor"));
        };
        let row_perm = PermRef::new_checked(&self.row_perm_fwd, &self.row_perm_inv, n);
        checked_solve(&self.params, pattern, &self.values, rhs, ncols, |r, k| {
            Self::raw_solve(symbolic, &self.numeric, row_perm, r, n, k)
        })
    }

    /// Multifrontal solve of the columns of `rhs` (column-major), each checked and refined.
    ///
    /// One column goes through the scalar solve. More are solved in blocks of
    /// [`SOLVE_BLOCK_WIDTH`] columns by the blocked kernel
    /// ([`FrontalStructure::solve_rows_in_place`]: dense triangular solves and GEMMs per
    /// front); each block is checked as a whole, and its failing columns are refined together
    /// ([`check_and_refine_block`]).
    fn checked_solve_multifrontal(
        &self,
        pattern: &SparsityPattern,
        rhs: &mut [f64],
        ncols: usize,
    ) -> Result<(), SolverError> {
        let Some(frontal) = self.frontal.as_ref() else {
            return Err(SolverError::call_order("solve_in_place", "factor"));
        };
        let n = pattern.nrows();
        if ncols == 1 {
            let mut y = vec![0.0; n];
            let mut work = vec![0.0; n];
            let b = rhs.to_vec();
            frontal.solve_in_place(&self.frontal_factors, rhs, &mut y);
            return check_and_refine(
                &self.params,
                pattern,
                &self.values,
                &b,
                rhs,
                &mut work,
                |r| frontal.solve_in_place(&self.frontal_factors, r, &mut y),
            );
        }
        let mut block_work = BlockWork::default();
        let mut refine_work = RefineWork::default();
        let mut x = vec![0.0; n * ncols.min(SOLVE_BLOCK_WIDTH)];
        for chunk in rhs.chunks_mut(n * SOLVE_BLOCK_WIDTH) {
            let k = chunk.len() / n;
            let x = &mut x[..n * k];
            to_row_major(chunk, n, k, x);
            frontal.solve_rows_in_place(&self.frontal_factors, x, k, &mut block_work);
            check_and_refine_block(
                &self.params,
                pattern,
                &self.values,
                chunk,
                x,
                k,
                &mut refine_work,
                |d, kd| frontal.solve_rows_in_place(&self.frontal_factors, d, kd, &mut block_work),
            )?;
            to_column_major(x, n, k, chunk);
        }
        Ok(())
    }

    /// The explicit order: the permutation given, or the configured ordering's (`None` for
    /// [`crate::ColumnOrdering::Auto`]); checked against the pattern.
    fn explicit_order(&self, pattern: &SparsityPattern) -> Result<Option<Vec<usize>>, SolverError> {
        let n = pattern.ncols();
        let perm = match &self.column_permutation {
            Some(perm) => Some(perm.clone()),
            None => self.params.ordering.permutation(pattern)?,
        };
        if let Some(perm) = &perm {
            if perm.len() != n {
                return Err(SolverError::DimensionMismatch {
                    quantity: "column permutation",
                    expected: n,
                    found: perm.len(),
                });
            }
            if !is_permutation(perm, n) {
                return Err(SolverError::invalid(
                    "column permutation",
                    n as f64,
                    "a permutation of 0..n",
                ));
            }
        }
        Ok(perm)
    }

    /// The column order of the supernodal kernel: the explicit order, or COLAMD.
    fn column_order(&self, pattern: &SparsityPattern) -> Result<Vec<usize>, SolverError> {
        let n = pattern.ncols();
        if let Some(perm) = self.explicit_order(pattern)? {
            return Ok(perm);
        }
        // faer's own choice for LU, with its default settings
        let mut fwd = vec![0usize; n];
        let mut inv = vec![0usize; n];
        let mut mem = scratch(colamd::order_scratch::<usize>(n, n, pattern.nnz()))?;
        colamd::order(
            &mut fwd,
            &mut inv,
            pattern.as_faer_symbolic(),
            Default::default(),
            MemStack::new(&mut mem),
        )?;
        Ok(fwd)
    }

    /// faer's supernodal LU analysis (what `faer::sparse::linalg::lu::factorize_symbolic_lu`
    /// does after COLAMD), for any column order: column elimination tree and column counts of
    /// `A^T A`, then the supernodes.
    fn symbolic(
        pattern: &SparsityPattern,
        col_perm_fwd: Vec<usize>,
    ) -> Result<Symbolic, SolverError> {
        let (supernodal, structural_bound) = Self::ata_analysis(pattern, &col_perm_fwd, true)?;
        let n = pattern.ncols();
        let mut col_perm_inv = vec![0usize; n];
        for (k, &p) in col_perm_fwd.iter().enumerate() {
            col_perm_inv[p] = k;
        }
        Ok(Symbolic {
            supernodal: supernodal.expect("supernodes requested"),
            col_perm_fwd,
            col_perm_inv,
            structural_bound,
        })
    }

    /// Column elimination tree and column counts of `A^T A` under `col_perm_fwd`: the fill
    /// bound `2 nnz(R) - n`, and faer's supernodal LU structure if `with_supernodes`.
    fn ata_analysis(
        pattern: &SparsityPattern,
        col_perm_fwd: &[usize],
        with_supernodes: bool,
    ) -> Result<(Option<SymbolicSupernodalLu<usize>>, usize), SolverError> {
        let n = pattern.ncols();
        let mut col_perm_inv = vec![0usize; n];
        for (k, &p) in col_perm_fwd.iter().enumerate() {
            col_perm_inv[p] = k;
        }
        let a = pattern.as_faer_symbolic();
        let (at_col_ptr, at_row_idx, _) = pattern.row_layout();
        let at = SymbolicSparseColMatRef::new_checked(n, n, &at_col_ptr, None, &at_row_idx);
        let col_perm = PermRef::new_checked(col_perm_fwd, &col_perm_inv, n);
        let mut mem = scratch(StackReq::any_of(&[
            col_etree_scratch::<usize>(n, n),
            postorder_scratch::<usize>(n),
            column_counts_aat_scratch::<usize>(n, n),
            factorize_supernodal_symbolic_lu_scratch::<usize>(n, n),
        ]))?;
        let stack = MemStack::new(&mut mem);
        let mut etree = vec![0usize; n];
        let mut post = vec![0usize; n];
        let mut col_counts = vec![0usize; n];
        let mut min_row = vec![0usize; n];
        let etree = col_etree(a, Some(col_perm), &mut etree, stack);
        postorder(&mut post, etree, stack);
        column_counts_ata(
            &mut col_counts,
            &mut min_row,
            at,
            Some(col_perm),
            etree,
            &post,
            stack,
        );
        let structural_bound = (2 * col_counts.iter().sum::<usize>()).saturating_sub(n);
        if !with_supernodes {
            return Ok((None, structural_bound));
        }
        let supernodal = factorize_supernodal_symbolic_lu(
            a,
            Some(col_perm),
            &min_row,
            etree,
            &col_counts,
            stack,
            Default::default(),
        )?;
        Ok((Some(supernodal), structural_bound))
    }

    /// Supernodal numeric factorisation of `self.values`.
    fn factor_supernodal(&mut self) -> Result<(), SolverError> {
        let (Some(pattern), Some(symbolic)) = (self.pattern.as_ref(), self.symbolic.as_ref())
        else {
            return Err(SolverError::call_order("factor", "analyse"));
        };
        let n = pattern.nrows();
        let par = faer::get_global_parallelism();
        let nnz = pattern.nnz();
        // the transpose lives only during the factorisation, as in faer's own LU
        let mut at_values = vec![0.0f64; nnz];
        let mut at_col_ptr = vec![0usize; n + 1];
        let mut at_row_idx = vec![0usize; nnz];
        let mut mem = scratch(StackReq::any_of(&[
            faer::sparse::utils::transpose_scratch::<usize>(n, n),
            factorize_supernodal_numeric_lu_scratch::<usize, f64>(
                &symbolic.supernodal,
                Default::default(),
            ),
        ]))?;
        let stack = MemStack::new(&mut mem);
        let a = pattern.as_faer(&self.values);
        let at = faer::sparse::utils::transpose(
            &mut at_values,
            &mut at_col_ptr,
            &mut at_row_idx,
            a,
            stack,
        );
        let at = SparseColMatRef::new(at.symbolic(), at.val());
        self.row_perm_fwd.resize(n, 0);
        self.row_perm_inv.resize(n, 0);
        factorize_supernodal_numeric_lu(
            &mut self.row_perm_fwd,
            &mut self.row_perm_inv,
            &mut self.numeric,
            a,
            at,
            symbolic.col_perm(),
            &symbolic.supernodal,
            par,
            stack,
            Default::default(),
        )
        .map_err(|e| match e {
            LuError::SymbolicSingular { index } => SolverError::Singular {
                // `index` is a step of the column-permuted elimination
                pivot: Some(symbolic.col_perm_fwd[index]),
            },
            LuError::Generic(e) => SolverError::Backend(e),
        })
    }
}

impl LinearSolver<f64> for SparseLu {
    fn analyse(&mut self, pattern: &SparsityPattern) -> Result<(), SolverError> {
        check_square(pattern)?;
        self.factored = None;
        self.pattern = None;
        self.symbolic = None;
        self.frontal = None;
        self.fill_bound = None;
        self.frontal_factors = FrontalFactors::default();
        if self.params.lu_kind.resolved() == LuKind::Multifrontal {
            // AMD on A + A^T unless an order is given (the structure is that of A + A^T)
            let order = self.explicit_order(pattern)?;
            if let Some(frontal) = FrontalStructure::analyse(pattern, order.as_deref())? {
                let (_, bound) = Self::ata_analysis(pattern, frontal.permutation(), false)?;
                self.fill_bound = Some(bound);
                self.frontal = Some(frontal);
            }
        }
        if self.frontal.is_none() {
            // Always the supernodal kernel here: on 5-point patterns faer's automatic choice
            // picks the simplicial kernel up to ~4000 unknowns, where it measured 2-3x slower
            // (n = 4096: 27 ms vs 8.6 ms per numeric factorisation, one core), and below ~100
            // unknowns the difference is under a microsecond. It also keeps clear of the
            // simplicial kernel's zero-pivot panic (faer issue 232).
            let order = self.column_order(pattern)?;
            let symbolic = Self::symbolic(pattern, order)?;
            self.fill_bound = Some(symbolic.structural_bound);
            self.symbolic = Some(symbolic);
        }
        self.pattern = Some(pattern.clone());
        self.values = vec![0.0; pattern.nnz()];
        Ok(())
    }

    fn factor(&mut self, values: &[f64]) -> Result<(), SolverError> {
        self.factored = None;
        let pattern = analysed_values(self.pattern.as_ref(), values)?;
        check_no_empty_line(pattern, values)?;
        self.values.copy_from_slice(values);
        let n = pattern.nrows();
        let mut kind = LuKind::Supernodal;
        if let Some(frontal) = self.frontal.as_ref() {
            let par = faer::get_global_parallelism();
            match frontal.factor(pattern, &self.values, &mut self.frontal_factors, par) {
                Ok(()) => kind = LuKind::Multifrontal,
                Err(FrontFailure::Singular(column)) => {
                    return Err(SolverError::Singular {
                        pivot: Some(column),
                    });
                }
                Err(FrontFailure::NonFinite) => return Err(SolverError::Singular { pivot: None }),
                Err(FrontFailure::NeedsPivoting) => {
                    // a pivot from outside a front is needed: the supernodal kernel pivots
                    // over all rows; its structure is analysed once, at the first fallback
                    self.frontal_factors = FrontalFactors::default();
                    if self.symbolic.is_none() {
                        let order = self.column_order(pattern)?;
                        self.symbolic = Some(Self::symbolic(pattern, order)?);
                    }
                }
            }
        }
        if kind == LuKind::Supernodal && n > 0 {
            self.factor_supernodal()?;
        }
        self.factored = Some(kind);
        self.factorisations += 1;
        Ok(())
    }

    direct_solves!();
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
