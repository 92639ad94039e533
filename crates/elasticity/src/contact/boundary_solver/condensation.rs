//! The law-independent condensation of the bulk onto the contact tractions: the stabilised
//! bulk factorised once, `P Z` and `N Z`, and the unit-load states.

use std::sync::{Arc, Mutex};

use capstan_friction::FrictionLaw;
use capstan_solvers::{BoxedLinearSolver, LinearSolver};
use faer::Mat;

use crate::contact::error::ContactError;
use crate::contact::model::{ContactModel, ExtendedPattern};
use crate::contact::operator::ContactOperator;

/// Power iterations of [`largest_singular_value`].
pub(super) const SINGULAR_VALUE_ITERATIONS: usize = 30;

/// Workspace (doubles) of one block of condensation solves: 2^24 (128 MiB).
pub(super) const CONDENSATION_BLOCK_ENTRIES: usize = 1 << 24;

/// The law-independent part of [`BoundarySolver`]: the factorised stabilised bulk and the
/// condensed matrices (cheap to clone: the large parts are shared).
#[derive(Clone)]
pub(super) struct Condensation {
    /// The factorised stabilised bulk (any registered backend: `ContactSettings::linear`).
    pub(super) lu: Arc<Mutex<BoxedLinearSolver>>,
    pub(super) spring: Vec<f64>,
    pub(super) pz: Arc<Mat<f64>>,
    pub(super) nz: Arc<Mat<f64>>,
    /// `(P v_i, N v_i)` for unit `tau0` (`i = 0`) and unit `tau_max` (`i = 1`).
    pub(super) base: [(Vec<f64>, Vec<f64>); 2],
    /// The stuck state (`v^2 = 0` at every contact node) for the unit loads: Newton's start.
    pub(super) stuck: [Vec<f64>; 2],
}

/// Factorises the stabilised bulk `A + sum_k w_k c_k e_row_k e_tdof_k^T` (`values` holds `A` on
/// the extended pattern) and returns `(P Z, N Z)`, `Z = A~^-1 W`, by blocked multi-right-hand-side
/// solves (at most [`CONDENSATION_BLOCK_ENTRIES`] doubles of workspace per block).
pub(super) fn condense<D: ContactOperator, L: FrictionLaw<f64>>(
    model: &ContactModel<D, L>,
    ext: &ExtendedPattern,
    values: &[f64],
    spring: &[f64],
    lu: &mut dyn LinearSolver<f64>,
) -> Result<(Mat<f64>, Mat<f64>), ContactError> {
    let m = spring.len();
    let n = model.dof_count();
    let mut values = values.to_vec();
    for (k, c) in spring.iter().enumerate() {
        values[ext.tangential_slot[k]] += model.active_node(k).traction_weight * c;
    }
    lu.factor(&values)?;
    let mut pz = Mat::<f64>::zeros(m, m);
    let mut nz = Mat::<f64>::zeros(m, m);
    let block = (CONDENSATION_BLOCK_ENTRIES / n.max(1)).clamp(1, m.max(1));
    let mut cols = vec![0.0; n * block];
    for first in (0..m).step_by(block) {
        let width = block.min(m - first);
        let cols = &mut cols[..n * width];
        cols.iter_mut().for_each(|x| *x = 0.0);
        for c in 0..width {
            let node = model.active_node(first + c);
            cols[c * n + node.tangential_row.expect("active")] = node.traction_weight;
        }
        lu.solve_many_in_place(cols, width)?;
        for c in 0..width {
            let col = &cols[c * n..(c + 1) * n];
            for j in 0..m {
                let nj = model.active_node(j);
                pz[(j, first + c)] = col[nj.tangential_dof];
                nz[(j, first + c)] = nj.normal_stress.dot(col);
            }
        }
    }
    Ok((pz, nz))
}

/// The frictionless condensed operator `H0 = I - C P Z`.
pub(super) fn frictionless_operator(spring: &[f64], pz: &Mat<f64>) -> Mat<f64> {
    let m = pz.nrows();
    Mat::<f64>::from_fn(m, m, |i, j| {
        f64::from(u8::from(i == j)) - spring[i] * pz[(i, j)]
    })
}

/// An estimate (power iteration on `H^T H`, within a few percent) of the largest singular
/// value of `h`.
pub(super) fn largest_singular_value(h: &Mat<f64>) -> f64 {
    let m = h.nrows();
    if m == 0 {
        return 0.0;
    }
    // a start vector with no special symmetry
    let mut v: Vec<f64> = (0..m)
        .map(|i| 1.0 + (i as f64 * 0.618_034).fract())
        .collect();
    let mut sigma = 0.0;
    for _ in 0..SINGULAR_VALUE_ITERATIONS {
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(norm > 0.0 && norm.is_finite()) {
            return sigma;
        }
        v.iter_mut().for_each(|x| *x /= norm);
        let hv: Vec<f64> = (0..m)
            .map(|i| (0..m).map(|j| h[(i, j)] * v[j]).sum())
            .collect();
        sigma = hv.iter().map(|x| x * x).sum::<f64>().sqrt();
        v = (0..m)
            .map(|j| (0..m).map(|i| h[(i, j)] * hv[i]).sum())
            .collect();
    }
    sigma
}

/// `(P v, N v)`: `v^2` and `T^3_3` at the active contact nodes.
pub(super) fn project<D: ContactOperator, L: FrictionLaw<f64>>(
    model: &ContactModel<D, L>,
    v: &[f64],
) -> (Vec<f64>, Vec<f64>) {
    (0..model.active().len())
        .map(|k| {
            let node = model.active_node(k);
            (v[node.tangential_dof], node.normal_stress.dot(v))
        })
        .unzip()
}

pub(super) fn row_max(
    pattern: &capstan_solvers::SparsityPattern,
    values: &[f64],
    row: usize,
) -> f64 {
    pattern
        .entries()
        .zip(values)
        .filter(|((r, _), _)| *r == row)
        .fold(0.0f64, |m, (_, v)| m.max(v.abs()))
        .max(1.0)
}
