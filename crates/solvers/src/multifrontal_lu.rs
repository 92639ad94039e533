//! Multifrontal LU on the symmetric structure of `A + A^T`: the kernel behind
//! [`crate::LuKind::Multifrontal`].
//!
//! # Math
//! ```text
//! A' = Q^T A Q                      Q: fill-reducing order of A + A^T (symmetric)
//! C^T C = A' + A'^T  (symbolic)     supernodes s = columns [b_s, e_s), off-block rows R_s
//! front F_s = [F11 F12; F21 F22]    rows and columns [b_s, e_s) u R_s, dense:
//!     F_s = A'(front) + sum over children c of the contribution blocks CB_c (extend-add)
//! P_s F11 = L11 U11                 pivots only from the block rows [b_s, e_s), accepted if
//!     |pivot| >= 0.01 max |column k of [F11; F21]|      (threshold partial pivoting)
//! L21 = F21 U11^-1,  U12 = L11^-1 P_s F12,  CB_s = F22 - L21 U12  -> parent of s
//! ```
//! Row swaps never leave a front's block, so `struct(L + U)` stays within `struct(C + C^T)`:
//! the factor storage is exact and allocated once per pattern. A pivot the threshold rejects
//! would need a row outside the block; the factorisation then stops with
//! [`FrontFailure::NeedsPivoting`] and [`crate::SparseLu`] falls back to faer's supernodal
//! kernel (structure of `A^T A`, any pivot row).
//!
//! # References
//! Duff and Reid, "The multifrontal solution of indefinite sparse symmetric linear equations",
//! ACM TOMS 9 (1983); Amestoy, Duff, Koster, L'Excellent, "A fully asynchronous multifrontal
//! solver using distributed dynamic scheduling", SIAM J. Matrix Anal. Appl. 23 (2001) (the
//! unsymmetric-values, symmetric-structure variant with threshold pivoting, as in MUMPS).

use faer::reborrow::{Reborrow, ReborrowMut};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, SymbolicCholeskyRaw, SymmetricOrdering, factorize_symbolic_cholesky,
};
use faer::{Accum, MatMut, Par};

use crate::error::SolverError;
use crate::sparsity_pattern::SparsityPattern;

/// Smallest accepted `|pivot| / max |entry of its column in the front|`.
pub(crate) const PIVOT_THRESHOLD: f64 = 0.01;

/// Fronts with fewer multiply-adds than this in their Schur update run sequentially.
const PARALLEL_FLOPS: usize = 1 << 20;

/// Why a multifrontal factorisation stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum FrontFailure {
    /// A column of the remaining Schur complement is entirely zero: `A` is singular. Carries
    /// the column in the caller's numbering.
    Singular(usize),
    /// A non-finite value reached a pivot column.
    NonFinite,
    /// No pivot in a front's block passes the threshold: rows outside it would be needed.
    NeedsPivoting,
}

/// The symbolic part, built once per pattern: order, supernodes, assembly lists.
#[derive(Debug)]
pub(crate) struct FrontalStructure {
    /// `perm_fwd[k]` = original index at position `k` (rows and columns alike).
    perm_fwd: Vec<usize>,
    perm_inv: Vec<usize>,
    /// Supernode `s` = positions `begin[s]..begin[s + 1]`.
    begin: Vec<usize>,
    /// Off-block rows `R_s` (positions, ascending): `rows[row_ptr[s]..row_ptr[s + 1]]`.
    row_ptr: Vec<usize>,
    rows: Vec<u32>,
    /// Children of `s` in the assembly tree: `children[child_ptr[s]..child_ptr[s + 1]]`.
    child_ptr: Vec<usize>,
    children: Vec<u32>,
    /// Factor storage of `s`: `val_ptr[s]..val_ptr[s + 1]` holds the `m x ns` panel
    /// `[L11 \ U11; L21]` (column-major, `m = ns + nr`), then `U12` (`ns x nr`, column-major).
    val_ptr: Vec<usize>,
    /// Entries of `A` assembled into front `s`: `(slot, column)` in
    /// `assembly[assembly_ptr[s]..assembly_ptr[s + 1]]`.
    assembly_ptr: Vec<usize>,
    assembly: Vec<(u32, u32)>,
    /// Largest front order `m`.
    max_front: usize,
}

/// The numeric part: factor values and the row swaps of each front's block.
#[derive(Debug, Default)]
pub(crate) struct FrontalFactors {
    values: Vec<f64>,
    /// Position `k` was swapped with position `swaps[k]` (LAPACK-style, within its block).
    swaps: Vec<u32>,
}

impl FrontalStructure {
    /// Analyses `pattern` (square) with the symmetric order `perm` (`perm[k]` = index placed
    /// `k`-th), or AMD on `A + A^T` for `None`. `Ok(None)` if an index does not fit in 32 bits.
    ///
    /// # Errors
    /// [`SolverError::Backend`] if faer's symbolic analysis fails (out of memory).
    pub(crate) fn analyse(
        pattern: &SparsityPattern,
        perm: Option<&[usize]>,
    ) -> Result<Option<Self>, SolverError> {
        let n = pattern.ncols();
        if n >= u32::MAX as usize || pattern.nnz() >= u32::MAX as usize {
            return Ok(None);
        }
        // lower triangle of the structure of A + A^T, without duplicates
        let col_ptr = pattern.col_ptr();
        let row_idx = pattern.row_idx();
        let mut lower_ptr = vec![0usize; n + 1];
        for j in 0..n {
            for &i in &row_idx[col_ptr[j]..col_ptr[j + 1]] {
                lower_ptr[i.min(j) + 1] += 1;
            }
        }
        for j in 0..n {
            lower_ptr[j + 1] += lower_ptr[j];
        }
        let mut next = lower_ptr.clone();
        let mut lower_idx = vec![0usize; pattern.nnz()];
        for j in 0..n {
            for &i in &row_idx[col_ptr[j]..col_ptr[j + 1]] {
                let c = i.min(j);
                lower_idx[next[c]] = i.max(j);
                next[c] += 1;
            }
        }
        drop(next);
        let mut write = 0;
        let mut start = 0;
        for j in 0..n {
            let column = &mut lower_idx[start..lower_ptr[j + 1]];
            column.sort_unstable();
            let mut last = usize::MAX;
            let mut kept = Vec::new();
            for &i in column.iter() {
                if i != last {
                    kept.push(i);
                    last = i;
                }
            }
            start = lower_ptr[j + 1];
            lower_ptr[j + 1] = write + kept.len();
            lower_idx[write..write + kept.len()].copy_from_slice(&kept);
            write += kept.len();
        }
        lower_idx.truncate(write);
        let lower =
            faer::sparse::SymbolicSparseColMatRef::new_checked(n, n, &lower_ptr, None, &lower_idx);
        let inverse = perm.map(|p| {
            let mut inv = vec![0usize; n];
            for (k, &j) in p.iter().enumerate() {
                inv[j] = k;
            }
            inv
        });
        let ordering = match (perm, &inverse) {
            (Some(p), Some(inv)) => {
                SymmetricOrdering::Custom(faer::perm::PermRef::new_checked(p, inv, n))
            }
            _ => SymmetricOrdering::Amd,
        };
        let symbolic = factorize_symbolic_cholesky(
            lower,
            faer::Side::Lower,
            ordering,
            CholeskySymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                ..Default::default()
            },
        )?;
        drop((lower_ptr, lower_idx));
        let (perm_fwd, perm_inv) = match symbolic.perm() {
            Some(p) => {
                let (fwd, inv) = p.arrays();
                (fwd.to_vec(), inv.to_vec())
            }
            None => ((0..n).collect(), (0..n).collect()),
        };
        let mut begin = Vec::new();
        let mut row_ptr = vec![0usize];
        let mut rows = Vec::new();
        match symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(supernodal) => {
                begin.extend_from_slice(supernodal.supernode_begin());
                for s in 0..supernodal.n_supernodes() {
                    rows.extend(supernodal.supernode(s).pattern().iter().map(|&i| i as u32));
                    row_ptr.push(rows.len());
                }
            }
            // faer keeps the simplicial structure when the flop ratio is not positive (no
            // off-diagonal entries at all): every column is then a front of its own
            SymbolicCholeskyRaw::Simplicial(simplicial) => {
                let (ptr, idx) = (simplicial.col_ptr(), simplicial.row_idx());
                for j in 0..n {
                    begin.push(j);
                    rows.extend(
                        idx[ptr[j]..ptr[j + 1]]
                            .iter()
                            .filter(|&&i| i > j)
                            .map(|&i| i as u32),
                    );
                    row_ptr.push(rows.len());
                }
            }
        }
        begin.push(n);
        let n_super = begin.len() - 1;
        drop(symbolic);

        let mut super_of = vec![0u32; n];
        for s in 0..n_super {
            super_of[begin[s]..begin[s + 1]].fill(s as u32);
        }
        // assembly tree: the parent of s owns the first (smallest) row of R_s
        let parent = |s: usize| {
            rows[row_ptr[s]..row_ptr[s + 1]]
                .iter()
                .min()
                .map(|&i| super_of[i as usize] as usize)
        };
        let mut child_count = vec![0usize; n_super + 1];
        for s in 0..n_super {
            if let Some(p) = parent(s) {
                child_count[p + 1] += 1;
            }
        }
        for s in 0..n_super {
            child_count[s + 1] += child_count[s];
        }
        let child_ptr = child_count;
        let mut next = child_ptr.clone();
        let mut children = vec![0u32; child_ptr[n_super]];
        for s in 0..n_super {
            if let Some(p) = parent(s) {
                children[next[p]] = s as u32;
                next[p] += 1;
            }
        }
        let mut val_ptr = Vec::with_capacity(n_super + 1);
        val_ptr.push(0usize);
        let mut max_front = 0;
        for s in 0..n_super {
            let ns = begin[s + 1] - begin[s];
            let nr = row_ptr[s + 1] - row_ptr[s];
            max_front = max_front.max(ns + nr);
            val_ptr.push(val_ptr[s] + (ns + nr) * ns + ns * nr);
        }
        // each entry of A goes to the front of its earlier position
        let mut assembly_ptr = vec![0usize; n_super + 1];
        for j in 0..n {
            for &i in &row_idx[col_ptr[j]..col_ptr[j + 1]] {
                let first = perm_inv[i].min(perm_inv[j]);
                assembly_ptr[super_of[first] as usize + 1] += 1;
            }
        }
        for s in 0..n_super {
            assembly_ptr[s + 1] += assembly_ptr[s];
        }
        let mut next = assembly_ptr.clone();
        let mut assembly = vec![(0u32, 0u32); pattern.nnz()];
        for j in 0..n {
            for slot in col_ptr[j]..col_ptr[j + 1] {
                let first = perm_inv[row_idx[slot]].min(perm_inv[j]);
                let s = super_of[first] as usize;
                assembly[next[s]] = (slot as u32, j as u32);
                next[s] += 1;
            }
        }
        Ok(Some(Self {
            perm_fwd,
            perm_inv,
            begin,
            row_ptr,
            rows,
            child_ptr,
            children,
            val_ptr,
            assembly_ptr,
            assembly,
            max_front,
        }))
    }

    /// The symmetric order (`perm[k]` = index placed `k`-th).
    pub(crate) fn permutation(&self) -> &[usize] {
        &self.perm_fwd
    }

    /// Number of values stored in the factors (`L` and `U`, the diagonal once).
    pub(crate) fn factor_entries(&self) -> usize {
        self.val_ptr.last().copied().unwrap_or(0)
    }

    fn n_supernodes(&self) -> usize {
        self.begin.len() - 1
    }

    fn off_block_rows(&self, s: usize) -> &[u32] {
        &self.rows[self.row_ptr[s]..self.row_ptr[s + 1]]
    }

    /// Numeric factorisation of `values` (in `pattern` order) into `factors`.
    pub(crate) fn factor(
        &self,
        pattern: &SparsityPattern,
        values: &[f64],
        factors: &mut FrontalFactors,
        par: Par,
    ) -> Result<(), FrontFailure> {
        let n = self.perm_fwd.len();
        let row_idx = pattern.row_idx();
        factors.values.clear();
        factors.values.resize(self.factor_entries(), 0.0);
        factors.swaps.clear();
        factors.swaps.resize(n, 0);
        let mut pos = vec![0u32; n];
        let mut front: Vec<f64> = Vec::with_capacity(self.max_front * self.max_front);
        let mut contributions: Vec<Option<Vec<f64>>> = vec![None; self.n_supernodes()];
        for s in 0..self.n_supernodes() {
            let (b, e) = (self.begin[s], self.begin[s + 1]);
            let ns = e - b;
            let r = self.off_block_rows(s);
            let nr = r.len();
            let m = ns + nr;
            for k in 0..ns {
                pos[b + k] = k as u32;
            }
            for (t, &i) in r.iter().enumerate() {
                pos[i as usize] = (ns + t) as u32;
            }
            front.clear();
            front.resize(m * m, 0.0);
            for &(slot, col) in &self.assembly[self.assembly_ptr[s]..self.assembly_ptr[s + 1]] {
                let slot = slot as usize;
                let i = pos[self.perm_inv[row_idx[slot]]] as usize;
                let j = pos[self.perm_inv[col as usize]] as usize;
                front[i + m * j] += values[slot];
            }
            for &c in &self.children[self.child_ptr[s]..self.child_ptr[s + 1]] {
                let c = c as usize;
                let rc = self.off_block_rows(c);
                let nc = rc.len();
                let cb = contributions[c].take().unwrap_or_default();
                debug_assert_eq!(cb.len(), nc * nc);
                for (bb, &jb) in rc.iter().enumerate() {
                    let col = m * pos[jb as usize] as usize;
                    for (a, &ia) in rc.iter().enumerate() {
                        front[col + pos[ia as usize] as usize] += cb[a + nc * bb];
                    }
                }
            }
            factor_panel(&mut front, m, ns, &mut factors.swaps[b..e], b, par).map_err(
                |failure| match failure {
                    FrontFailure::Singular(k) => FrontFailure::Singular(self.perm_fwd[b + k]),
                    other => other,
                },
            )?;
            if nr > 0 {
                let par = if nr * nr * ns >= PARALLEL_FLOPS {
                    par
                } else {
                    Par::Seq
                };
                let f = MatMut::from_column_major_slice_mut(&mut front, m, m);
                let (top, bottom) = f.split_at_row_mut(ns);
                let (l11, mut u12) = top.split_at_col_mut(ns);
                faer::linalg::triangular_solve::solve_unit_lower_triangular_in_place(
                    l11.rb(),
                    u12.rb_mut(),
                    par,
                );
                let (l21, f22) = bottom.split_at_col_mut(ns);
                faer::linalg::matmul::matmul(f22, Accum::Add, l21.rb(), u12.rb(), -1.0, par);
            }
            let out = &mut factors.values[self.val_ptr[s]..self.val_ptr[s + 1]];
            let (panel, u12) = out.split_at_mut(m * ns);
            panel.copy_from_slice(&front[..m * ns]);
            for t in 0..nr {
                let col = &front[m * (ns + t)..];
                u12[ns * t..ns * (t + 1)].copy_from_slice(&col[..ns]);
            }
            if nr > 0 {
                let mut cb = Vec::with_capacity(nr * nr);
                for t in 0..nr {
                    cb.extend_from_slice(&front[m * (ns + t) + ns..m * (ns + t + 1)]);
                }
                contributions[s] = Some(cb);
            }
        }
        Ok(())
    }

    /// Solves `A x = rhs` in place with the factors (no check, no refinement).
    pub(crate) fn solve_in_place(&self, factors: &FrontalFactors, rhs: &mut [f64], y: &mut [f64]) {
        let val = &factors.values;
        for (k, &p) in self.perm_fwd.iter().enumerate() {
            y[k] = rhs[p];
        }
        // forward: L y = P y
        for s in 0..self.n_supernodes() {
            let (b, e) = (self.begin[s], self.begin[s + 1]);
            let ns = e - b;
            let r = self.off_block_rows(s);
            let m = ns + r.len();
            for k in b..e {
                y.swap(k, factors.swaps[k] as usize);
            }
            let panel = &val[self.val_ptr[s]..self.val_ptr[s] + m * ns];
            for k in 0..ns {
                let yk = y[b + k];
                if yk == 0.0 {
                    continue;
                }
                let col = &panel[m * k..m * (k + 1)];
                for i in k + 1..ns {
                    y[b + i] -= col[i] * yk;
                }
                for (t, &i) in r.iter().enumerate() {
                    y[i as usize] -= col[ns + t] * yk;
                }
            }
        }
        // backward: U x = y
        for s in (0..self.n_supernodes()).rev() {
            let (b, e) = (self.begin[s], self.begin[s + 1]);
            let ns = e - b;
            let r = self.off_block_rows(s);
            let m = ns + r.len();
            let panel = &val[self.val_ptr[s]..self.val_ptr[s] + m * ns];
            let u12 = &val[self.val_ptr[s] + m * ns..self.val_ptr[s + 1]];
            for (t, &i) in r.iter().enumerate() {
                let yr = y[i as usize];
                if yr == 0.0 {
                    continue;
                }
                for (yk, u) in y[b..e].iter_mut().zip(&u12[ns * t..ns * (t + 1)]) {
                    *yk -= u * yr;
                }
            }
            for k in (0..ns).rev() {
                let col = &panel[m * k..m * (k + 1)];
                y[b + k] /= col[k];
                let yk = y[b + k];
                for i in 0..k {
                    y[b + i] -= col[i] * yk;
                }
            }
        }
        for (k, &p) in self.perm_fwd.iter().enumerate() {
            rhs[p] = y[k];
        }
    }
}

/// Columns solved together by [`FrontalStructure::solve_rows_in_place`]'s callers: a row of
/// the block is 512 bytes, and a front's rows then stay in cache between the triangular solve
/// and the off-block update.
pub(crate) const SOLVE_BLOCK_WIDTH: usize = 64;

/// Supernodes with fewer columns than this are solved column by column of `L` and `U` (one
/// `axpy` of a block row per entry); wider ones use faer's dense triangular solve and GEMM.
const DENSE_SOLVE_COLUMNS: usize = 8;

/// Scratch of the blocked solve, reused across calls.
#[derive(Debug, Default)]
pub(crate) struct BlockWork {
    /// The block in the symmetric order (row-major, `n x k`).
    permuted: Vec<f64>,
    /// Gathered off-block rows of one supernode (row-major, `nr x k`).
    gathered: Vec<f64>,
}

/// Row `i` of the row-major block `y` with `k` columns.
fn row(y: &[f64], i: usize, k: usize) -> &[f64] {
    &y[i * k..(i + 1) * k]
}

/// Row `i` of the row-major block `y` with `k` columns, mutably.
fn row_mut(y: &mut [f64], i: usize, k: usize) -> &mut [f64] {
    &mut y[i * k..(i + 1) * k]
}

/// `target -= a * source`, elementwise.
fn sub_scaled(target: &mut [f64], a: f64, source: &[f64]) {
    for (t, s) in target.iter_mut().zip(source) {
        *t -= a * s;
    }
}

impl FrontalStructure {
    /// Solves `A X = B` for the `k` columns of `x`, a row-major `n x k` block in the caller's
    /// numbering (row `i` = entries `i k .. (i + 1) k`), in place (no check, no refinement).
    ///
    /// # Math
    /// ```text
    /// Y = Q^T X                                   rows in the symmetric order
    /// forward, s = 0, 1, ..:   Y_s <- P_s Y_s      row swaps of the block rows [b_s, e_s)
    ///                          Y_s <- L11^-1 Y_s   (ns x k, unit lower)
    ///                          Y_R <- Y_R - L21 Y_s          gather/GEMM/scatter on R_s
    /// backward, s = .., 1, 0:  Y_s <- U11^-1 (Y_s - U12 Y_R)
    /// X = Q Y
    /// ```
    /// Each front's factors are read once per block instead of once per column.
    ///
    /// # Panics
    /// If `x.len() != n k` (programmer error).
    #[track_caller]
    pub(crate) fn solve_rows_in_place(
        &self,
        factors: &FrontalFactors,
        x: &mut [f64],
        k: usize,
        work: &mut BlockWork,
    ) {
        let n = self.perm_fwd.len();
        assert_eq!(x.len(), n * k, "`x` must hold n x k entries");
        if k == 0 {
            return;
        }
        let y = &mut work.permuted;
        y.clear();
        y.reserve(n * k);
        for &p in &self.perm_fwd {
            y.extend_from_slice(row(x, p, k));
        }
        let g = &mut work.gathered;
        g.clear();
        g.resize(self.max_front * k, 0.0);
        let val = &factors.values;
        for s in 0..self.n_supernodes() {
            let (b, e) = (self.begin[s], self.begin[s + 1]);
            let ns = e - b;
            let r = self.off_block_rows(s);
            let nr = r.len();
            let m = ns + nr;
            for i in b..e {
                let p = factors.swaps[i] as usize;
                if p != i {
                    let (head, tail) = y.split_at_mut(p * k);
                    row_mut(head, i, k).swap_with_slice(&mut tail[..k]);
                }
            }
            let panel = &val[self.val_ptr[s]..self.val_ptr[s] + m * ns];
            if ns < DENSE_SOLVE_COLUMNS {
                // column j of L: rows below j in the block, then R_s
                for j in 0..ns {
                    let col = &panel[m * j..m * (j + 1)];
                    let (head, tail) = y.split_at_mut((b + j + 1) * k);
                    let yj = row(head, b + j, k);
                    for (i, &l) in col[j + 1..ns].iter().enumerate() {
                        sub_scaled(row_mut(tail, i, k), l, yj);
                    }
                    for (t, &i) in r.iter().enumerate() {
                        // R_s lies after the block: i > b + j
                        sub_scaled(row_mut(tail, i as usize - (b + j + 1), k), col[ns + t], yj);
                    }
                }
            } else {
                let panel = faer::MatRef::from_column_major_slice(panel, m, ns);
                let (l11, l21) = panel.split_at_row(ns);
                let mut ys = MatMut::from_row_major_slice_mut(&mut y[b * k..e * k], ns, k);
                faer::linalg::triangular_solve::solve_unit_lower_triangular_in_place(
                    l11,
                    ys.rb_mut(),
                    Par::Seq,
                );
                if nr > 0 {
                    let gr = MatMut::from_row_major_slice_mut(&mut g[..nr * k], nr, k);
                    faer::linalg::matmul::matmul(gr, Accum::Replace, l21, ys.rb(), 1.0, Par::Seq);
                    for (t, &i) in r.iter().enumerate() {
                        sub_scaled(row_mut(y, i as usize, k), 1.0, row(g, t, k));
                    }
                }
            }
        }
        for s in (0..self.n_supernodes()).rev() {
            let (b, e) = (self.begin[s], self.begin[s + 1]);
            let ns = e - b;
            let r = self.off_block_rows(s);
            let nr = r.len();
            let m = ns + nr;
            let panel = &val[self.val_ptr[s]..self.val_ptr[s] + m * ns];
            let u12 = &val[self.val_ptr[s] + m * ns..self.val_ptr[s + 1]];
            if ns < DENSE_SOLVE_COLUMNS {
                let (head, tail) = y.split_at_mut(e * k);
                let ys = &mut head[b * k..];
                for (t, &i) in r.iter().enumerate() {
                    let yi = row(tail, i as usize - e, k);
                    for j in 0..ns {
                        sub_scaled(row_mut(ys, j, k), u12[ns * t + j], yi);
                    }
                }
                for j in (0..ns).rev() {
                    let col = &panel[m * j..m * (j + 1)];
                    let (above, rest) = ys.split_at_mut(j * k);
                    let yj = &mut rest[..k];
                    let pivot = col[j];
                    yj.iter_mut().for_each(|v| *v /= pivot);
                    for (i, &u) in col[..j].iter().enumerate() {
                        sub_scaled(row_mut(above, i, k), u, yj);
                    }
                }
            } else {
                for (t, &i) in r.iter().enumerate() {
                    row_mut(g, t, k).copy_from_slice(row(y, i as usize, k));
                }
                let panel = faer::MatRef::from_column_major_slice(panel, m, ns);
                let u11 = panel.split_at_row(ns).0;
                let mut ys = MatMut::from_row_major_slice_mut(&mut y[b * k..e * k], ns, k);
                if nr > 0 {
                    let u12 = faer::MatRef::from_column_major_slice(u12, ns, nr);
                    let gr = faer::MatRef::from_row_major_slice(&g[..nr * k], nr, k);
                    faer::linalg::matmul::matmul(ys.rb_mut(), Accum::Add, u12, gr, -1.0, Par::Seq);
                }
                faer::linalg::triangular_solve::solve_upper_triangular_in_place(
                    u11,
                    ys.rb_mut(),
                    Par::Seq,
                );
            }
        }
        for (i, &p) in self.perm_fwd.iter().enumerate() {
            row_mut(x, p, k).copy_from_slice(row(y, i, k));
        }
    }
}

/// Columns per block of [`factor_panel`]: within a block the LU is right-looking by rank-1
/// updates; the rest of the panel is updated per block by a triangular solve and a matrix
/// product (most of the work of wide supernodes, at matrix-product speed).
const PANEL_BLOCK: usize = 32;

/// Right-looking LU of the first `ns` columns of the `m x m` column-major `front`, pivots from
/// rows `0..ns` only; the trailing columns get only the row swaps. `swaps[k]` receives
/// `offset + ` the row swapped with `k`.
///
/// # Math
/// Blocked by [`PANEL_BLOCK`] columns `[kb, ke)`: factor them (rows `kb..m`) by rank-1
/// updates, then `U[kb..ke, ke..ns] = L[kb..ke, kb..ke]^-1 F[kb..ke, ke..ns]` and
/// `F[ke..m, ke..ns] -= L[ke..m, kb..ke] U[kb..ke, ke..ns]`. Every column sees the same
/// updates as in the unblocked order before its pivot is chosen, so the pivots agree.
fn factor_panel(
    front: &mut [f64],
    m: usize,
    ns: usize,
    swaps: &mut [u32],
    offset: usize,
    par: Par,
) -> Result<(), FrontFailure> {
    factor_panel_blocked(front, m, ns, swaps, offset, PANEL_BLOCK, par)
}

/// [`factor_panel`] with blocks of `nb` columns (`nb >= ns`: unblocked).
fn factor_panel_blocked(
    front: &mut [f64],
    m: usize,
    ns: usize,
    swaps: &mut [u32],
    offset: usize,
    nb: usize,
    par: Par,
) -> Result<(), FrontFailure> {
    let nb = nb.max(1);
    for kb in (0..ns).step_by(nb) {
        let ke = (kb + nb).min(ns);
        factor_columns(front, m, ns, kb..ke, swaps, offset)?;
        if ke == ns {
            break;
        }
        let par = if (m - ke) * (ns - ke) * (ke - kb) >= PARALLEL_FLOPS {
            par
        } else {
            Par::Seq
        };
        let f = MatMut::from_column_major_slice_mut(front, m, m);
        let (left, right) = f.split_at_col_mut(ke);
        let block = left.rb().subcols(kb, ke - kb);
        let right = right.subcols_mut(0, ns - ke);
        let (top, bottom) = right.split_at_row_mut(ke);
        let mut u = top.subrows_mut(kb, ke - kb);
        faer::linalg::triangular_solve::solve_unit_lower_triangular_in_place(
            block.subrows(kb, ke - kb),
            u.rb_mut(),
            par,
        );
        faer::linalg::matmul::matmul(
            bottom,
            Accum::Add,
            block.subrows(ke, m - ke),
            u.rb(),
            -1.0,
            par,
        );
    }
    Ok(())
}

/// The unblocked step of [`factor_panel_blocked`]: columns `cols` (within `0..ns`), whose
/// updates from the columns before them are done; rank-1 updates reach only `cols`.
fn factor_columns(
    front: &mut [f64],
    m: usize,
    ns: usize,
    cols: core::ops::Range<usize>,
    swaps: &mut [u32],
    offset: usize,
) -> Result<(), FrontFailure> {
    let end = cols.end;
    for k in cols {
        let col = &front[m * k..m * (k + 1)];
        if col[k..].iter().any(|v| !v.is_finite()) {
            return Err(FrontFailure::NonFinite);
        }
        let (mut pivot_row, mut p) = (k, 0.0f64);
        for (i, v) in col[..ns].iter().enumerate().skip(k) {
            if v.abs() > p {
                p = v.abs();
                pivot_row = i;
            }
        }
        let q = col[ns..].iter().fold(0.0f64, |q, v| q.max(v.abs()));
        if p == 0.0 && q == 0.0 {
            return Err(FrontFailure::Singular(k));
        }
        if p < PIVOT_THRESHOLD * q {
            return Err(FrontFailure::NeedsPivoting);
        }
        swaps[k] = (offset + pivot_row) as u32;
        if pivot_row != k {
            for c in 0..m {
                front.swap(k + m * c, pivot_row + m * c);
            }
        }
        let (left, right) = front.split_at_mut(m * (k + 1));
        let col = &mut left[m * k..];
        let inverse = 1.0 / col[k];
        for v in &mut col[k + 1..] {
            *v *= inverse;
        }
        for c in 0..end - k - 1 {
            let target = &mut right[m * c..m * (c + 1)];
            let u = target[k];
            if u == 0.0 {
                continue;
            }
            for (t, l) in target[k + 1..].iter_mut().zip(&col[k + 1..]) {
                *t -= l * u;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::samples::{
        ConvectionDiffusion2d, LinearSystem, Poisson2d, RandomDiagonallyDominant, SplitMix64,
    };

    /// Random sparse matrix whose diagonal is `diagonal` times smaller than its other entries:
    /// the smaller, the more row swaps inside the fronts (and the more fronts without an
    /// acceptable pivot).
    fn random_general(n: usize, per_row: usize, diagonal: f64, seed: u64) -> LinearSystem {
        let mut rng = SplitMix64(seed);
        let mut t = Vec::new();
        for i in 0..n {
            t.push((i, i, diagonal * rng.uniform()));
            for _ in 0..per_row {
                let j = (rng.next_u64() % n as u64) as usize;
                t.push((i, j, rng.uniform()));
            }
            t.push((i, (i + 1) % n, 1.0 + rng.uniform()));
        }
        LinearSystem::from_triplets(n, &t, vec![0.0; n])
    }

    /// Largest `|a - b|` relative to the largest `|b|`.
    fn relative_difference(a: &[f64], b: &[f64]) -> f64 {
        let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let diff = a
            .iter()
            .zip(b)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        diff / scale
    }

    /// Solves `k` dense random right-hand sides by the blocked kernel and one by one by the
    /// scalar kernel; returns the largest relative difference over the columns.
    fn blocked_against_scalar(
        structure: &FrontalStructure,
        factors: &FrontalFactors,
        n: usize,
        k: usize,
        seed: u64,
    ) -> f64 {
        let mut rng = SplitMix64(seed);
        let columns: Vec<Vec<f64>> = (0..k)
            .map(|_| (0..n).map(|_| rng.uniform()).collect())
            .collect();
        let mut block = vec![0.0; n * k];
        for (c, col) in columns.iter().enumerate() {
            for (i, v) in col.iter().enumerate() {
                block[i * k + c] = *v;
            }
        }
        structure.solve_rows_in_place(factors, &mut block, k, &mut BlockWork::default());
        let mut y = vec![0.0; n];
        let mut worst = 0.0f64;
        for (c, col) in columns.into_iter().enumerate() {
            let mut x = col;
            structure.solve_in_place(factors, &mut x, &mut y);
            let blocked: Vec<f64> = (0..n).map(|i| block[i * k + c]).collect();
            worst = worst.max(relative_difference(&blocked, &x));
        }
        worst
    }

    fn analyse_and_factor(system: &LinearSystem) -> Option<(FrontalStructure, FrontalFactors)> {
        let structure = FrontalStructure::analyse(&system.pattern, None)
            .unwrap()
            .unwrap();
        let mut factors = FrontalFactors::default();
        structure
            .factor(&system.pattern, &system.values, &mut factors, Par::Seq)
            .ok()?;
        Some((structure, factors))
    }

    /// The widths of the tests: one column, a few, one internal block, and widths that are
    /// no multiple of it (nor of the dense-solve threshold).
    const WIDTHS: [usize; 5] = [1, 3, 64, 67, 131];

    /// A random `m x m` front whose diagonal is `diagonal` times the other entries.
    fn random_front(m: usize, diagonal: f64, seed: u64) -> Vec<f64> {
        let mut rng = SplitMix64(seed);
        let mut f: Vec<f64> = (0..m * m).map(|_| 2.0 * rng.uniform() - 1.0).collect();
        for k in 0..m {
            f[k + m * k] *= diagonal;
        }
        f
    }

    #[test]
    fn blocked_panel_equals_the_unblocked_panel() {
        let mut swapped = 0;
        for (seed, (m, ns)) in [(150, 100), (97, 97), (200, 41), (64, 33), (300, 260)]
            .into_iter()
            .enumerate()
        {
            let front = random_front(m, 0.5, 40 + seed as u64);
            let run = |nb: usize| {
                let mut f = front.clone();
                let mut swaps = vec![0u32; ns];
                factor_panel_blocked(&mut f, m, ns, &mut swaps, 7, nb, Par::Seq).unwrap();
                (f, swaps)
            };
            let (reference, ref_swaps) = run(ns);
            swapped += ref_swaps
                .iter()
                .enumerate()
                .filter(|&(k, &p)| p as usize != k + 7)
                .count();
            for nb in [1, 5, PANEL_BLOCK] {
                let (f, swaps) = run(nb);
                assert_eq!(swaps, ref_swaps, "m {m}, ns {ns}, nb {nb}");
                let diff = relative_difference(&f, &reference);
                // the same updates summed in another order
                assert!(diff < 1e-12, "m {m}, ns {ns}, nb {nb}: {diff:e}");
            }
        }
        assert!(swapped > 100, "only {swapped} row swaps");
        // A block whose rows cannot pass the threshold is refused by both.
        let (m, ns) = (120, 80);
        let mut front = random_front(m, 1.0, 3);
        for c in 0..m {
            for i in ns..m {
                front[i + m * c] *= 1e4;
            }
        }
        for nb in [ns, PANEL_BLOCK] {
            let mut f = front.clone();
            assert_eq!(
                factor_panel_blocked(&mut f, m, ns, &mut [0; 80], 0, nb, Par::Seq),
                Err(FrontFailure::NeedsPivoting)
            );
        }
    }

    #[test]
    fn blocked_solve_equals_scalar_solves_on_samples() {
        let samples = [
            Poisson2d::new(12).system(),
            ConvectionDiffusion2d {
                n: 15,
                velocity: [30.0, -20.0],
            }
            .system(),
            RandomDiagonallyDominant {
                n: 300,
                off_diagonals: 4,
                seed: 7,
            }
            .system(),
        ];
        for (which, system) in samples.iter().enumerate() {
            let (structure, factors) = analyse_and_factor(system).expect("no fallback");
            for k in WIDTHS {
                let diff = blocked_against_scalar(
                    &structure,
                    &factors,
                    system.dimension(),
                    k,
                    3 + k as u64,
                );
                // same factors, sums in another order: round-off only
                assert!(diff < 1e-13, "sample {which}, k {k}: {diff:e}");
            }
        }
    }

    #[test]
    fn blocked_solve_equals_scalar_solves_with_row_swaps_in_fronts() {
        let mut swapped = 0;
        let (mut narrow, mut wide) = (false, false);
        for seed in 0..30u64 {
            let n = 40 + (seed as usize * 37) % 260;
            // diagonal 5x the other entries: most fronts keep their pivots (22 of the 30 matrices),
            // with row swaps in each of those
            let system = random_general(n, 2 + seed as usize % 3, 5.0, 500 + seed);
            let Some((structure, factors)) = analyse_and_factor(&system) else {
                continue; // a front without an acceptable pivot: not the kernel's case
            };
            if factors
                .swaps
                .iter()
                .enumerate()
                .all(|(k, &p)| p as usize == k)
            {
                continue;
            }
            swapped += 1;
            for s in 0..structure.n_supernodes() {
                let ns = structure.begin[s + 1] - structure.begin[s];
                narrow |= ns < DENSE_SOLVE_COLUMNS;
                wide |= ns >= DENSE_SOLVE_COLUMNS;
            }
            for k in WIDTHS {
                let diff =
                    blocked_against_scalar(&structure, &factors, n, k, seed * 1000 + k as u64);
                // round-off amplified by the conditioning of random matrices (some diagonals
                // near zero): measured at most 2.3e-13 (seed 14, k 64), most below 5e-14
                assert!(diff < 1e-12, "seed {seed}, n {n}, k {k}: {diff:e}");
            }
        }
        assert!(
            swapped >= 20,
            "only {swapped} factorisations with row swaps"
        );
        assert!(narrow && wide, "both supernode paths are exercised");
    }
}
