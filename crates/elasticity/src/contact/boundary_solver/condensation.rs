//! The law-independent condensation of the bulk onto the contact tractions: the stabilised
//! bulk factorised once, `P Z` and `N Z`, and the unit-load states.

use std::sync::{Arc, Mutex};

use capstan_friction::FrictionLaw;
use capstan_solvers::{BoxedLinearSolver, LinearSolver, Observer, Progress, SetUpPhase};
use faer::Mat;
use faer::linalg::solvers::Solve;

use crate::contact::error::ContactError;
use crate::contact::model::ContactModel;
use crate::contact::operator::ContactOperator;
use crate::contact::pattern::ExtendedPattern;

/// Power iterations of [`largest_singular_value`].
pub(super) const SINGULAR_VALUE_ITERATIONS: usize = 30;

/// Workspace (doubles) of one block of condensation solves: 2^24 (128 MiB).
pub(super) const CONDENSATION_BLOCK_ENTRIES: usize = 1 << 24;

/// `(P v, N v)`: the tangential contact displacements and normal stresses of a load state.
pub(super) type ContactState = (Vec<f64>, Vec<f64>);

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
    /// `((P v_f, N v_f), stuck state)` of the fixed loads (a body force at its full value,
    /// [`ContactModel::with_fixed_loads`]), which every load state adds; `None` without.
    pub(super) fixed: Option<(ContactState, Vec<f64>)>,
}

/// Factorises the stabilised bulk `A + sum_k w_k c_k e_row_k e_tdof_k^T` (`values` holds `A` on
/// the extended pattern) and returns `(P Z, N Z)`, `Z = A~^-1 W` ([`factor_stabilised`], then
/// [`condense_factored`]), reporting the factorisation to `observer`.
pub(super) fn condense<D: ContactOperator, L: FrictionLaw<f64>>(
    model: &ContactModel<D, L>,
    ext: &ExtendedPattern,
    values: &[f64],
    spring: &[f64],
    lu: &mut dyn LinearSolver<f64>,
    schur: Option<&ContactSchur>,
    observer: &mut dyn Observer<f64>,
) -> Result<(Mat<f64>, Mat<f64>), ContactError> {
    observer.iteration(&Progress::set_up(SetUpPhase::Factorisation, 0, 1));
    factor_stabilised(model, ext, values, spring, lu)?;
    observer.iteration(&Progress::set_up(SetUpPhase::Factorisation, 1, 1));
    condense_factored(model, spring, lu, schur, observer)
}

/// Factorises the stabilised bulk `A~ = A + sum_k w_k c_k e_row_k e_tdof_k^T` (`values` holds
/// `A` on the extended pattern, `c` is `spring`, `w_k` the traction weights) into `lu`.
pub(super) fn factor_stabilised<D: ContactOperator, L: FrictionLaw<f64>>(
    model: &ContactModel<D, L>,
    ext: &ExtendedPattern,
    values: &[f64],
    spring: &[f64],
    lu: &mut dyn LinearSolver<f64>,
) -> Result<(), ContactError> {
    let mut values = values.to_vec();
    for (k, c) in spring.iter().enumerate() {
        values[ext.tangential_slot[k]] += model.active_node(k).traction_weight * c;
    }
    lu.factor(&values)?;
    Ok(())
}

/// `(P Z, N Z)`, `Z = A~^-1 W`, with `A~` factorised in `lu` ([`factor_stabilised`] for
/// `spring`): from the Schur complements `schur` when given and they agree with a solve
/// (dense work only), else by blocked multi-right-hand-side solves (at most
/// [`CONDENSATION_BLOCK_ENTRIES`] doubles of workspace per block).
///
/// Reports every block of solves to `observer` as [`capstan_solvers::SolveStage::SetUp`]
/// events and stops with [`ContactError::Interrupted`] before the condensation or between
/// blocks when it asks to.
pub(super) fn condense_factored<D: ContactOperator, L: FrictionLaw<f64>>(
    model: &ContactModel<D, L>,
    spring: &[f64],
    lu: &mut dyn LinearSolver<f64>,
    schur: Option<&ContactSchur>,
    observer: &mut dyn Observer<f64>,
) -> Result<(Mat<f64>, Mat<f64>), ContactError> {
    let m = spring.len();
    let n = model.dof_count();
    if observer.interrupted() {
        return Err(ContactError::Interrupted { iterations: 0 });
    }
    if let Some(schur) = schur {
        let (pz, nz) = schur.condense(model, spring)?;
        if agrees_with_a_solve(model, &pz, &nz, lu)? {
            observer.iteration(&Progress::set_up(SetUpPhase::Condensation, m, m));
            return Ok((pz, nz));
        }
    }
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
        observer.iteration(&Progress::set_up(
            SetUpPhase::Condensation,
            first + width,
            m,
        ));
        if observer.interrupted() {
            return Err(ContactError::Interrupted { iterations: 0 });
        }
    }
    Ok((pz, nz))
}

/// Largest relative difference accepted between the Schur condensation and a solve.
const SCHUR_CHECK: f64 = 1e-9;

/// Whether `(P Z, N Z)` from the Schur complements agree with one solve by the factorised
/// stabilised bulk `lu` on the sum of the unit right-hand sides (`Z 1 = A~^-1 W 1`), to
/// [`SCHUR_CHECK`] of the largest row sum of magnitudes `max_i sum_j |Z_ij|` (the sums cancel
/// along the rigid mode of a circle): the partial factorisation pivots more loosely than
/// the LU, and a failed check condenses by solves instead.
fn agrees_with_a_solve<D: ContactOperator, L: FrictionLaw<f64>>(
    model: &ContactModel<D, L>,
    pz: &Mat<f64>,
    nz: &Mat<f64>,
    lu: &mut dyn LinearSolver<f64>,
) -> Result<bool, ContactError> {
    let m = pz.nrows();
    let mut v = vec![0.0; model.dof_count()];
    for k in 0..m {
        let node = model.active_node(k);
        v[node.tangential_row.expect("active")] += node.traction_weight;
    }
    lu.solve_in_place(&mut v)?;
    let (x, sigma) = project(model, &v);
    let close = |z: &Mat<f64>, y: &[f64]| {
        let row_sums: Vec<f64> = (0..m).map(|i| (0..m).map(|j| z[(i, j)]).sum()).collect();
        // the sums cancel along a near-rigid mode: measure against the sums of magnitudes
        let magnitude = (0..m)
            .map(|i| (0..m).map(|j| z[(i, j)].abs()).sum::<f64>())
            .fold(0.0f64, f64::max);
        let scale = y
            .iter()
            .fold(magnitude, |a, b| a.max(b.abs()))
            .max(f64::MIN_POSITIVE);
        row_sums
            .iter()
            .zip(y)
            .all(|(a, b)| (a - b).abs() <= SCHUR_CHECK * scale)
    };
    Ok(close(pz, &x) && close(nz, &sigma))
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

/// The bulk's Schur complements onto the contact rows, from which the condensed matrices of
/// any spring follow by dense work only (no sparse solves).
///
/// # Math
/// With `T` the tangential contact rows and unknowns and `I` the rest of the bulk, the
/// bordered matrix `E = [A 0; N 1]` (`N`: the normal-stress rows) has the Schur complement
/// onto `T` and the border
/// ```text
/// [S 0; K 1],   S = A_TT - A_TI A_II^-1 A_IT,   K = N_T - N_I A_II^-1 A_IT
/// ```
/// (one partial factorisation, [`capstan_solvers::schur_complement`]). The spring changes
/// `A_TT` only, so `S~ = S + sum_k w_k c_k e_row_k e_tdof_k^T`; a right-hand side `W s`
/// supported on `T` gives `v_T = S~^-1 W_T s` and `v_I = -A_II^-1 A_IT v_T`, hence
/// ```text
/// P Z = (S~^-1 W_T)[tangential dofs],   N Z = K S~^-1 W_T
/// ```
/// the same matrices as the `m` solves of [`condense`], up to rounding.
pub(super) struct ContactSchur {
    /// `S` (`t x t`, `t = |T|`).
    s: Mat<f64>,
    /// `K` (`m x t`).
    k: Mat<f64>,
    /// Index in `T` of each active node's tangential row and tangential unknown.
    row_at: Vec<usize>,
    dof_at: Vec<usize>,
}

/// What [`ContactSchur`] is computed from, gathered from the model: the bordered matrix
/// `E = [A 0; N 1]` (pattern and values), the trailing unknowns `T` and the interior's order.
/// Plain data (`Send`), so that the partial factorisation ([`SchurInput::compute`]) can run on
/// another thread beside the factorisation of the stabilised bulk.
pub(super) struct SchurInput {
    pattern: capstan_solvers::SparsityPattern,
    values: Vec<f64>,
    trailing: Vec<usize>,
    order: Option<Vec<usize>>,
    /// `t = |T|` without the normal-stress rows.
    t: usize,
    m: usize,
    row_at: Vec<usize>,
    dof_at: Vec<usize>,
}

impl SchurInput {
    /// Gathers the input of [`ContactSchur`] from `model`.
    ///
    /// # Errors
    /// Pattern errors; the operator's ordering failing.
    pub(super) fn new<D: ContactOperator, L: FrictionLaw<f64>>(
        model: &ContactModel<D, L>,
    ) -> Result<Self, ContactError> {
        let system = model.system();
        let n = model.dof_count();
        let m = model.active().len();
        let mut index = vec![usize::MAX; n];
        let mut trailing = Vec::new();
        let mut at = |j: usize, trailing: &mut Vec<usize>| {
            if index[j] == usize::MAX {
                index[j] = trailing.len();
                trailing.push(j);
            }
            index[j]
        };
        let mut row_at = Vec::with_capacity(m);
        let mut dof_at = Vec::with_capacity(m);
        for k in 0..m {
            let node = model.active_node(k);
            row_at.push(at(node.tangential_row.expect("active"), &mut trailing));
            dof_at.push(at(node.tangential_dof, &mut trailing));
        }
        let t = trailing.len();
        // E = [A 0; N 1]: the normal-stress rows as rows n..n + m, with unit diagonal, merged
        // into `A`'s columns (`A`'s entries are not sorted again)
        let mut entries: Vec<(usize, usize)> = Vec::new();
        let mut values = Vec::new();
        for k in 0..m {
            let row = &model.active_node(k).normal_stress;
            for (&c, &v) in row.columns.iter().zip(&row.values) {
                entries.push((n + k, c));
                values.push(v);
            }
            entries.push((n + k, n + k));
            values.push(1.0);
        }
        let (pattern, a_slots, slots) = system
            .pattern
            .with_entries(n + m, n + m, &entries)
            .map_err(ContactError::from)?;
        let mut placed = vec![0.0; pattern.nnz()];
        for (&slot, &v) in a_slots.iter().zip(&system.values) {
            placed[slot] += v;
        }
        for (&slot, v) in slots.iter().zip(values) {
            placed[slot] += v;
        }
        trailing.extend(n..n + m);
        // the operator's own fill-reducing order for the interior (nested dissection of grids)
        let order = model
            .discretisation()
            .lu_ordering()
            .permutation(&system.pattern)?
            .map(|mut order| {
                order.extend(n..n + m);
                order
            });
        Ok(Self {
            pattern,
            values: placed,
            trailing,
            order,
            t,
            m,
            row_at,
            dof_at,
        })
    }

    /// The Schur complements (one partial factorisation); `None` when the interior needs
    /// pivoting across fronts (condense by solves then).
    ///
    /// # Errors
    /// A singular interior; faer's analysis out of memory.
    pub(super) fn compute(self) -> Result<Option<ContactSchur>, ContactError> {
        let Some(schur) = capstan_solvers::schur_complement(
            &self.pattern,
            &self.values,
            &self.trailing,
            self.order.as_deref(),
        )?
        else {
            return Ok(None);
        };
        let (t, m) = (self.t, self.m);
        let size = t + m;
        Ok(Some(ContactSchur {
            s: Mat::from_fn(t, t, |i, j| schur[i + size * j]),
            k: Mat::from_fn(m, t, |i, j| schur[t + i + size * j]),
            row_at: self.row_at,
            dof_at: self.dof_at,
        }))
    }
}

impl ContactSchur {
    /// The Schur complements of `model`'s bulk; `None` when the interior needs pivoting
    /// across fronts (condense by solves then).
    ///
    /// # Errors
    /// A singular interior; faer's analysis out of memory.
    #[cfg(test)]
    pub(super) fn new<D: ContactOperator, L: FrictionLaw<f64>>(
        model: &ContactModel<D, L>,
    ) -> Result<Option<Self>, ContactError> {
        SchurInput::new(model)?.compute()
    }

    /// `(P Z, N Z)` for the spring `spring` (see [`ContactSchur`]).
    ///
    /// # Errors
    /// [`capstan_solvers::SolverError::Singular`] when `S~` is singular (non-finite result).
    pub(super) fn condense<D: ContactOperator, L: FrictionLaw<f64>>(
        &self,
        model: &ContactModel<D, L>,
        spring: &[f64],
    ) -> Result<(Mat<f64>, Mat<f64>), ContactError> {
        let m = spring.len();
        let t = self.s.nrows();
        let mut s = self.s.clone();
        let mut w = Mat::<f64>::zeros(t, m);
        for (k, c) in spring.iter().enumerate() {
            let weight = model.active_node(k).traction_weight;
            s[(self.row_at[k], self.dof_at[k])] += weight * c;
            w[(self.row_at[k], k)] = weight;
        }
        let x = s.partial_piv_lu().solve(&w);
        let pz = Mat::<f64>::from_fn(m, m, |j, c| x[(self.dof_at[j], c)]);
        let nz = &self.k * &x;
        if pz
            .col_iter()
            .chain(nz.col_iter())
            .flat_map(|c| c.iter())
            .any(|v| !v.is_finite())
        {
            return Err(capstan_solvers::SolverError::Singular { pivot: None }.into());
        }
        Ok((pz, nz))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::ThickBody;
    use capstan_friction::{RegularisedCoulomb, RegularisedCoulombParams};
    use capstan_geometry::{EllipticalPrism, Obstacle};
    use capstan_solvers::SparseLu;

    /// `max |a - b| / max |a|`.
    fn relative_difference(a: &Mat<f64>, b: &Mat<f64>) -> f64 {
        let (mut d, mut s) = (0.0f64, 0.0f64);
        for j in 0..a.ncols() {
            for i in 0..a.nrows() {
                d = d.max((a[(i, j)] - b[(i, j)]).abs());
                s = s.max(a[(i, j)].abs());
            }
        }
        d / s
    }

    #[test]
    fn schur_condensation_matches_condensation_by_solves() {
        let ellipse = ThickBody {
            obstacle: Obstacle::Ellipse(EllipticalPrism::new(2.0, 1.2).unwrap()),
            ..ThickBody::paper(33, 7).unwrap()
        };
        for (body, method) in [
            (ThickBody::paper(41, 9).unwrap(), "fd"),
            (ellipse, "fd"),
            (ThickBody::paper(41, 9).unwrap(), "fem-q1"),
            (ThickBody::paper(41, 9).unwrap(), "fem-q2"),
        ] {
            let body = ThickBody {
                method: method.parse().unwrap(),
                ..body
            };
            let params = RegularisedCoulombParams::new(0.5, 1e-5).unwrap();
            let model = body.model(RegularisedCoulomb, params, 1e-5).unwrap();
            let ext = model.extended();
            let mut values = vec![0.0; ext.pattern.nnz()];
            for (k, &a) in model.system().values.iter().enumerate() {
                values[ext.a_slot[k]] += a;
            }
            let m = model.active().len();
            // a spring of the solver's size, varying along the face
            let spring: Vec<f64> = (0..m)
                .map(|k| values[ext.tangential_slot[k]].abs() * (1.0 + 0.1 * (k % 3) as f64))
                .collect();
            let mut lu = SparseLu::default();
            lu.analyse(&ext.pattern).unwrap();
            let by_solves = condense(
                &model,
                ext,
                &values,
                &spring,
                &mut lu,
                None,
                &mut capstan_solvers::SilentObserver,
            )
            .unwrap();
            let schur = ContactSchur::new(&model)
                .unwrap()
                .expect("no pivoting across fronts");
            let by_schur = condense(
                &model,
                ext,
                &values,
                &spring,
                &mut lu,
                Some(&schur),
                &mut capstan_solvers::SilentObserver,
            )
            .unwrap();
            // two eliminations of the same matrix: round-off, amplified by the spring's scale
            for (a, b, what) in [
                (&by_solves.0, &by_schur.0, "P Z"),
                (&by_solves.1, &by_schur.1, "N Z"),
            ] {
                let d = relative_difference(a, b);
                assert!(d < 1e-11, "{method}: {what} differs by {d:.2e}");
            }
        }
    }
}
