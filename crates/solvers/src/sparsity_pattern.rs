//! Compressed-sparse-column pattern, built once and filled with new values many times.

use crate::error::SolverError;
use crate::scalar::{SolverScalar, norm2};

/// The nonzero structure of a sparse matrix in compressed sparse column (CSC) form.
///
/// Column `j` owns the slots `col_ptr[j]..col_ptr[j + 1]`; `row_idx[slot]` is the row of that
/// slot, strictly increasing within a column (sorted, no duplicates). Values are not stored
/// here: a caller keeps a `values: Vec<F>` of length [`SparsityPattern::nnz`] and refills it,
/// so one pattern (and one symbolic factorisation) serves every Newton step.
///
/// # Math
/// ```text
/// A[row_idx[s], j] = values[s]    for col_ptr[j] <= s < col_ptr[j + 1]
/// ```
///
/// # Example
/// ```
/// use capstan_solvers::SparsityPattern;
/// // 2 x 2 matrix [[2, 1], [0, 3]] assembled from three contributions, one duplicated
/// let entries = [(0, 0), (1, 1), (0, 1), (0, 0)];
/// let (pattern, slots) = SparsityPattern::from_entries(2, 2, &entries).unwrap();
/// assert_eq!(pattern.nnz(), 3);
/// assert_eq!(slots[0], slots[3]); // the duplicate shares a slot
/// let mut values = vec![0.0; pattern.nnz()];
/// for (k, v) in [1.0, 3.0, 1.0, 1.0].into_iter().enumerate() {
///     values[slots[k]] += v;
/// }
/// let mut y = [0.0; 2];
/// pattern.matvec(&values, &[1.0, 1.0], &mut y);
/// assert_eq!(y, [3.0, 3.0]);
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SparsityPattern {
    nrows: usize,
    ncols: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
}

impl SparsityPattern {
    /// Builds the pattern of an `nrows x ncols` matrix from `(row, col)` entries, and returns
    /// with it, for every input entry `k`, its slot in the CSC value array.
    ///
    /// Entries may come in any order and repeat; repeated entries share a slot, so assembly is
    /// `values[slots[k]] += contribution[k]`. Cost `O(m + nrows + ncols)` for `m` entries (two
    /// counting sorts).
    ///
    /// # Errors
    /// [`SolverError::EntryOutOfBounds`] if an entry lies outside the matrix.
    pub fn from_entries(
        nrows: usize,
        ncols: usize,
        entries: &[(usize, usize)],
    ) -> Result<(Self, Vec<usize>), SolverError> {
        if let Some(&(row, col)) = entries.iter().find(|&&(r, c)| r >= nrows || c >= ncols) {
            return Err(SolverError::EntryOutOfBounds {
                row,
                col,
                nrows,
                ncols,
            });
        }
        // Entry indices sorted by (col, row), duplicates neighbours: a counting sort by row
        // (skipped when the entries already come row by row, as a row-wise assembly lists
        // them), then a stable one by column.
        let mut order = vec![0usize; entries.len()];
        {
            let mut start = vec![0usize; ncols + 1];
            for &(_, c) in entries {
                start[c + 1] += 1;
            }
            for j in 0..ncols {
                start[j + 1] += start[j];
            }
            let mut place = |k: usize| {
                let c = entries[k].1;
                order[start[c]] = k;
                start[c] += 1;
            };
            if entries.windows(2).all(|w| w[0].0 <= w[1].0) {
                (0..entries.len()).for_each(&mut place);
            } else {
                let mut by_row = vec![0usize; entries.len()];
                let mut row_start = vec![0usize; nrows + 1];
                for &(r, _) in entries {
                    row_start[r + 1] += 1;
                }
                for i in 0..nrows {
                    row_start[i + 1] += row_start[i];
                }
                for (k, &(r, _)) in entries.iter().enumerate() {
                    by_row[row_start[r]] = k;
                    row_start[r] += 1;
                }
                by_row.into_iter().for_each(place);
            }
        }
        let mut col_ptr = vec![0usize; ncols + 1];
        let mut row_idx = Vec::with_capacity(entries.len());
        let mut slots = vec![0usize; entries.len()];
        let mut last: Option<(usize, usize)> = None;
        for &k in &order {
            let (r, c) = entries[k];
            if last != Some((r, c)) {
                row_idx.push(r);
                col_ptr[c + 1] += 1;
                last = Some((r, c));
            }
            slots[k] = row_idx.len() - 1;
        }
        for j in 0..ncols {
            col_ptr[j + 1] += col_ptr[j];
        }
        Ok((
            Self {
                nrows,
                ncols,
                col_ptr,
                row_idx,
            },
            slots,
        ))
    }

    /// This pattern grown to `nrows x ncols` (at least its own size) with the `extra` entries
    /// `(row, col)` (any order, repeats and entries already present allowed): the pattern
    /// [`SparsityPattern::from_entries`] builds from `self.entries()` followed by `extra`,
    /// with the same slots, but by merging the few extra entries into the columns instead of
    /// sorting every entry again. Returns `(pattern, own_slots, extra_slots)`: the new slot of
    /// every slot of `self`, and of every extra entry.
    ///
    /// # Math
    /// Column `c` of the result is the sorted union of the rows of column `c` of `self` and the
    /// rows of the extra entries in column `c`; cost `O(nnz + ncols + e log e)` for `e` extra
    /// entries.
    ///
    /// # Errors
    /// [`SolverError::EntryOutOfBounds`] if an extra entry lies outside `nrows x ncols`;
    /// [`SolverError::InvalidParameter`] (field `nrows` or `ncols`) if the size is smaller
    /// than this pattern's.
    ///
    /// # Example
    /// ```
    /// use capstan_solvers::SparsityPattern;
    /// let (a, _) = SparsityPattern::from_entries(2, 2, &[(0, 0), (1, 1)]).unwrap();
    /// let (b, own, extra) = a.with_entries(3, 3, &[(2, 0), (0, 0), (2, 2)]).unwrap();
    /// assert_eq!(b.nnz(), 4);
    /// assert_eq!(own, vec![0, 2]);
    /// assert_eq!(extra, vec![1, 0, 3]); // an entry already present shares its slot
    /// ```
    pub fn with_entries(
        &self,
        nrows: usize,
        ncols: usize,
        extra: &[(usize, usize)],
    ) -> Result<(Self, Vec<usize>, Vec<usize>), SolverError> {
        for (field, size, own) in [("nrows", nrows, self.nrows), ("ncols", ncols, self.ncols)] {
            if size < own {
                return Err(SolverError::InvalidParameter {
                    field,
                    value: size as f64,
                    allowed: "at least the pattern's own size",
                });
            }
        }
        if let Some(&(row, col)) = extra.iter().find(|&&(r, c)| r >= nrows || c >= ncols) {
            return Err(SolverError::EntryOutOfBounds {
                row,
                col,
                nrows,
                ncols,
            });
        }
        // extra entry indices by (col, row), repeats neighbours (stable: the first one leads)
        let mut order: Vec<usize> = (0..extra.len()).collect();
        order.sort_by_key(|&k| (extra[k].1, extra[k].0));
        let mut col_ptr = Vec::with_capacity(ncols + 1);
        col_ptr.push(0);
        let mut row_idx = Vec::with_capacity(self.nnz() + extra.len());
        let mut own_slots = vec![0usize; self.nnz()];
        let mut extra_slots = vec![0usize; extra.len()];
        let mut next = 0; // position in `order`
        for c in 0..ncols {
            let (start, end) = if c < self.ncols {
                (self.col_ptr[c], self.col_ptr[c + 1])
            } else {
                (0, 0)
            };
            let mut s = start;
            loop {
                let own = (s < end).then(|| self.row_idx[s]);
                let more =
                    (next < order.len() && extra[order[next]].1 == c).then(|| extra[order[next]].0);
                let take_own = match (own, more) {
                    (None, None) => break,
                    (Some(r), Some(e)) => r <= e,
                    (own, _) => own.is_some(),
                };
                if take_own {
                    own_slots[s] = row_idx.len();
                    row_idx.push(self.row_idx[s]);
                    s += 1;
                } else {
                    let r = extra[order[next]].0;
                    // a repeat of the last row placed (own or extra) shares its slot
                    if row_idx.len() == col_ptr[c] || row_idx[row_idx.len() - 1] != r {
                        row_idx.push(r);
                    }
                    extra_slots[order[next]] = row_idx.len() - 1;
                    next += 1;
                }
            }
            col_ptr.push(row_idx.len());
        }
        Ok((
            Self {
                nrows,
                ncols,
                col_ptr,
                row_idx,
            },
            own_slots,
            extra_slots,
        ))
    }

    /// The pattern with the given compressed-column arrays: `col_ptr` of length `ncols + 1`
    /// from 0, non-decreasing, and in each column strictly increasing rows below `nrows` (the
    /// slot order of [`SparsityPattern::from_entries`], without its sort). Cost `O(nnz)`.
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] (field `col_ptr` or `row_idx`) for arrays that break
    /// these rules.
    ///
    /// # Example
    /// ```
    /// use capstan_solvers::SparsityPattern;
    /// let p = SparsityPattern::from_compressed_columns(2, 2, vec![0, 2, 3], vec![0, 1, 1]).unwrap();
    /// assert_eq!(p.slot(1, 0), Some(1));
    /// assert!(SparsityPattern::from_compressed_columns(2, 2, vec![0, 2, 3], vec![1, 0, 1]).is_err());
    /// ```
    pub fn from_compressed_columns(
        nrows: usize,
        ncols: usize,
        col_ptr: Vec<usize>,
        row_idx: Vec<usize>,
    ) -> Result<Self, SolverError> {
        let bad = |field: &'static str, value: usize, allowed: &'static str| {
            Err(SolverError::invalid(field, value as f64, allowed))
        };
        if col_ptr.len() != ncols + 1 || col_ptr[0] != 0 || col_ptr[ncols] != row_idx.len() {
            return bad("col_ptr", col_ptr.len(), "ncols + 1 pointers from 0 to nnz");
        }
        for j in 0..ncols {
            if col_ptr[j] > col_ptr[j + 1] {
                return bad("col_ptr", j, "non-decreasing");
            }
            let rows = &row_idx[col_ptr[j]..col_ptr[j + 1]];
            if rows.windows(2).any(|w| w[0] >= w[1]) || rows.last().is_some_and(|&r| r >= nrows) {
                return bad(
                    "row_idx",
                    j,
                    "strictly increasing rows below nrows in each column",
                );
            }
        }
        Ok(Self {
            nrows,
            ncols,
            col_ptr,
            row_idx,
        })
    }

    /// Pattern and summed values of an `sprs` matrix (CSC or CSR, duplicates allowed).
    ///
    /// # Errors
    /// None in practice (an `sprs` matrix is in bounds); the signature mirrors
    /// [`SparsityPattern::from_entries`].
    pub fn from_sprs<F: SolverScalar>(
        matrix: &sprs::CsMat<F>,
    ) -> Result<(Self, Vec<F>), SolverError> {
        let mut entries = Vec::with_capacity(matrix.nnz());
        let mut contributions = Vec::with_capacity(matrix.nnz());
        for (v, (r, c)) in matrix.iter() {
            entries.push((r, c));
            contributions.push(*v);
        }
        let (pattern, slots) = Self::from_entries(matrix.rows(), matrix.cols(), &entries)?;
        let mut values = vec![F::zero(); pattern.nnz()];
        for (k, v) in contributions.into_iter().enumerate() {
            values[slots[k]] = values[slots[k]] + v;
        }
        Ok((pattern, values))
    }

    /// Number of rows.
    pub fn nrows(&self) -> usize {
        self.nrows
    }

    /// Number of columns.
    pub fn ncols(&self) -> usize {
        self.ncols
    }

    /// Number of stored entries (length of a value array).
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Whether the matrix is square.
    pub fn is_square(&self) -> bool {
        self.nrows == self.ncols
    }

    /// Column pointers, length `ncols + 1`.
    pub fn col_ptr(&self) -> &[usize] {
        &self.col_ptr
    }

    /// Row index of each slot, sorted within each column.
    pub fn row_idx(&self) -> &[usize] {
        &self.row_idx
    }

    /// `(row, col)` of every slot, in slot order (column by column, rows ascending), so
    /// `pattern.entries().enumerate()` yields `(slot, (row, col))`.
    pub fn entries(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        (0..self.ncols).flat_map(move |j| self.column_rows(j).iter().map(move |&i| (i, j)))
    }

    /// Rows of column `col` (sorted).
    ///
    /// # Panics
    /// If `col >= ncols` (programmer error).
    #[track_caller]
    pub fn column_rows(&self, col: usize) -> &[usize] {
        &self.row_idx[self.col_ptr[col]..self.col_ptr[col + 1]]
    }

    /// Slot of entry `(row, col)`, or `None` if it is not in the pattern (binary search).
    pub fn slot(&self, row: usize, col: usize) -> Option<usize> {
        if col >= self.ncols {
            return None;
        }
        let start = self.col_ptr[col];
        self.column_rows(col)
            .binary_search(&row)
            .ok()
            .map(|k| start + k)
    }

    /// Slot of each diagonal entry `(i, i)`, `i < min(nrows, ncols)`; `None` where the diagonal
    /// is structurally zero.
    pub fn diagonal_slots(&self) -> Vec<Option<usize>> {
        (0..self.nrows.min(self.ncols))
            .map(|i| self.slot(i, i))
            .collect()
    }

    /// `y = A x`.
    ///
    /// # Math
    /// ```text
    /// y_i = sum_j A_ij x_j,  accumulated column by column (no transpose needed)
    /// ```
    ///
    /// # Panics
    /// If `values.len() != nnz`, `x.len() != ncols` or `y.len() != nrows` (programmer error).
    #[track_caller]
    pub fn matvec<F: SolverScalar>(&self, values: &[F], x: &[F], y: &mut [F]) {
        self.assert_lengths(values, x, y.len());
        y.iter_mut().for_each(|v| *v = F::zero());
        for (j, &xj) in x.iter().enumerate() {
            for s in self.col_ptr[j]..self.col_ptr[j + 1] {
                y[self.row_idx[s]] = y[self.row_idx[s]] + values[s] * xj;
            }
        }
    }

    /// `r = b - A x`, written into `r`.
    ///
    /// # Panics
    /// If a length does not match the pattern (programmer error).
    #[track_caller]
    pub fn residual_into<F: SolverScalar>(&self, values: &[F], x: &[F], b: &[F], r: &mut [F]) {
        self.assert_lengths(values, x, r.len());
        assert_eq!(b.len(), self.nrows, "`b` must have nrows entries");
        r.copy_from_slice(b);
        for (j, &xj) in x.iter().enumerate() {
            for s in self.col_ptr[j]..self.col_ptr[j + 1] {
                r[self.row_idx[s]] = r[self.row_idx[s]] - values[s] * xj;
            }
        }
    }

    /// `|b - A x|_2`, computed from the CSC columns (no transpose) with one scratch vector.
    ///
    /// # Panics
    /// If a length does not match the pattern (programmer error).
    #[track_caller]
    pub fn residual_norm<F: SolverScalar>(&self, values: &[F], x: &[F], b: &[F]) -> F {
        let mut r = vec![F::zero(); self.nrows];
        self.residual_into(values, x, b, &mut r);
        norm2(&r)
    }

    /// The row-compressed (transposed) layout: `(row_ptr, col_idx, slot)`, where row `i` owns
    /// positions `row_ptr[i]..row_ptr[i + 1]`, sorted by column, and `slot[p]` is the CSC slot
    /// holding that entry's value.
    pub fn row_layout(&self) -> (Vec<usize>, Vec<usize>, Vec<usize>) {
        let mut row_ptr = vec![0usize; self.nrows + 1];
        for &r in &self.row_idx {
            row_ptr[r + 1] += 1;
        }
        for i in 0..self.nrows {
            row_ptr[i + 1] += row_ptr[i];
        }
        let mut next = row_ptr.clone();
        let mut col_idx = vec![0usize; self.nnz()];
        let mut slot = vec![0usize; self.nnz()];
        // Columns are visited in increasing order, so each row comes out sorted by column.
        for j in 0..self.ncols {
            for s in self.col_ptr[j]..self.col_ptr[j + 1] {
                let p = next[self.row_idx[s]];
                col_idx[p] = j;
                slot[p] = s;
                next[self.row_idx[s]] += 1;
            }
        }
        (row_ptr, col_idx, slot)
    }

    /// The symbolic faer view of this pattern.
    pub fn as_faer_symbolic(&self) -> faer::sparse::SymbolicSparseColMatRef<'_, usize> {
        // `new_checked` re-validates the invariants in O(nnz): negligible next to a factorisation.
        faer::sparse::SymbolicSparseColMatRef::new_checked(
            self.nrows,
            self.ncols,
            &self.col_ptr,
            None,
            &self.row_idx,
        )
    }

    /// A faer sparse matrix view of `values` on this pattern.
    ///
    /// # Panics
    /// If `values.len() != nnz` (programmer error).
    #[track_caller]
    pub fn as_faer<'a, T>(
        &'a self,
        values: &'a [T],
    ) -> faer::sparse::SparseColMatRef<'a, usize, T> {
        assert_eq!(values.len(), self.nnz(), "`values` must have nnz entries");
        faer::sparse::SparseColMatRef::new(self.as_faer_symbolic(), values)
    }

    /// An owned `sprs` CSC matrix with a copy of `values`, for interoperability
    /// (Matrix Market output, other solvers).
    ///
    /// # Panics
    /// If `values.len() != nnz` (programmer error).
    #[track_caller]
    pub fn to_sprs<T: Clone>(&self, values: &[T]) -> sprs::CsMat<T> {
        assert_eq!(values.len(), self.nnz(), "`values` must have nnz entries");
        sprs::CsMat::new_csc(
            (self.nrows, self.ncols),
            self.col_ptr.clone(),
            self.row_idx.clone(),
            values.to_vec(),
        )
    }

    /// Checks the length of a value array against the pattern.
    pub(crate) fn check_values_len(&self, len: usize) -> Result<(), SolverError> {
        if len != self.nnz() {
            return Err(SolverError::DimensionMismatch {
                quantity: "values",
                expected: self.nnz(),
                found: len,
            });
        }
        Ok(())
    }

    #[track_caller]
    fn assert_lengths<F>(&self, values: &[F], x: &[F], out_len: usize) {
        assert_eq!(values.len(), self.nnz(), "`values` must have nnz entries");
        assert_eq!(x.len(), self.ncols, "`x` must have ncols entries");
        assert_eq!(out_len, self.nrows, "output must have nrows entries");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn from_entries_sorts_rows_and_merges_duplicates() {
        let entries = [(2, 0), (0, 0), (2, 0), (1, 2), (0, 2)];
        let (p, slots) = SparsityPattern::from_entries(3, 3, &entries).unwrap();
        assert_eq!(p.col_ptr(), &[0, 2, 2, 4]);
        assert_eq!(p.row_idx(), &[0, 2, 0, 1]);
        assert_eq!(slots, vec![1, 0, 1, 3, 2]);
    }

    /// Entries already row by row (columns unsorted, duplicates) skip the row pass: the same
    /// pattern as the shuffled list above, and slots by entry.
    #[test]
    fn from_entries_row_sorted_fast_path_matches() {
        let entries = [(0, 2), (0, 0), (1, 2), (2, 0), (2, 0)];
        let (p, slots) = SparsityPattern::from_entries(3, 3, &entries).unwrap();
        assert_eq!(p.col_ptr(), &[0, 2, 2, 4]);
        assert_eq!(p.row_idx(), &[0, 2, 0, 1]);
        assert_eq!(slots, vec![2, 0, 3, 1, 1]);
    }

    #[test]
    fn with_entries_matches_from_entries_on_all_the_entries() {
        // a pseudo-random 9 x 9 pattern, then extras that repeat, overlap it and grow it
        let mut seed = 12345u64;
        let mut next = |m: usize| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 33) as usize) % m
        };
        for _ in 0..20 {
            let own: Vec<(usize, usize)> = (0..30).map(|_| (next(9), next(9))).collect();
            let (a, _) = SparsityPattern::from_entries(9, 9, &own).unwrap();
            for (nrows, ncols) in [(9, 9), (12, 9), (12, 12)] {
                let extra: Vec<(usize, usize)> =
                    (0..25).map(|_| (next(nrows), next(ncols))).collect();
                let all: Vec<(usize, usize)> = a.entries().chain(extra.iter().copied()).collect();
                let (reference, slots) = SparsityPattern::from_entries(nrows, ncols, &all).unwrap();
                let (b, own_slots, extra_slots) = a.with_entries(nrows, ncols, &extra).unwrap();
                assert_eq!(b, reference);
                assert_eq!(own_slots, slots[..a.nnz()]);
                assert_eq!(extra_slots, slots[a.nnz()..]);
            }
        }
        let (a, _) = SparsityPattern::from_entries(2, 2, &[(0, 0)]).unwrap();
        assert!(matches!(
            a.with_entries(2, 2, &[(2, 0)]),
            Err(SolverError::EntryOutOfBounds { row: 2, .. })
        ));
        assert!(matches!(
            a.with_entries(1, 2, &[]),
            Err(SolverError::InvalidParameter { field: "nrows", .. })
        ));
    }

    #[test]
    fn from_entries_rejects_out_of_bounds() {
        let err = SparsityPattern::from_entries(2, 2, &[(0, 0), (2, 1)]).unwrap_err();
        assert!(matches!(
            err,
            SolverError::EntryOutOfBounds { row: 2, col: 1, .. }
        ));
    }

    #[test]
    fn empty_and_rectangular_patterns_work() {
        let (p, s) = SparsityPattern::from_entries(0, 0, &[]).unwrap();
        assert_eq!((p.nnz(), p.col_ptr(), s.len()), (0, &[0usize][..], 0));
        let (p, _) = SparsityPattern::from_entries(2, 3, &[(1, 2), (0, 0)]).unwrap();
        let mut y = [0.0; 2];
        p.matvec(&[1.0, 5.0], &[1.0, 1.0, 2.0], &mut y);
        assert_eq!(y, [1.0, 10.0]);
        assert!(!p.is_square());
    }

    #[test]
    fn slot_and_diagonal_lookup() {
        let (p, _) = SparsityPattern::from_entries(3, 3, &[(0, 0), (2, 2), (1, 2)]).unwrap();
        assert_eq!(p.slot(1, 2), Some(1));
        assert_eq!(p.slot(1, 1), None);
        assert_eq!(p.slot(0, 7), None);
        assert_eq!(p.diagonal_slots(), vec![Some(0), None, Some(2)]);
        let all: Vec<_> = p.entries().collect();
        assert_eq!(all, vec![(0, 0), (1, 2), (2, 2)]);
    }

    #[test]
    fn row_layout_is_the_transpose() {
        let entries = [(0, 0), (1, 0), (0, 1), (2, 1), (1, 2), (2, 2)];
        let (p, _) = SparsityPattern::from_entries(3, 3, &entries).unwrap();
        let (row_ptr, col_idx, slot) = p.row_layout();
        assert_eq!(row_ptr, vec![0, 2, 4, 6]);
        assert_eq!(col_idx, vec![0, 1, 0, 2, 1, 2]);
        for i in 0..3 {
            for q in row_ptr[i]..row_ptr[i + 1] {
                assert_eq!(p.slot(i, col_idx[q]), Some(slot[q]));
            }
        }
    }

    #[test]
    fn residual_norm_matches_matvec() {
        let (p, _) = SparsityPattern::from_entries(2, 2, &[(0, 0), (1, 0), (1, 1)]).unwrap();
        let values = [2.0, 1.0, 4.0];
        let x = [1.0, 1.0];
        let b = [5.0, 1.0];
        // A x = [2, 5], b - A x = [3, -4]
        assert_eq!(p.residual_norm(&values, &x, &b), 5.0);
    }

    #[test]
    fn faer_and_sprs_views_agree() {
        let (p, _) = SparsityPattern::from_entries(2, 2, &[(0, 0), (1, 0), (1, 1)]).unwrap();
        let values = [2.0, 1.0, 4.0];
        let f = p.as_faer(&values);
        assert_eq!(f.compute_nnz(), 3);
        let s = p.to_sprs(&values);
        assert_eq!(s.get(1, 0), Some(&1.0));
        assert!(s.is_csc());
        let (q, v) = SparsityPattern::from_sprs(&s).unwrap();
        assert_eq!((q, v), (p, values.to_vec()));
    }

    #[test]
    fn check_values_len_reports_mismatch() {
        let (p, _) = SparsityPattern::from_entries(1, 1, &[(0, 0)]).unwrap();
        assert!(matches!(
            p.check_values_len(2),
            Err(SolverError::DimensionMismatch {
                expected: 1,
                found: 2,
                ..
            })
        ));
    }
}
