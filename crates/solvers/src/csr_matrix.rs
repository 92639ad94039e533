//! A compressed-row matrix for the matrix-free kernels of the Krylov and multigrid solvers:
//! products, transposes and the Galerkin triple product `P^T A P`.

use rayon::prelude::*;

use crate::error::SolverError;
use crate::sparsity_pattern::SparsityPattern;

/// Rows per parallel task of the products (large enough to amortise the scheduling).
const ROWS_PER_TASK: usize = 4096;

/// A real sparse matrix in compressed rows (CSR), columns sorted within each row.
///
/// # Math
/// ```text
/// row i holds the entries (col_idx[p], values[p]) for p in row_ptr[i] .. row_ptr[i + 1]
/// (A x)_i = sum_p values[p] x[col_idx[p]]
/// ```
/// Column indices are `u32` (half the memory traffic of `usize` in a product; at most
/// `u32::MAX` columns).
#[derive(Clone, Debug, PartialEq)]
pub struct CsrMatrix {
    nrows: usize,
    ncols: usize,
    row_ptr: Vec<usize>,
    col_idx: Vec<u32>,
    values: Vec<f64>,
}

impl CsrMatrix {
    /// The matrix from its compressed rows.
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] for inconsistent pointers, unsorted or out-of-range
    /// columns (or more than `u32::MAX` columns); [`SolverError::DimensionMismatch`] when
    /// `values` and `col_idx` differ in length.
    pub fn new(
        nrows: usize,
        ncols: usize,
        row_ptr: Vec<usize>,
        col_idx: Vec<u32>,
        values: Vec<f64>,
    ) -> Result<Self, SolverError> {
        if ncols > u32::MAX as usize {
            return Err(SolverError::invalid("ncols", ncols as f64, "[0, 2^32)"));
        }
        if row_ptr.len() != nrows + 1 || row_ptr[0] != 0 || row_ptr[nrows] != col_idx.len() {
            return Err(SolverError::invalid(
                "row_ptr",
                row_ptr.len() as f64,
                "nrows + 1 pointers from 0 to nnz",
            ));
        }
        if values.len() != col_idx.len() {
            return Err(SolverError::DimensionMismatch {
                quantity: "values",
                expected: col_idx.len(),
                found: values.len(),
            });
        }
        for i in 0..nrows {
            if row_ptr[i] > row_ptr[i + 1] {
                return Err(SolverError::invalid("row_ptr", i as f64, "non-decreasing"));
            }
            let cols = &col_idx[row_ptr[i]..row_ptr[i + 1]];
            if cols.windows(2).any(|w| w[0] >= w[1])
                || cols.last().is_some_and(|&c| c as usize >= ncols)
            {
                return Err(SolverError::invalid(
                    "col_idx",
                    i as f64,
                    "strictly increasing columns below ncols in each row",
                ));
            }
        }
        Ok(Self {
            nrows,
            ncols,
            row_ptr,
            col_idx,
            values,
        })
    }

    /// The matrix of `pattern` (compressed columns) with `values` in slot order.
    ///
    /// # Errors
    /// [`SolverError::DimensionMismatch`] for a wrong number of values.
    pub fn from_pattern(pattern: &SparsityPattern, values: &[f64]) -> Result<Self, SolverError> {
        pattern.check_values_len(values.len())?;
        let (row_ptr, col_idx, slot) = pattern.row_layout();
        Self::new(
            pattern.nrows(),
            pattern.ncols(),
            row_ptr,
            col_idx.into_iter().map(|c| c as u32).collect(),
            slot.into_iter().map(|s| values[s]).collect(),
        )
    }

    /// Number of rows.
    pub fn nrows(&self) -> usize {
        self.nrows
    }

    /// Number of columns.
    pub fn ncols(&self) -> usize {
        self.ncols
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.values.len()
    }

    /// Row pointers (`nrows + 1`).
    pub fn row_ptr(&self) -> &[usize] {
        &self.row_ptr
    }

    /// Column of every stored entry.
    pub fn col_idx(&self) -> &[u32] {
        &self.col_idx
    }

    /// Value of every stored entry.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Mutable values (the pattern is fixed).
    pub fn values_mut(&mut self) -> &mut [f64] {
        &mut self.values
    }

    /// Bytes held by the matrix.
    pub fn bytes(&self) -> usize {
        8 * self.row_ptr.len() + 4 * self.col_idx.len() + 8 * self.values.len()
    }

    /// The entries of row `i`: columns and values.
    pub fn row(&self, i: usize) -> (&[u32], &[f64]) {
        let r = self.row_ptr[i]..self.row_ptr[i + 1];
        (&self.col_idx[r.clone()], &self.values[r])
    }

    /// The diagonal `a_ii` (0 where not stored).
    pub fn diagonal(&self) -> Vec<f64> {
        (0..self.nrows)
            .map(|i| {
                let (c, v) = self.row(i);
                c.binary_search(&(i as u32)).map_or(0.0, |p| v[p])
            })
            .collect()
    }

    /// `y = A x`, rows in parallel.
    ///
    /// # Panics
    /// If `x` or `y` has the wrong length.
    #[track_caller]
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        assert!(
            x.len() == self.ncols && y.len() == self.nrows,
            "lengths of A x"
        );
        y.par_chunks_mut(ROWS_PER_TASK)
            .enumerate()
            .for_each(|(t, chunk)| {
                let base = t * ROWS_PER_TASK;
                for (k, yi) in chunk.iter_mut().enumerate() {
                    let (c, v) = self.row(base + k);
                    *yi = c.iter().zip(v).map(|(&j, a)| a * x[j as usize]).sum();
                }
            });
    }

    /// `r = b - A x`, rows in parallel.
    ///
    /// # Panics
    /// If a slice has the wrong length.
    #[track_caller]
    pub fn residual(&self, x: &[f64], b: &[f64], r: &mut [f64]) {
        assert!(b.len() == self.nrows, "length of b");
        self.mul_vec(x, r);
        r.par_iter_mut().zip(b).for_each(|(ri, bi)| *ri = bi - *ri);
    }

    /// The transpose `A^T`, in compressed rows.
    pub fn transpose(&self) -> Self {
        let mut row_ptr = vec![0usize; self.ncols + 1];
        for &c in &self.col_idx {
            row_ptr[c as usize + 1] += 1;
        }
        for j in 0..self.ncols {
            row_ptr[j + 1] += row_ptr[j];
        }
        let mut next = row_ptr.clone();
        let mut col_idx = vec![0u32; self.nnz()];
        let mut values = vec![0.0; self.nnz()];
        for i in 0..self.nrows {
            let (c, v) = self.row(i);
            for (&j, &a) in c.iter().zip(v) {
                let p = next[j as usize];
                col_idx[p] = i as u32;
                values[p] = a;
                next[j as usize] += 1;
            }
        }
        Self {
            nrows: self.ncols,
            ncols: self.nrows,
            row_ptr,
            col_idx,
            values,
        }
    }

    /// The Galerkin coarse operator `P^T A P` for the prolongation `P` (`A` square `n x n`,
    /// `P` `n x m`), given `restriction = P^T`.
    ///
    /// # Math
    /// ```text
    /// (P^T A P)_IJ = sum_i sum_j R_Ii a_ij P_jJ,   R = P^T
    /// ```
    /// row by row of the result (one sparse accumulator per task, at most about eight tasks per
    /// thread; coarse rows in parallel):
    /// no intermediate `A P` is stored. Exact zeros that arise are kept, so the pattern
    /// depends only on the patterns of `A` and `P`.
    ///
    /// # Panics
    /// If the dimensions do not match.
    #[track_caller]
    pub fn galerkin(&self, prolongation: &Self, restriction: &Self) -> Self {
        assert!(
            self.nrows == self.ncols
                && prolongation.nrows == self.nrows
                && restriction.ncols == self.nrows
                && restriction.nrows == prolongation.ncols,
            "P^T A P: dimensions"
        );
        let m = prolongation.ncols;
        // each task allocates two accumulators of length m: at most ~8 tasks per thread, so
        // the set-up stays O(m) (not O(m^2 / 512)) on large coarse levels
        let chunk = (ROWS_PER_TASK / 8).max(m.div_ceil(8 * rayon::current_num_threads()));
        let tasks: Vec<(usize, usize)> = (0..m)
            .step_by(chunk)
            .map(|s| (s, (s + chunk).min(m)))
            .collect();
        let parts: Vec<(Vec<usize>, Vec<u32>, Vec<f64>)> = tasks
            .par_iter()
            .map(|&(start, end)| {
                let mut acc = vec![0.0f64; m];
                let mut mark = vec![usize::MAX; m];
                let mut cols: Vec<u32> = Vec::new();
                let mut lens = Vec::with_capacity(end - start);
                let mut out_c = Vec::new();
                let mut out_v = Vec::new();
                for big_i in start..end {
                    cols.clear();
                    let (ri, rv) = restriction.row(big_i);
                    for (&i, &r) in ri.iter().zip(rv) {
                        let (ac, av) = self.row(i as usize);
                        for (&j, &a) in ac.iter().zip(av) {
                            let ra = r * a;
                            let (pc, pv) = prolongation.row(j as usize);
                            for (&big_j, &p) in pc.iter().zip(pv) {
                                let jj = big_j as usize;
                                if mark[jj] != big_i {
                                    mark[jj] = big_i;
                                    acc[jj] = 0.0;
                                    cols.push(big_j);
                                }
                                acc[jj] += ra * p;
                            }
                        }
                    }
                    cols.sort_unstable();
                    lens.push(cols.len());
                    for &c in &cols {
                        out_c.push(c);
                        out_v.push(acc[c as usize]);
                    }
                }
                (lens, out_c, out_v)
            })
            .collect();
        let nnz = parts.iter().map(|p| p.1.len()).sum();
        let mut row_ptr = Vec::with_capacity(m + 1);
        row_ptr.push(0);
        let mut col_idx = Vec::with_capacity(nnz);
        let mut values = Vec::with_capacity(nnz);
        for (lens, c, v) in parts {
            for l in lens {
                row_ptr.push(row_ptr.last().copied().unwrap_or(0) + l);
            }
            col_idx.extend(c);
            values.extend(v);
        }
        Self {
            nrows: m,
            ncols: m,
            row_ptr,
            col_idx,
            values,
        }
    }

    /// The pattern (compressed columns) and values in slot order, for the direct backends.
    pub fn to_pattern(&self) -> (SparsityPattern, Vec<f64>) {
        let t = self.transpose(); // rows of A^T = columns of A, rows sorted
        let pattern = SparsityPattern::from_compressed_columns(
            self.nrows,
            self.ncols,
            t.row_ptr,
            t.col_idx.into_iter().map(|c| c as usize).collect(),
        )
        .expect("a transposed CSR matrix is a valid CSC pattern");
        (pattern, t.values)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dense(a: &CsrMatrix) -> Vec<Vec<f64>> {
        let mut d = vec![vec![0.0; a.ncols()]; a.nrows()];
        for (i, row) in d.iter_mut().enumerate() {
            let (c, v) = a.row(i);
            for (&j, &x) in c.iter().zip(v) {
                row[j as usize] = x;
            }
        }
        d
    }

    fn sample() -> (CsrMatrix, CsrMatrix) {
        // A 4 x 4 nonsymmetric, P 4 x 2 linear interpolation
        let a = CsrMatrix::new(
            4,
            4,
            vec![0, 2, 5, 8, 10],
            vec![0, 1, 0, 1, 2, 1, 2, 3, 2, 3],
            vec![4.0, -1.0, -2.0, 4.0, -1.0, -1.0, 4.0, -3.0, -1.0, 4.0],
        )
        .unwrap();
        let p = CsrMatrix::new(
            4,
            2,
            vec![0, 1, 3, 5, 6],
            vec![0, 0, 1, 0, 1, 1],
            vec![1.0, 0.75, 0.25, 0.25, 0.75, 1.0],
        )
        .unwrap();
        (a, p)
    }

    #[test]
    fn galerkin_equals_the_dense_triple_product() {
        let (a, p) = sample();
        let c = a.galerkin(&p, &p.transpose());
        let (da, dp) = (dense(&a), dense(&p));
        for big_i in 0..2 {
            for big_j in 0..2 {
                let mut s = 0.0;
                for i in 0..4 {
                    for j in 0..4 {
                        s += dp[i][big_i] * da[i][j] * dp[j][big_j];
                    }
                }
                assert!((dense(&c)[big_i][big_j] - s).abs() < 1e-14);
            }
        }
    }

    #[test]
    fn transpose_and_pattern_round_trip() {
        let (a, _) = sample();
        assert_eq!(a.transpose().transpose(), a);
        let (pattern, values) = a.to_pattern();
        assert_eq!(CsrMatrix::from_pattern(&pattern, &values).unwrap(), a);
        let x = [1.0, 2.0, 3.0, 4.0];
        let (mut y, mut z) = ([0.0; 4], [0.0; 4]);
        a.mul_vec(&x, &mut y);
        pattern.matvec(&values, &x, &mut z);
        assert_eq!(y, z);
        assert_eq!(a.diagonal(), vec![4.0; 4]);
    }

    #[test]
    fn new_rejects_unsorted_columns() {
        assert!(CsrMatrix::new(1, 2, vec![0, 2], vec![1, 0], vec![1.0, 1.0]).is_err());
        assert!(CsrMatrix::new(1, 2, vec![0, 1], vec![2], vec![1.0]).is_err());
    }
}
