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
//!     or the pivot row has no entry right of the pivot (a Dirichlet row: no update, no growth)
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

    /// The shape of supernode `s`'s front.
    fn front(&self, s: usize) -> Front<'_> {
        let (b, e) = (self.begin[s], self.begin[s + 1]);
        let r = self.off_block_rows(s);
        Front {
            b,
            e,
            ns: e - b,
            r,
            nr: r.len(),
            m: e - b + r.len(),
        }
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
            let Front { b, e, ns, r, nr, m } = self.front(s);
            for k in 0..ns {
                pos[b + k] = k as u32;
            }
            for (t, &i) in r.iter().enumerate() {
                pos[i as usize] = (ns + t) as u32;
            }
            self.assemble_front(s, m, &pos, row_idx, values, &mut contributions, &mut front);
            let swaps = &mut factors.swaps[b..e];
            self.eliminate(&mut front, m, ns, swaps, b, PIVOT_THRESHOLD, par)?;
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

    /// Assembles the `m x m` front of supernode `s` into `front` (cleared first): the entries
    /// of `A` it owns and the contribution blocks of its children (taken out of
    /// `contributions`); `pos` maps positions to the front's rows.
    #[allow(clippy::too_many_arguments)] // the factorisation loop's state, passed down as is
    fn assemble_front(
        &self,
        s: usize,
        m: usize,
        pos: &[u32],
        row_idx: &[usize],
        values: &[f64],
        contributions: &mut [Option<Vec<f64>>],
        front: &mut Vec<f64>,
    ) {
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
    }

    /// Eliminates the first `ns` columns of the `m x m` front whose first column is position
    /// `b` (pivots from rows `0..ns` passing `threshold`, swaps recorded in `swaps`), then forms
    /// `U12 = L11^-1 F12` and the Schur update `F22 -= L21 U12` in place.
    #[allow(clippy::too_many_arguments)] // the front, its shape and the kernel's knobs
    fn eliminate(
        &self,
        front: &mut [f64],
        m: usize,
        ns: usize,
        swaps: &mut [u32],
        b: usize,
        threshold: f64,
        par: Par,
    ) -> Result<(), FrontFailure> {
        factor_panel(front, m, ns, swaps, b, PANEL_BLOCK, threshold, par).map_err(|failure| {
            match failure {
                FrontFailure::Singular(k) => FrontFailure::Singular(self.perm_fwd[b + k]),
                other => other,
            }
        })?;
        let nr = m - ns;
        if nr > 0 {
            let par = if nr * nr * ns >= PARALLEL_FLOPS {
                par
            } else {
                Par::Seq
            };
            let f = MatMut::from_column_major_slice_mut(front, m, m);
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
        Ok(())
    }
}

mod panel;
mod schur;
pub(crate) mod solve;
/// A supernode's front: its columns `b..e` (`ns` of them), the rows `r` below the diagonal block
/// (`nr` of them), `m = ns + nr` rows in all.
struct Front<'a> {
    b: usize,
    e: usize,
    ns: usize,
    r: &'a [u32],
    nr: usize,
    m: usize,
}

#[cfg(test)]
mod tests;

pub(crate) use panel::FrontFailure;
use panel::{PANEL_BLOCK, PARALLEL_FLOPS, PIVOT_THRESHOLD, factor_panel};
