//! Exact (nonsmooth) Coulomb friction on the thick body: the friction rows of the full
//! system written as the Alart–Curnier projection, solved by the full-system (semismooth)
//! Newton method. Plane strain (one tangential entry per site) and 3-D (the friction disc
//! or ellipse, a two-component slip).

use std::sync::Arc;

use capstan_friction::nonsmooth_law::DynNonsmoothLaw;
use capstan_friction::{FrictionLaw, FrictionState, Projection};
use capstan_solvers::{ActiveSet, SparsityPattern};

use crate::contact::error::ContactError;
use crate::contact::model::ContactModel;
use crate::contact::operator::ContactOperator;
use crate::contact::pattern::ExtendedPattern;
use crate::error::ElasticityError;

/// The blend `delta` of the stick branch into the generalised Jacobian of a sliding site
/// (see [`ContactModel::into_exact_friction`]).
const SLIP_JACOBIAN_BLEND: f64 = 1e-6;

/// The state of a site after the projection, its physical slip and friction traction.
type SiteState = (FrictionState, [f64; 2], [f64; 2]);

/// One contact site under exact friction: its entries, their rows of `A` and the data of the
/// projection.
#[derive(Debug, Clone)]
struct ExactSite {
    /// Active entries (indices into [`ContactModel::active`]).
    entries: Vec<usize>,
    /// Per entry, `(A slot, column)` of the entries of its tangential row in `A`.
    rows: Vec<Vec<(usize, usize)>>,
    /// Per entry `e` and partner `f != e`: the slots in the extended pattern of
    /// `(row_e, column)` for the columns of `rows[f]` (empty for `f == e`).
    cross: Vec<Vec<Vec<usize>>>,
    /// `tau = sum_f inverse[f] t_f`: the columns of the (pseudo-)inverse of `F^T`.
    inverse: Vec<[f64; 2]>,
    /// The augmentation `r` (traction per length).
    augmentation: f64,
}

/// Exact friction on every contact site of a model: the law (a projection onto the friction
/// set) and the per-site data. See [`ContactModel::into_exact_friction`].
#[derive(Debug, Clone)]
pub(crate) struct ExactFriction {
    law: Arc<dyn DynNonsmoothLaw>,
    sites: Vec<ExactSite>,
}

/// The projection at one site: the trial, the projection and the normal stress seen by it.
struct SiteProjection {
    slip: [f64; 2],
    projection: Projection<f64>,
    /// `d sigma_seen / d sigma_n` (0 where unilateral contact clips a tensile stress).
    d_sigma: f64,
    /// `d trial / d sigma_n` (the penalty start's trial reads `|sigma_n|`).
    d_trial_sigma: [f64; 2],
    /// `|sigma_n|`.
    projection_sigma_abs: f64,
}

impl<D: ContactOperator, L: FrictionLaw<f64>> ContactModel<D, L> {
    /// The model with exact (nonsmooth) friction `law` on every contact site in place of its
    /// pointwise law (which is then not used): `law` is a projection onto the friction set
    /// (`exact-coulomb`: the disc `|t| <= mu |sigma_n|`; `exact-orthotropic-coulomb`: the
    /// ellipse), [`capstan_friction::nonsmooth_law::bind_nonsmooth`] or a scene's
    /// [`capstan_friction::AnyNonsmoothParams`].
    ///
    /// # Math
    /// With `q_e(v) = (A v - b)_{row_e}` the free tangential balance row of entry `e` of a site
    /// (weight `w_e`, frame `f_e`, `F = [f_e]`), the friction traction the row carries and the
    /// slip are
    /// ```text
    /// t_e = q_e / w_e,   tau = F^{-T} t   (pseudo-inverse f / |f|^2 for one entry),   u = F x
    /// ```
    /// and the friction rows become (Alart–Curnier, De Saxcé)
    /// ```text
    /// R_e(v) = q_e(v) - w_e f_e . P_C(sigma_n)(tau(v) - r u(v))
    /// ```
    /// `R = 0` iff `tau = P_C(tau - r u)`: stick (`|tau| <= mu |sigma_n|`, `u = 0`) or slip on
    /// the limit surface against the slip. `r = |A_{row_e, dof_e}| / (w_e |f_e|^2)` (mean over
    /// the entries) makes `r u` of the size of `tau`. The generalised Jacobian is
    /// ```text
    /// dR_e = a_e - sum_f (w_e / w_f) (f_e^T J F^{-T}_f) a_f + w_e r sum_f (f_e^T J f_f) e_{dof_f}
    ///        - w_e (f_e . dP/dsigma) dsigma_n
    /// ```
    /// (`J = dP/dtrial`): stick rows read `w r u = 0`, slip rows the balance with the limit
    /// traction, so Newton on `R` is the semismooth Newton method. Separated sites (unilateral
    /// contact) keep the free row (`tau = 0`).
    ///
    /// On a circle the bilateral body has a rigid sliding mode, and the exact solution of the
    /// paper's body sticks at one node only (the neutral point: the regularised stick zone
    /// shrinks onto it as `eps -> 0`, docs/models.md). An iterate in which every site slides
    /// has a Jacobian singular along the mode, so at sliding sites `J` is blended with the
    /// stick branch, `(1 - delta) J + delta I`, `delta = 1e-6`: the Newton step is then
    /// inexact by `O(delta)` (the residual, and so the solution, are unchanged).
    ///
    /// The full-system solver starts the semismooth Newton method from the regularised
    /// problem `t = P_C(-(|sigma_n| / s) u)` (`s` the model's slip threshold: regularised
    /// Coulomb of width `mu s`), solved from the stuck start with the same continuation as
    /// every regularised law ([`crate::contact::FullSystemProblem::penalty_start`]).
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `friction.law` for a site whose frames are
    /// singular or whose tangential diagonal vanishes.
    pub fn into_exact_friction(
        mut self,
        law: Arc<dyn DynNonsmoothLaw>,
    ) -> Result<Self, ContactError> {
        let invalid = |value: f64, allowed: &'static str| {
            ContactError::from(ElasticityError::InvalidParameter {
                field: "friction.law",
                value,
                allowed,
            })
        };
        let system = self.system();
        let ext = self.extended();
        let mut row_of = vec![usize::MAX; system.dimension()];
        for j in 0..self.site_count() {
            for &k in self.site_members(j) {
                row_of[self.active_node(k).tangential_row.expect("active")] = k;
            }
        }
        let mut rows_of_entry: Vec<Vec<(usize, usize)>> = vec![Vec::new(); self.active().len()];
        for (slot, (i, j)) in system.pattern.entries().enumerate() {
            if row_of[i] != usize::MAX {
                rows_of_entry[row_of[i]].push((slot, j));
            }
        }
        let mut extra: Vec<(usize, usize)> = Vec::new();
        let mut sites = Vec::with_capacity(self.site_count());
        for j in 0..self.site_count() {
            let entries = self.site_members(j).to_vec();
            let frames: Vec<[f64; 2]> =
                entries.iter().map(|&k| self.active_node(k).frame).collect();
            let inverse = match frames[..] {
                [f] => {
                    let n2 = f[0] * f[0] + f[1] * f[1];
                    if n2.is_nan() || n2 <= 0.0 {
                        return Err(invalid(n2, "contact sites with a non-degenerate frame"));
                    }
                    vec![[f[0] / n2, f[1] / n2]]
                }
                [f, g] => {
                    // F = [f g] (columns); tau = F^{-T} t: the rows of F^{-1} as columns
                    let det = f[0] * g[1] - g[0] * f[1];
                    if det.is_nan() || det.abs() <= 1e-14 * (f[0].hypot(f[1]) * g[0].hypot(g[1])) {
                        return Err(invalid(det, "contact sites with independent frames"));
                    }
                    vec![[g[1] / det, -g[0] / det], [-f[1] / det, f[0] / det]]
                }
                _ => unreachable!("a site has one or two entries"),
            };
            let mut r = 0.0;
            for &k in &entries {
                let node = self.active_node(k);
                let row = node.tangential_row.expect("active");
                let diagonal = system
                    .pattern
                    .slot(row, node.tangential_dof)
                    .map_or(0.0, |s| system.values[s].abs());
                let f = node.frame;
                r += diagonal / (node.traction_weight * (f[0] * f[0] + f[1] * f[1]));
            }
            r /= entries.len() as f64;
            if !(r.is_finite() && r > 0.0) {
                return Err(invalid(
                    r,
                    "contact rows with a nonzero tangential diagonal",
                ));
            }
            let rows: Vec<Vec<(usize, usize)>> =
                entries.iter().map(|&k| rows_of_entry[k].clone()).collect();
            let mut cross = vec![vec![Vec::new(); entries.len()]; entries.len()];
            for (e, &k) in entries.iter().enumerate() {
                let row_e = self.active_node(k).tangential_row.expect("active");
                for (f, row_f) in rows.iter().enumerate() {
                    if f != e {
                        // placeholders: indices into `extra`, mapped to slots below
                        cross[e][f] = row_f
                            .iter()
                            .map(|&(_, c)| {
                                extra.push((row_e, c));
                                extra.len() - 1
                            })
                            .collect();
                    }
                }
            }
            sites.push(ExactSite {
                entries,
                rows,
                cross,
                inverse,
                augmentation: r,
            });
        }
        let (new_ext, extra_slots) = extend_pattern(ext, &extra)?;
        for site in &mut sites {
            for row in &mut site.cross {
                for list in row {
                    for x in list.iter_mut() {
                        *x = extra_slots[*x];
                    }
                }
            }
        }
        self.set_exact(new_ext, ExactFriction { law, sites });
        Ok(self)
    }
}

/// `ext` with the entries `extra` added: the new pattern with every slot of `ext` mapped, and
/// the slots of `extra`.
fn extend_pattern(
    ext: &ExtendedPattern,
    extra: &[(usize, usize)],
) -> Result<(ExtendedPattern, Vec<usize>), ContactError> {
    if extra.is_empty() {
        return Ok((ext.clone(), Vec::new()));
    }
    let mut entries: Vec<(usize, usize)> = ext.pattern.entries().collect();
    let old = entries.len();
    entries.extend_from_slice(extra);
    let n = ext.pattern.nrows();
    let (pattern, slots) =
        SparsityPattern::from_entries(n, n, &entries).map_err(ElasticityError::from)?;
    let map = |s: usize| slots[s];
    Ok((
        ExtendedPattern {
            pattern,
            a_slot: ext.a_slot.iter().map(|&s| map(s)).collect(),
            tangential_slot: ext.tangential_slot.iter().map(|&s| map(s)).collect(),
            normal_slots: ext
                .normal_slots
                .iter()
                .map(|v| v.iter().map(|&s| map(s)).collect())
                .collect(),
            partner_slot: ext.partner_slot.iter().map(|s| s.map(map)).collect(),
        },
        slots[old..].to_vec(),
    ))
}

impl ExactFriction {
    /// The projection at site `j` for `v`, with `free[e] = q_e(v)` the free rows of its
    /// entries; `None` where the site has separated (`separated`: unilateral contact).
    fn project<D, L: FrictionLaw<f64>>(
        &self,
        model: &ContactModel<D, L>,
        j: usize,
        v: &[f64],
        free: &[f64],
        separated: Option<&[bool]>,
        penalty: Option<f64>,
    ) -> Option<SiteProjection> {
        if separated.is_some_and(|s| s[j]) {
            return None;
        }
        let site = &self.sites[j];
        let mut tau = [0.0; 2];
        let mut slip = [0.0; 2];
        for (e, &k) in site.entries.iter().enumerate() {
            let node = model.active_node(k);
            let t = free[e] / node.traction_weight;
            for c in 0..2 {
                tau[c] += site.inverse[e][c] * t;
                slip[c] += node.frame[c] * v[node.tangential_dof];
            }
        }
        let first = model.active_node(site.entries[0]);
        let sigma = first.normal_stress.dot(v);
        let (trial, d_trial_sigma) = match penalty {
            // the penalty start: t = P_C(-(|sigma_n| / width) u), regularised Coulomb
            Some(width) => {
                let k = sigma.abs() / width;
                let dk = sigma.signum() / width;
                ([-k * slip[0], -k * slip[1]], [-dk * slip[0], -dk * slip[1]])
            }
            None => {
                let r = site.augmentation;
                ([tau[0] - r * slip[0], tau[1] - r * slip[1]], [0.0; 2])
            }
        };
        let (seen, d_sigma) = match (separated, penalty) {
            // unilateral contact: a tensile node in contact carries no friction
            (Some(_), _) if sigma > 0.0 => (0.0, 0.0),
            // the bilateral penalty start takes the set of |sigma_n| (a tensile start is
            // not free to slide)
            (None, Some(_)) if sigma > 0.0 => (-sigma, -1.0),
            _ => (sigma, 1.0),
        };
        let projection = self.law.project(trial, seen).unwrap_or_else(|_| {
            // a non-finite iterate: a non-finite row, which the line search rejects
            Projection::new([f64::NAN; 2], [[0.0; 2]; 2], [0.0; 2], FrictionState::Slip)
        });
        Some(SiteProjection {
            slip,
            projection,
            d_sigma,
            d_trial_sigma,
            projection_sigma_abs: sigma.abs(),
        })
    }

    /// The free rows `q_e` of site `j` from `r = A v - b`.
    fn free_rows<D, L: FrictionLaw<f64>>(
        &self,
        model: &ContactModel<D, L>,
        j: usize,
        r: &[f64],
    ) -> [f64; 2] {
        let mut q = [0.0; 2];
        for (e, &k) in self.sites[j].entries.iter().enumerate() {
            q[e] = r[model.active_node(k).tangential_row.expect("active")];
        }
        q
    }

    /// Subtracts `w_e f_e . P` from the friction rows of `r`, which holds `A v - b` there.
    pub(crate) fn residual_into<D, L: FrictionLaw<f64>>(
        &self,
        model: &ContactModel<D, L>,
        v: &[f64],
        separated: Option<&[bool]>,
        r: &mut [f64],
        penalty: Option<f64>,
    ) {
        for j in 0..self.sites.len() {
            let q = self.free_rows(model, j, r);
            let Some(sp) = self.project(model, j, v, &q, separated, penalty) else {
                continue;
            };
            for &k in &self.sites[j].entries {
                let node = model.active_node(k);
                let t = node.frame[0] * sp.projection.traction[0]
                    + node.frame[1] * sp.projection.traction[1];
                r[node.tangential_row.expect("active")] -= node.traction_weight * t;
            }
        }
    }

    /// Adds the generalised derivative of the friction rows to `values` (which hold `A` on
    /// the extended pattern); `r` is `A v - b`.
    #[allow(clippy::needless_range_loop)] // mirrors f_e^T J F^{-T}_f
    pub(crate) fn jacobian_into<D, L: FrictionLaw<f64>>(
        &self,
        model: &ContactModel<D, L>,
        v: &[f64],
        r: &[f64],
        separated: Option<&[bool]>,
        values: &mut [f64],
        penalty: Option<f64>,
    ) {
        let a = &model.system().values;
        let ext = model.extended();
        for (j, site) in self.sites.iter().enumerate() {
            let q = self.free_rows(model, j, r);
            let Some(sp) = self.project(model, j, v, &q, separated, penalty) else {
                continue;
            };
            let mut jp = sp.projection.d_trial;
            if penalty.is_none() && sp.projection.state == FrictionState::Slip {
                // J -> (1 - delta) J + delta I at sliding sites: keeps the Jacobian regular
                // along a rigid sliding mode when an iterate has no sticking site
                let delta = SLIP_JACOBIAN_BLEND;
                for c in 0..2 {
                    for d in 0..2 {
                        jp[c][d] = (1.0 - delta) * jp[c][d] + if c == d { delta } else { 0.0 };
                    }
                }
            }
            for (e, &k) in site.entries.iter().enumerate() {
                let node = model.active_node(k);
                let (fe, we) = (node.frame, node.traction_weight);
                for (f, &kf) in site.entries.iter().enumerate() {
                    let other = model.active_node(kf);
                    // f_e^T J F^{-T}_f and f_e^T J f_f
                    let (mut m, mut s) = (0.0, 0.0);
                    for c in 0..2 {
                        for d in 0..2 {
                            m += fe[c] * jp[c][d] * site.inverse[f][d];
                            s += fe[c] * jp[c][d] * other.frame[d];
                        }
                    }
                    // the penalty start's trial does not read the traction
                    let coefficient = if penalty.is_some() {
                        0.0
                    } else {
                        we * m / other.traction_weight
                    };
                    if coefficient != 0.0 {
                        for (i, &(slot, _)) in site.rows[f].iter().enumerate() {
                            let target = if f == e {
                                ext.a_slot[slot]
                            } else {
                                site.cross[e][f][i]
                            };
                            values[target] -= coefficient * a[slot];
                        }
                    }
                    let stiffness = match penalty {
                        Some(width) => sp.projection_sigma_abs / width,
                        None => site.augmentation,
                    };
                    let stick = we * stiffness * s;
                    if f == e {
                        values[ext.tangential_slot[k]] += stick;
                    } else if let Some(slot) = ext.partner_slot[k] {
                        values[slot] += stick;
                    }
                }
                let mut dp = 0.0;
                for c in 0..2 {
                    let through_trial =
                        jp[c][0] * sp.d_trial_sigma[0] + jp[c][1] * sp.d_trial_sigma[1];
                    dp += fe[c] * (sp.projection.d_pressure[c] * sp.d_sigma + through_trial);
                }
                let w = we * dp;
                if w != 0.0 {
                    for (c, &slot) in node.normal_stress.values.iter().zip(&ext.normal_slots[k]) {
                        values[slot] -= w * c;
                    }
                }
            }
        }
    }

    /// Per site: the state of the projection (`None` where separated), the physical slip and
    /// the friction traction on the body; `r` is `A v - b`.
    pub(crate) fn site_states<D, L: FrictionLaw<f64>>(
        &self,
        model: &ContactModel<D, L>,
        v: &[f64],
        r: &[f64],
        separated: Option<&[bool]>,
    ) -> Vec<Option<SiteState>> {
        (0..self.sites.len())
            .map(|j| {
                let q = self.free_rows(model, j, r);
                self.project(model, j, v, &q, separated, None)
                    .map(|sp| (sp.projection.state, sp.slip, sp.projection.traction))
            })
            .collect()
    }

    /// The active set (stick, slip, separated) at `v`; `r` is `A v - b`.
    pub(crate) fn active_set<D, L: FrictionLaw<f64>>(
        &self,
        model: &ContactModel<D, L>,
        v: &[f64],
        r: &[f64],
        separated: Option<&[bool]>,
    ) -> ActiveSet {
        let mut set = ActiveSet::default();
        for state in self.site_states(model, v, r, separated) {
            match state.map(|s| s.0) {
                None | Some(FrictionState::Separated) => set.separated += 1,
                Some(FrictionState::Stick) => set.stick += 1,
                Some(FrictionState::Slip) => set.slip += 1,
            }
        }
        set
    }

    /// Per contact site (by [`crate::discretisation::ContactNode::site`]) where the body
    /// touches: the state for [`crate::contact::ContactProfile::state`] (`0` stick, else the
    /// sign of the `e_2` slip, `+1` when it is zero) and the friction traction on the body.
    pub(crate) fn profile<D, L: FrictionLaw<f64>>(
        &self,
        model: &ContactModel<D, L>,
        rhs: &[f64],
        v: &[f64],
    ) -> std::collections::HashMap<usize, (i8, [f64; 2])> {
        let r = model.free_residual(rhs, v);
        let separated = model.separated_sites(rhs, v);
        self.site_states(model, v, &r, separated.as_deref())
            .into_iter()
            .enumerate()
            .filter_map(|(j, s)| {
                let (state, slip, traction) = s?;
                let code = match state {
                    FrictionState::Stick => 0,
                    _ if slip[1] >= 0.0 => 1,
                    _ => -1,
                };
                let site = model.active_node(self.sites[j].entries[0]).site;
                Some((site, (code, traction)))
            })
            .collect()
    }
}
