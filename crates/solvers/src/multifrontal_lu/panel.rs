//! The dense partial LU of one front (threshold pivoting inside the front, blocked).

use faer::reborrow::{Reborrow, ReborrowMut};
use faer::{Accum, MatMut, Par};

/// Smallest accepted `|pivot| / max |entry of its column in the front|`.
pub(crate) const PIVOT_THRESHOLD: f64 = 0.01;

/// Fronts with fewer multiply-adds than this in their Schur update run sequentially.
pub(super) const PARALLEL_FLOPS: usize = 1 << 20;

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

/// Columns per block of [`factor_panel`]: within a block the LU is right-looking by rank-1
/// updates; the rest of the panel is updated per block by a triangular solve and a matrix
/// product (most of the work of wide supernodes, at matrix-product speed).
pub(super) const PANEL_BLOCK: usize = 32;

/// Right-looking LU of the first `ns` columns of the `m x m` column-major `front`, pivots from
/// rows `0..ns` only, accepted when at least `threshold` times the largest entry of their
/// column ([`PIVOT_THRESHOLD`] for the LU); the trailing columns get only the row swaps. `swaps[k]` receives
/// `offset + ` the row swapped with `k`.
///
/// # Math
/// Blocked by `nb` columns `[kb, ke)` (the solver passes [`PANEL_BLOCK`]; `nb >= ns`:
/// unblocked): factor them (rows `kb..m`) by rank-1 updates, then
/// `U[kb..ke, ke..ns] = L[kb..ke, kb..ke]^-1 F[kb..ke, ke..ns]` and
/// `F[ke..m, ke..ns] -= L[ke..m, kb..ke] U[kb..ke, ke..ns]`. Every column sees the same
/// updates as in the unblocked order before its pivot is chosen, so the pivots agree.
#[allow(clippy::too_many_arguments)] // the front, its shape, and the kernel's knobs
pub(super) fn factor_panel(
    front: &mut [f64],
    m: usize,
    ns: usize,
    swaps: &mut [u32],
    offset: usize,
    nb: usize,
    threshold: f64,
    par: Par,
) -> Result<(), FrontFailure> {
    let nb = nb.max(1);
    for kb in (0..ns).step_by(nb) {
        let ke = (kb + nb).min(ns);
        factor_columns(front, m, ns, kb..ke, swaps, offset, threshold)?;
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

/// The unblocked step of [`factor_panel`]: columns `cols` (within `0..ns`), whose
/// updates from the columns before them are done; rank-1 updates reach only `cols`.
fn factor_columns(
    front: &mut [f64],
    m: usize,
    ns: usize,
    cols: core::ops::Range<usize>,
    swaps: &mut [u32],
    offset: usize,
    threshold: f64,
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
        if p < threshold * q && !row_is_done(front, m, k, pivot_row) {
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

/// Whether row `row` of the front has no entry right of column `k` (a Dirichlet row, `e_k^T`):
/// eliminating on it then updates nothing, so its multipliers cannot make entries grow and
/// the threshold does not apply.
fn row_is_done(front: &[f64], m: usize, k: usize, row: usize) -> bool {
    (k + 1..m).all(|c| front[row + m * c] == 0.0)
}
