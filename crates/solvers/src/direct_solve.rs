//! The checked solve shared by the direct backends (LU and Cholesky): the solution check
//! and iterative refinement, block transposes, empty-line detection, scratch buffers.

use crate::direct_params::DirectParams;
use crate::error::SolverError;
use crate::linear_solver::{check_many_len, check_rhs, check_values};
use crate::scalar::max_abs;
use crate::sparsity_pattern::SparsityPattern;

/// The checks every direct `solve_in_place` starts with: a finite right-hand side (`ncols`
/// columns of `n`, column-major); `Ok(false)` when there is nothing to solve (`n = 0`).
///
/// # Errors
/// [`SolverError::NonFinite`] naming the first non-finite entry (its row).
pub(crate) fn finite_rhs(rhs: &[f64], n: usize) -> Result<bool, SolverError> {
    if let Some(index) = crate::scalar::first_non_finite(rhs) {
        return Err(SolverError::NonFinite {
            quantity: "right-hand side",
            index: index % n.max(1),
            iteration: None,
        });
    }
    Ok(n > 0)
}

/// The `solve_in_place`, `last_iterations` and `solve_many_in_place` of a direct backend
/// whose analysed pattern is `self.pattern` and whose solve with the solution check is
/// `self.checked_solve(rhs, ncols)`: the same three methods for every such backend.
macro_rules! direct_solves {
    () => {
        fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<(), SolverError> {
            let n = self.pattern.as_ref().map_or(0, |p| p.nrows());
            $crate::direct_solve::solve_one(n, rhs, |r, k| self.checked_solve(r, k))
        }

        fn last_iterations(&self) -> Option<usize> {
            None
        }

        fn solve_many_in_place(
            &mut self,
            rhs: &mut [f64],
            ncols: usize,
        ) -> Result<(), SolverError> {
            let n = self.pattern.as_ref().map_or(0, |p| p.nrows());
            $crate::direct_solve::solve_many(n, rhs, ncols, |r, k| self.checked_solve(r, k))
        }
    };
}
pub(crate) use direct_solves;

/// The checks that open a direct backend's `factor`: `analyse` has run (its pattern is
/// `pattern`), and `values` fit it and are finite.
///
/// # Errors
/// [`SolverError::CallOrder`], [`SolverError::DimensionMismatch`], [`SolverError::NonFinite`].
pub(crate) fn analysed_values<'p>(
    pattern: Option<&'p SparsityPattern>,
    values: &[f64],
) -> Result<&'p SparsityPattern, SolverError> {
    let pattern = pattern.ok_or(SolverError::call_order("factor", "analyse"))?;
    check_values(pattern, values)?;
    Ok(pattern)
}

/// [`SolverError::Singular`] at the first row or column of `values` with no nonzero.
///
/// # Errors
/// As said.
pub(crate) fn check_no_empty_line(
    pattern: &SparsityPattern,
    values: &[f64],
) -> Result<(), SolverError> {
    match empty_line(pattern, values) {
        Some(line) => Err(SolverError::Singular { pivot: Some(line) }),
        None => Ok(()),
    }
}

/// `solve_in_place` of a direct backend of order `n`: the length check, then `solve`.
///
/// # Errors
/// [`SolverError::DimensionMismatch`]; whatever `solve` returns.
pub(crate) fn solve_one(
    n: usize,
    rhs: &mut [f64],
    solve: impl FnOnce(&mut [f64], usize) -> Result<(), SolverError>,
) -> Result<(), SolverError> {
    check_rhs(rhs, n)?;
    solve(rhs, 1)
}

/// `solve_many_in_place` of a direct backend of order `n`: `ncols` columns of `n`
/// (column-major), checked, then `solve`.
///
/// # Errors
/// [`SolverError::DimensionMismatch`]; whatever `solve` returns.
pub(crate) fn solve_many(
    n: usize,
    rhs: &mut [f64],
    ncols: usize,
    solve: impl FnOnce(&mut [f64], usize) -> Result<(), SolverError>,
) -> Result<(), SolverError> {
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
    solve(rhs, ncols)
}

/// The one checked solve of the direct backends: `raw_solve(r, k)` overwrites the `k`
/// columns of `r` with `A^-1 r` from the factors; every column of the solution is then
/// checked and refined against `A` ([`check_and_refine`]).
///
/// # Math
/// ```text
/// x = A^-1 b (factors);  r = b - A x;  accept if |r|_inf <= tol |b|_inf,
/// else x += A^-1 r (at most `refinement_steps` times)
/// ```
///
/// # Errors
/// [`SolverError::Singular`] if a column fails the check after refinement; whatever
/// `raw_solve` returns.
pub(crate) fn checked_solve(
    params: &DirectParams,
    pattern: &SparsityPattern,
    values: &[f64],
    rhs: &mut [f64],
    ncols: usize,
    raw_solve: impl Fn(&mut [f64], usize) -> Result<(), SolverError>,
) -> Result<(), SolverError> {
    let n = pattern.nrows();
    let b = rhs.to_vec();
    raw_solve(rhs, ncols)?;
    let mut work = vec![0.0; n];
    for (x, b) in rhs.chunks_exact_mut(n).zip(b.chunks_exact(n)) {
        let mut failure = None;
        check_and_refine(params, pattern, values, b, x, &mut work, |r| {
            if let Err(e) = raw_solve(r, 1) {
                failure = Some(e);
            }
        })?;
        if let Some(e) = failure {
            return Err(e);
        }
    }
    Ok(())
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
    let bn = max_abs(b);
    for step in 0..=params.refinement_steps {
        if crate::scalar::first_non_finite(x).is_some() {
            return Err(SolverError::Singular { pivot: None });
        }
        pattern.residual_into(values, x, b, work);
        let rn = max_abs(work);
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

/// Rows of the tiles in [`to_row_major`] and [`to_column_major`]: a tile of 64 rows and up to
/// [`crate::multifrontal_lu::SOLVE_BLOCK_WIDTH`] columns is 32 KiB, in L1 or L2.
const TRANSPOSE_TILE: usize = 64;

/// `to[i k + c] = from[c n + i]`: the column-major `n x k` block `from` as a row-major one
/// (`to.len() = n k`).
pub(crate) fn to_row_major(from: &[f64], n: usize, k: usize, to: &mut [f64]) {
    debug_assert_eq!(from.len(), n * k);
    debug_assert_eq!(to.len(), n * k);
    for_tiles(n, k, |i, c| to[i * k + c] = from[c * n + i]);
}

/// `to[c n + i] = from[i k + c]`: the row-major `n x k` block `from` as a column-major one.
pub(crate) fn to_column_major(from: &[f64], n: usize, k: usize, to: &mut [f64]) {
    debug_assert_eq!(from.len(), n * k);
    debug_assert_eq!(to.len(), n * k);
    for_tiles(n, k, |i, c| to[c * n + i] = from[i * k + c]);
}

/// Calls `copy(i, c)` for every row `i < n` and column `c < k` of an `n x k` block, rows in
/// tiles of [`TRANSPOSE_TILE`] and, inside a tile, a column at a time: the column-major side
/// of a transpose is walked contiguously, the row-major side stays in cache.
fn for_tiles(n: usize, k: usize, mut copy: impl FnMut(usize, usize)) {
    for i0 in (0..n).step_by(TRANSPOSE_TILE) {
        let i1 = (i0 + TRANSPOSE_TILE).min(n);
        for c in 0..k {
            for i in i0..i1 {
                copy(i, c);
            }
        }
    }
}

/// `r = r - A x` for the `k` columns of the row-major `n x k` blocks `x`, `r` (row `i` =
/// entries `i k .. (i + 1) k`), by rows of `A` (`rows` = [`SparsityPattern::row_layout`]): each
/// row of `r` stays in cache while the rows of `x` it needs are subtracted from it.
fn subtract_product_rows(
    rows: &(Vec<usize>, Vec<usize>, Vec<usize>),
    values: &[f64],
    x: &[f64],
    r: &mut [f64],
    k: usize,
) {
    let (row_ptr, col_idx, slot) = rows;
    for (i, ri) in r.chunks_exact_mut(k).enumerate() {
        for p in row_ptr[i]..row_ptr[i + 1] {
            let a = values[slot[p]];
            let j = col_idx[p];
            for (rv, xv) in ri.iter_mut().zip(&x[j * k..(j + 1) * k]) {
                *rv -= a * xv;
            }
        }
    }
}

/// Columns `cols` of the row-major block `from` (`k` columns) into the row-major block `to`.
fn gather_columns(from: &[f64], k: usize, cols: &[usize], to: &mut Vec<f64>) {
    to.clear();
    for from_row in from.chunks_exact(k) {
        to.extend(cols.iter().map(|&c| from_row[c]));
    }
}

/// Scratch of [`check_and_refine_block`], reused across blocks.
#[derive(Debug, Default)]
pub(crate) struct RefineWork {
    /// The row layout of the pattern (built at the first check).
    rows: (Vec<usize>, Vec<usize>, Vec<usize>),
    residual: Vec<f64>,
    x_columns: Vec<f64>,
    correction: Vec<f64>,
}

/// [`check_and_refine`] for a block of `k` solutions at once. `b` is the column-major `n x k`
/// block of right-hand sides, `x` the row-major `n x k` block of solutions (row `i` = entries
/// `i k .. (i + 1) k`), and `solve(r, kr)` overwrites the row-major `n x kr` block `r` with
/// `A^-1 r`. Every column gets the check of [`check_and_refine`]; the residuals are computed
/// for the whole block, and only the columns that fail are refined, together.
///
/// # Math
/// ```text
/// for each column c:  accept x_c  iff  x_c finite  and  |b_c - A x_c|_inf <= tol |b_c|_inf
/// F = failing columns:  D = A^-1 (B - A X)[:, F],  X[:, F] <- X[:, F] + D
/// ```
///
/// # Errors
/// [`SolverError::Singular`] if a column is non-finite, or still fails after
/// `refinement_steps` refinements.
#[allow(clippy::too_many_arguments)] // the check's inputs, its output and its two closures' state
pub(crate) fn check_and_refine_block(
    params: &DirectParams,
    pattern: &SparsityPattern,
    values: &[f64],
    b: &[f64],
    x: &mut [f64],
    k: usize,
    work: &mut RefineWork,
    mut solve: impl FnMut(&mut [f64], usize),
) -> Result<(), SolverError> {
    let n = pattern.nrows();
    debug_assert_eq!(b.len(), n * k);
    debug_assert_eq!(x.len(), n * k);
    if k == 0 || n == 0 {
        return Ok(());
    }
    let b_norm: Vec<f64> = b.chunks_exact(n).map(max_abs).collect();
    if work.rows.0.is_empty() {
        work.rows = pattern.row_layout();
    }
    // the columns still to check; their x (compact, row-major) once some columns are accepted
    let mut cols: Vec<usize> = (0..k).collect();
    for step in 0..=params.refinement_steps {
        let kc = cols.len();
        let xs = if kc == k {
            &*x
        } else {
            gather_columns(x, k, &cols, &mut work.x_columns);
            work.x_columns.as_slice()
        };
        if crate::scalar::first_non_finite(xs).is_some() {
            return Err(SolverError::Singular { pivot: None });
        }
        let r = &mut work.residual;
        r.resize(n * k, 0.0);
        let r = &mut r[..n * kc];
        // r = b, transposed in tiles of rows as in `to_row_major`
        for i0 in (0..n).step_by(TRANSPOSE_TILE) {
            let i1 = (i0 + TRANSPOSE_TILE).min(n);
            for (q, &c) in cols.iter().enumerate() {
                for (i, v) in (i0..i1).zip(&b[c * n + i0..c * n + i1]) {
                    r[i * kc + q] = *v;
                }
            }
        }
        subtract_product_rows(&work.rows, values, xs, r, kc);
        let mut r_norm = vec![0.0f64; kc];
        for r_row in r.chunks_exact(kc) {
            for (m, v) in r_norm.iter_mut().zip(r_row) {
                *m = m.max(v.abs());
            }
        }
        // positions (in `cols`) of the columns that fail the check
        let failing: Vec<usize> = (0..kc)
            .filter(|&q| {
                // NaN fails too, as in `check_and_refine`
                r_norm[q]
                    .partial_cmp(&(params.residual_tolerance * b_norm[cols[q]]))
                    .is_none_or(|o| o == core::cmp::Ordering::Greater)
            })
            .collect();
        if failing.is_empty() {
            return Ok(());
        }
        if step == params.refinement_steps || failing.iter().any(|&q| !r_norm[q].is_finite()) {
            return Err(SolverError::Singular { pivot: None });
        }
        let kf = failing.len();
        let d = &mut work.correction;
        gather_columns(r, kc, &failing, d);
        solve(d, kf);
        cols = failing.iter().map(|&q| cols[q]).collect();
        for (x_row, d_row) in x.chunks_exact_mut(k).zip(d.chunks_exact(kf)) {
            for (&c, dv) in cols.iter().zip(d_row) {
                x_row[c] += dv;
            }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_line_finds_zero_column_and_zero_row() {
        let (p, _) = SparsityPattern::from_entries(2, 2, &[(0, 0), (0, 1), (1, 1)]).unwrap();
        assert_eq!(empty_line(&p, &[1.0, 0.0, 0.0]), Some(1)); // column 1 all zero
        assert_eq!(empty_line(&p, &[1.0, 1.0, 0.0]), Some(1)); // row 1 all zero
        assert_eq!(empty_line(&p, &[1.0, 0.0, 1.0]), None);
    }

    #[test]
    fn block_refinement_solves_only_the_failing_columns() {
        let (p, _) = SparsityPattern::from_entries(2, 2, &[(0, 0), (1, 1)]).unwrap();
        let values = [2.0, 4.0];
        // b column-major (3 columns), x row-major: column 1 is 5% off, columns 0 and 2 exact
        let b = [2.0, 4.0, 4.0, 8.0, 0.0, 0.0];
        let mut x = [1.0, 1.9, 0.0, 1.0, 2.0, 0.0];
        let mut widths = Vec::new();
        let params = DirectParams::default();
        let mut work = RefineWork::default();
        let solve = |r: &mut [f64], k: usize| {
            widths.push(k);
            for (i, v) in r.iter_mut().enumerate() {
                *v /= values[i / k];
            }
        };
        check_and_refine_block(&params, &p, &values, &b, &mut x, 3, &mut work, solve).unwrap();
        assert_eq!(x, [1.0, 2.0, 0.0, 1.0, 2.0, 0.0]); // divisions by powers of two: exact
        assert_eq!(widths, vec![1]); // one refinement, of the failing column only
        let mut x = [1.0, f64::NAN, 0.0, 1.0, 2.0, 0.0];
        let err = check_and_refine_block(&params, &p, &values, &b, &mut x, 3, &mut work, |_, _| {});
        assert!(matches!(err, Err(SolverError::Singular { pivot: None })));
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
