//! Forward and back substitution with the multifrontal factors: one right-hand side, and
//! blocks of right-hand sides by dense kernels per front.

use faer::reborrow::{Reborrow, ReborrowMut};
use faer::{Accum, MatMut, Par};

use super::{Front, FrontalFactors, FrontalStructure};

impl FrontalStructure {
    /// Solves `A x = rhs` in place with the factors (no check, no refinement).
    pub(crate) fn solve_in_place(&self, factors: &FrontalFactors, rhs: &mut [f64], y: &mut [f64]) {
        let val = &factors.values;
        for (k, &p) in self.perm_fwd.iter().enumerate() {
            y[k] = rhs[p];
        }
        // forward: L y = P y
        for s in 0..self.n_supernodes() {
            let Front { b, e, ns, r, m, .. } = self.front(s);
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
            let Front { b, e, ns, r, m, .. } = self.front(s);
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
pub(super) const DENSE_SOLVE_COLUMNS: usize = 8;

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
            let Front { b, e, ns, r, nr, m } = self.front(s);
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
            let Front { b, e, ns, r, nr, m } = self.front(s);
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
