//! Exact (nonsmooth) Coulomb friction on the thick body: the friction rows of the full
//! system written as the Alart–Curnier projection, solved by the full-system (semismooth)
//! Newton method. Plane strain (one tangential entry per site) and 3-D (the friction disc
//! or ellipse, a two-component slip).

use std::sync::Arc;

use capstan_friction::nonsmooth_law::DynNonsmoothLaw;
use capstan_friction::{FrictionState, Projection};
use capstan_solvers::{ActiveSet, SparsityPattern};

use crate::contact::error::ContactError;
use crate::contact::pattern::ExtendedPattern;
use crate::discretisation::{ContactNode, LinearSystem};
use crate::error::ElasticityError;

/// The blend `delta` of the stick branch into the generalised Jacobian of a sliding site
/// (see [`crate::contact::ContactModel::into_exact_friction`]).
pub(crate) const SLIP_JACOBIAN_BLEND: f64 = 1e-6;

/// What exact friction reads of a contact model: its contact entries, bulk system and
/// extended pattern.
pub(crate) trait ContactRows {
    /// The active contact entry `k`.
    fn node(&self, k: usize) -> &ContactNode;
    /// The bulk system `A`.
    fn bulk(&self) -> &LinearSystem;
    /// The extended pattern of the full-system Jacobian.
    fn pattern(&self) -> &ExtendedPattern;
    /// The slip reference of unknown `dof` (a load path's previous state; zero from rest).
    fn reference(&self, dof: usize) -> f64;
}

/// The state of a site after the projection, its physical slip and friction traction.
type SiteState = (FrictionState, [f64; 2], [f64; 2]);

/// One contact site under exact friction: its entries, their rows of `A` and the data of the
/// projection.
#[derive(Debug, Clone)]
struct ExactSite {
    /// Active entries (indices into `ContactModel::active`).
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
/// set) and the per-site data. See [`crate::contact::ContactModel::into_exact_friction`].
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

impl ExactFriction {
    /// The exact friction `law` on the contact sites `members` (active entries per site, of
    /// `active` in all) of `rows`, with the extended pattern it needs (`None`: the pattern of
    /// `rows` as it is, when no site has two entries; see
    /// [`crate::contact::ContactModel::into_exact_friction`](crate::contact::ContactModel::into_exact_friction)).
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `friction.law` for a site whose frames are
    /// singular or whose tangential diagonal vanishes.
    pub(crate) fn build(
        rows: &dyn ContactRows,
        members: &[Vec<usize>],
        active: usize,
        law: Arc<dyn DynNonsmoothLaw>,
    ) -> Result<(Self, Option<ExtendedPattern>), ContactError> {
        let invalid = |value: f64, allowed: &'static str| {
            ContactError::from(ElasticityError::InvalidParameter {
                field: "friction.law",
                value,
                allowed,
            })
        };
        let system = rows.bulk();
        let ext = rows.pattern();
        let mut row_of = vec![usize::MAX; system.dimension()];
        for site in members {
            for &k in site {
                row_of[rows.node(k).tangential_row.expect("active")] = k;
            }
        }
        let mut rows_of_entry: Vec<Vec<(usize, usize)>> = vec![Vec::new(); active];
        for (slot, (i, j)) in system.pattern.entries().enumerate() {
            if row_of[i] != usize::MAX {
                rows_of_entry[row_of[i]].push((slot, j));
            }
        }
        let mut extra: Vec<(usize, usize)> = Vec::new();
        let mut sites = Vec::with_capacity(members.len());
        for site in members {
            let entries = site.clone();
            let frames: Vec<[f64; 2]> = entries.iter().map(|&k| rows.node(k).frame).collect();
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
                let node = rows.node(k);
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
            let entry_rows: Vec<Vec<(usize, usize)>> =
                entries.iter().map(|&k| rows_of_entry[k].clone()).collect();
            let mut cross = vec![vec![Vec::new(); entries.len()]; entries.len()];
            for (e, &k) in entries.iter().enumerate() {
                let row_e = rows.node(k).tangential_row.expect("active");
                for (f, row_f) in entry_rows.iter().enumerate() {
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
                rows: entry_rows,
                cross,
                inverse,
                augmentation: r,
            });
        }
        // one-entry sites (2-D) couple no entries: the pattern stays (no copy of it)
        let (new_ext, extra_slots) = if extra.is_empty() {
            (None, Vec::new())
        } else {
            let (new_ext, slots) = extend_pattern(ext, &extra)?;
            (Some(new_ext), slots)
        };
        for site in &mut sites {
            for row in &mut site.cross {
                for list in row {
                    for x in list.iter_mut() {
                        *x = extra_slots[*x];
                    }
                }
            }
        }
        Ok((ExactFriction { law, sites }, new_ext))
    }
}

/// `ext` with the entries `extra` added: the new pattern with every slot of `ext` mapped, and
/// the slots of `extra`.
fn extend_pattern(
    ext: &ExtendedPattern,
    extra: &[(usize, usize)],
) -> Result<(ExtendedPattern, Vec<usize>), ContactError> {
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
    /// The bound law (the projection onto the friction set).
    pub(crate) fn law(&self) -> &dyn DynNonsmoothLaw {
        self.law.as_ref()
    }

    /// Site `j`'s columns of `F^{-T}` (`tau = sum_e inverse[e] t_e`) and its augmentation `r`.
    pub(crate) fn site_data(&self, j: usize) -> (&[[f64; 2]], f64) {
        let site = &self.sites[j];
        (&site.inverse, site.augmentation)
    }
}

impl ExactFriction {
    /// The projection at site `j` for `v`, with `free[e] = q_e(v)` the free rows of its
    /// entries; `None` where the site has separated (`separated`: unilateral contact).
    fn project(
        &self,
        rows: &dyn ContactRows,
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
            let node = rows.node(k);
            let t = free[e] / node.traction_weight;
            // the slip increment over a load-path step (from rest: the displacement)
            let increment_from = rows.reference(node.tangential_dof);
            for c in 0..2 {
                tau[c] += site.inverse[e][c] * t;
                slip[c] += node.frame[c] * (v[node.tangential_dof] - increment_from);
            }
        }
        let first = rows.node(site.entries[0]);
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
    fn free_rows(&self, rows: &dyn ContactRows, j: usize, r: &[f64]) -> [f64; 2] {
        let mut q = [0.0; 2];
        for (e, &k) in self.sites[j].entries.iter().enumerate() {
            q[e] = r[rows.node(k).tangential_row.expect("active")];
        }
        q
    }

    /// Subtracts `w_e f_e . P` from the friction rows of `r`, which holds `A v - b` there.
    pub(crate) fn residual_into(
        &self,
        rows: &dyn ContactRows,
        v: &[f64],
        separated: Option<&[bool]>,
        r: &mut [f64],
        penalty: Option<f64>,
    ) {
        for j in 0..self.sites.len() {
            let q = self.free_rows(rows, j, r);
            let Some(sp) = self.project(rows, j, v, &q, separated, penalty) else {
                continue;
            };
            for &k in &self.sites[j].entries {
                let node = rows.node(k);
                let t = node.frame[0] * sp.projection.traction[0]
                    + node.frame[1] * sp.projection.traction[1];
                r[node.tangential_row.expect("active")] -= node.traction_weight * t;
            }
        }
    }

    /// Adds the generalised derivative of the friction rows to `values` (which hold `A` on
    /// the extended pattern); `r` is `A v - b`.
    #[allow(clippy::needless_range_loop)] // mirrors f_e^T J F^{-T}_f
    pub(crate) fn jacobian_into(
        &self,
        rows: &dyn ContactRows,
        v: &[f64],
        r: &[f64],
        separated: Option<&[bool]>,
        values: &mut [f64],
        penalty: Option<f64>,
    ) {
        let a = &rows.bulk().values;
        let ext = rows.pattern();
        for (j, site) in self.sites.iter().enumerate() {
            let q = self.free_rows(rows, j, r);
            let Some(sp) = self.project(rows, j, v, &q, separated, penalty) else {
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
                let node = rows.node(k);
                let (fe, we) = (node.frame, node.traction_weight);
                for (f, &kf) in site.entries.iter().enumerate() {
                    let other = rows.node(kf);
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
    pub(crate) fn site_states(
        &self,
        rows: &dyn ContactRows,
        v: &[f64],
        r: &[f64],
        separated: Option<&[bool]>,
    ) -> Vec<Option<SiteState>> {
        (0..self.sites.len())
            .map(|j| {
                let q = self.free_rows(rows, j, r);
                self.project(rows, j, v, &q, separated, None)
                    .map(|sp| (sp.projection.state, sp.slip, sp.projection.traction))
            })
            .collect()
    }

    /// The active set (stick, slip, separated) at `v`; `r` is `A v - b`.
    pub(crate) fn active_set(
        &self,
        rows: &dyn ContactRows,
        v: &[f64],
        r: &[f64],
        separated: Option<&[bool]>,
    ) -> ActiveSet {
        let mut set = ActiveSet::default();
        for state in self.site_states(rows, v, r, separated) {
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
    /// sign of the `e_2` slip, `+1` when it is zero) and the friction traction on the body;
    /// `r` is `A v - b`.
    pub(crate) fn profile(
        &self,
        rows: &dyn ContactRows,
        v: &[f64],
        r: &[f64],
        separated: Option<&[bool]>,
    ) -> std::collections::HashMap<usize, (i8, [f64; 2])> {
        self.site_states(rows, v, r, separated)
            .into_iter()
            .enumerate()
            .filter_map(|(j, s)| {
                let (state, slip, traction) = s?;
                let code = match state {
                    FrictionState::Stick => 0,
                    _ if slip[1] >= 0.0 => 1,
                    _ => -1,
                };
                let site = rows.node(self.sites[j].entries[0]).site;
                Some((site, (code, traction)))
            })
            .collect()
    }
}
