//! The friction law on the contact rows of a [`ContactModel`]: the traction at each contact
//! site, the full residual and its Jacobian on the extended pattern.

use capstan_friction::{ContactState, FrictionLaw};
use capstan_solvers::SolverError;

use super::{ContactModel, SiteTraction};
use crate::contact::exact_friction::ContactRows;
use crate::contact::loads::EndLoads;
use crate::contact::pattern::ExtendedPattern;
use crate::discretisation::{ContactNode, LinearSystem};

impl<D, L: FrictionLaw<f64>> ContactModel<D, L> {
    /// Number of contact sites with friction (contact nodes with a free tangential row).
    pub fn site_count(&self) -> usize {
        self.sites.members.len()
    }

    /// The active entries (indices into [`ContactModel::active`]) of site `j`.
    #[track_caller]
    pub fn site_members(&self, j: usize) -> &[usize] {
        &self.sites.members[j]
    }

    /// The law at site `j` for the physical slip `slip` and normal stress `normal_stress`
    /// (see [`SiteTraction`]; `slip` is taken as given).
    #[track_caller]
    pub fn site_traction_at_slip(
        &self,
        j: usize,
        slip: [f64; 2],
        normal_stress: f64,
    ) -> SiteTraction {
        let members = &self.sites.members[j];
        match members[..] {
            [a] => self.entries_traction(&[self.active_node(a)], slip, normal_stress),
            [a, b] => self.entries_traction(
                &[self.active_node(a), self.active_node(b)],
                slip,
                normal_stress,
            ),
            _ => unreachable!("a site has one or two entries"),
        }
    }

    /// The law for the contact `entries` of one site (one or two) at the physical slip
    /// `slip` and normal stress `normal_stress`.
    #[allow(clippy::needless_range_loop)] // mirrors frame_e^T (d tau / d u) frame_f
    pub(crate) fn entries_traction(
        &self,
        entries: &[&ContactNode],
        slip: [f64; 2],
        normal_stress: f64,
    ) -> SiteTraction {
        let state = ContactState::new(slip, normal_stress);
        let traction = self.law.traction(&state, &self.params);
        let d = self.law.traction_derivatives(&state, &self.params);
        let mut out = SiteTraction {
            slip,
            normal_stress,
            traction,
            covariant: [0.0; 2],
            d_tangential: [[0.0; 2]; 2],
            d_normal_stress: [0.0; 2],
        };
        // zero frame components are skipped: plane strain reduces exactly to
        // t_2 = sqrt(g22) t, d t_2/d v^2 = (sqrt(g22) sqrt(g22)) dt/du, d t_2/d sigma = sqrt(g22) dt/dp
        for (e, entry) in entries.iter().enumerate() {
            let fe = entry.frame;
            let mut t = 0.0;
            let mut dn = 0.0;
            for c in 0..2 {
                if fe[c] != 0.0 {
                    t += fe[c] * traction[c];
                    dn += fe[c] * d.d_pressure[c];
                }
            }
            out.covariant[e] = t;
            out.d_normal_stress[e] = dn;
            for (f, other) in entries.iter().enumerate() {
                let ff = other.frame;
                let mut dt = 0.0;
                for c in 0..2 {
                    for cc in 0..2 {
                        if fe[c] != 0.0 && ff[cc] != 0.0 {
                            dt += fe[c] * ff[cc] * d.d_slip[c][cc];
                        }
                    }
                }
                out.d_tangential[e][f] = dt;
            }
        }
        out
    }

    /// The law at site `j` for the displacement `v`.
    #[track_caller]
    pub fn site_traction(&self, j: usize, v: &[f64]) -> SiteTraction {
        let first = self.active_node(self.sites.members[j][0]);
        let slip = self.site_slip(j, 1.0, |k| v[self.active_node(k).tangential_dof]);
        self.site_traction_at_slip(j, slip, first.normal_stress.dot(v))
    }

    /// The full residual `R(v) = A v - b(tau) - sum_k w_k e_row t_k(v)` (on a model
    /// assembled over several processes, [`ContactModel::is_distributed`], each process
    /// evaluates its rows and gathers the others: collective).
    ///
    /// # Errors
    /// The gather's failure (only on a distributed model: [`SolverError::External`] of the
    /// engine).
    ///
    /// # Panics
    /// If `v`, `rhs` or `r` have the wrong length.
    #[track_caller]
    pub fn residual_into(&self, rhs: &[f64], v: &[f64], r: &mut [f64]) -> Result<(), SolverError> {
        self.residual_with(rhs, v, r, None)
    }

    /// [`ContactModel::residual_into`]; exact friction in its penalty start when `penalty`
    /// is set ([`crate::contact::FullSystemProblem::penalty_start`]).
    pub(crate) fn residual_with(
        &self,
        rhs: &[f64],
        v: &[f64],
        r: &mut [f64],
        penalty: Option<f64>,
    ) -> Result<(), SolverError> {
        self.system.pattern.matvec(&self.system.values, v, r);
        if let Some(bulk) = &self.bulk {
            // the bulk operator by its action (the assembled pattern is empty)
            let mut av = vec![0.0; r.len()];
            bulk.bulk().apply(v, &mut av);
            r.iter_mut().zip(&av).for_each(|(ri, a)| *ri += a);
        }
        for (ri, bi) in r.iter_mut().zip(rhs) {
            *ri -= bi;
        }
        let contact = self.unilateral.as_ref().map(|u| u.contact_set(v, rhs));
        if let Some(x) = &self.exact {
            x.residual_into(self, v, self.separated_sites(rhs, v).as_deref(), r, penalty);
        }
        let owned = self.owned_rows(r.len());
        for (j, members) in self.sites.members.iter().enumerate() {
            if !self.site_has_row_in(j, owned.as_ref()) {
                // another process's rows: its owner computes them, the gather brings them
                continue;
            }
            let Some((st, _)) = self
                .site_traction_in_contact(j, v, rhs, contact.as_deref())
                .filter(|_| self.exact.is_none())
            else {
                continue;
            };
            for (e, &k) in members.iter().enumerate() {
                let node = self.active_node(k);
                let row = node.tangential_row.expect("active nodes have a row");
                r[row] -= node.traction_weight * st.covariant[e];
            }
        }
        if let Some(u) = &self.unilateral {
            u.residual_into(v, rhs, r);
        }
        if let Some((d, block)) = &self.distribution {
            // this process's rows are right; the others come from their owners
            d.gather(r, *block)?;
        }
        Ok(())
    }

    /// This process's rows among `n` on a model assembled over several processes
    /// ([`ContactModel::is_distributed`]); `None`: all rows are this process's.
    pub(crate) fn owned_rows(&self, n: usize) -> Option<core::ops::Range<usize>> {
        self.distribution
            .as_ref()
            .map(|(d, block)| d.owned(n, *block))
    }

    /// Whether a tangential row of site `j` lies in `owned` (`None`: every site's does):
    /// the sites whose friction terms this process computes.
    fn site_has_row_in(&self, j: usize, owned: Option<&core::ops::Range<usize>>) -> bool {
        owned.is_none_or(|rows| {
            self.sites.members[j].iter().any(|&k| {
                self.active_node(k)
                    .tangential_row
                    .is_some_and(|row| rows.contains(&row))
            })
        })
    }

    /// [`ContactModel::active_set`] with each process counting only the sites whose first
    /// tangential row it owns and the counts summed over the processes
    /// ([`capstan_solvers::row_distribution::RowDistribution::sum`]: collective), on a
    /// distributed model with a regularised law; otherwise [`ContactModel::active_set`]
    /// itself (exact friction reads the free residual of the whole face).
    ///
    /// # Math
    /// ```text
    /// n_stick = sum_p #{ j owned by p : |u_j| <  eps },   n_slip likewise with |u_j| >= eps
    /// ```
    ///
    /// # Errors
    /// The reduction's failure ([`SolverError::External`] of the engine).
    pub fn active_set_reduced(
        &self,
        rhs: &[f64],
        v: &[f64],
    ) -> Result<capstan_solvers::ActiveSet, SolverError> {
        let Some((d, block)) = self
            .distribution
            .as_ref()
            .filter(|_| self.exact.is_none() && self.unilateral.is_none())
        else {
            return Ok(self.active_set(rhs, v));
        };
        let rows = d.owned(v.len(), *block);
        let (mut stick, mut slip) = (0usize, 0usize);
        for j in 0..self.sites.members.len() {
            let first = self.active_node(self.sites.members[j][0]);
            if !first.tangential_row.is_some_and(|row| rows.contains(&row)) {
                continue;
            }
            let u = self.site_slip(j, 1.0, |k| v[self.active_node(k).tangential_dof]);
            if (u[0] * u[0] + u[1] * u[1]).sqrt() < self.slip_threshold {
                stick += 1;
            } else {
                slip += 1;
            }
        }
        // counts below 2^53 are exact in f64; one reduction for both (slip in units of the
        // number of sites + 1)
        let base = (self.sites.members.len() + 1) as f64;
        let both = d.sum(stick as f64 + base * slip as f64)?;
        let slip = (both / base).floor();
        Ok(capstan_solvers::ActiveSet {
            stick: (both - slip * base) as usize,
            slip: slip as usize,
            separated: 0,
        })
    }

    /// The law at site `j` for `v` where the site is in contact: `None` where it has
    /// separated (unilateral contact, `contact` the contact set of the normal rows); the
    /// normal stress seen by the law is `min(sigma_n, 0)` under unilateral contact (its
    /// derivative zero where `sigma_n > 0`), capped by the contact reaction
    /// ([`ContactModel::friction_normal_stress`]; with the capping row, whose reaction the
    /// Jacobian then differentiates).
    fn site_traction_in_contact(
        &self,
        j: usize,
        v: &[f64],
        rhs: &[f64],
        contact: Option<&[bool]>,
    ) -> Option<(SiteTraction, Option<usize>)> {
        let (Some(contact), Some(u)) = (contact, &self.unilateral) else {
            return Some((self.site_traction(j, v), None));
        };
        if let Some(row) = u.site_row[j]
            && !contact[row]
        {
            return None;
        }
        let first = self.active_node(self.sites.members[j][0]);
        let slip = self.site_slip(j, 1.0, |k| v[self.active_node(k).tangential_dof]);
        let (pressure, capped) = self.friction_normal_stress(j, v, rhs);
        let mut st = self.site_traction_at_slip(j, slip, pressure);
        if capped.is_none() && first.normal_stress.dot(v) > 0.0 {
            st.d_normal_stress = [0.0; 2];
        }
        Some((st, capped))
    }

    /// The normal stress the friction law reads at site `j` under unilateral contact,
    /// `max(min(sigma_n, 0), -cap)` with the reaction cap of
    /// [`crate::contact::unilateral::FRICTION_PRESSURE_CAP`], and the site's normal row when
    /// the cap is the one that holds (`None`: `min(sigma_n, 0)`; also on a bilateral model,
    /// where it is `sigma_n` itself).
    pub(crate) fn friction_normal_stress(
        &self,
        j: usize,
        v: &[f64],
        rhs: &[f64],
    ) -> (f64, Option<usize>) {
        let first = self.active_node(self.sites.members[j][0]);
        let sigma = first.normal_stress.dot(v);
        let Some(u) = &self.unilateral else {
            return (sigma, None);
        };
        let pressure = sigma.min(0.0);
        match u.site_row[j] {
            Some(row) => {
                let cap = u.rows[row]
                    .friction_cap(v, rhs, first.traction_weight)
                    .max(0.0);
                if -pressure > cap {
                    (-cap, Some(row))
                } else {
                    (pressure, None)
                }
            }
            None => (pressure, None),
        }
    }

    /// `max_i |R(v)_i| / max(1, max_i |b_i|)`.
    ///
    /// # Errors
    /// As [`ContactModel::residual_into`].
    pub fn relative_residual(&self, loads: EndLoads, v: &[f64]) -> Result<f64, SolverError> {
        let rhs = self.rhs(loads);
        let mut r = vec![0.0; v.len()];
        self.residual_into(&rhs, v, &mut r)?;
        let b = rhs.iter().fold(0.0f64, |m, x| m.max(x.abs())).max(1.0);
        Ok(r.iter().fold(0.0f64, |m, x| m.max(x.abs())) / b)
    }

    /// Values of the full Jacobian `dR/dv` on the extended pattern, for the loads'
    /// right-hand side `rhs` (which the unilateral rows read).
    ///
    /// # Panics
    /// If `v` or `values` have the wrong length.
    #[track_caller]
    /// Exact friction in its penalty start when `penalty` is set (see
    /// [`ContactModel::residual_with`]).
    pub(crate) fn jacobian_with(
        &self,
        rhs: &[f64],
        v: &[f64],
        values: &mut [f64],
        penalty: Option<f64>,
    ) {
        values.iter_mut().for_each(|x| *x = 0.0);
        for (k, &a) in self.system.values.iter().enumerate() {
            values[self.ext.a_slot[k]] += a;
        }
        let contact = self.unilateral.as_ref().map(|u| u.contact_set(v, rhs));
        if let Some(u) = &self.unilateral {
            u.jacobian_into(v, rhs, &self.ext.a_slot, values);
        }
        if let Some(x) = &self.exact {
            let r = self.free_residual(rhs, v);
            let separated = self.separated_sites(rhs, v);
            x.jacobian_into(self, v, &r, separated.as_deref(), values, penalty);
            return;
        }
        let owned = self.owned_rows(v.len());
        for (j, members) in self.sites.members.iter().enumerate() {
            if !self.site_has_row_in(j, owned.as_ref()) {
                // rows another process inserts into the distributed matrix
                continue;
            }
            let Some((st, capped)) = self.site_traction_in_contact(j, v, rhs, contact.as_deref())
            else {
                continue;
            };
            let first_weight = self.active_node(members[0]).traction_weight;
            for (e, &k) in members.iter().enumerate() {
                let node = self.active_node(k);
                let w = node.traction_weight;
                values[self.ext.tangential_slot[k]] -= w * st.d_tangential[e][e];
                if let Some(slot) = self.ext.partner_slot[k] {
                    values[slot] -= w * st.d_tangential[e][1 - e];
                }
                if let (Some(row), Some(u)) = (capped, &self.unilateral) {
                    // the law reads -cap: d t / d v = -(dt/dsigma) d cap / d v
                    let tangential = node.tangential_row.expect("active nodes have a row");
                    for (c, g) in u.rows[row].friction_cap_gradient(first_weight) {
                        if let Some(slot) = self.ext.pattern.slot(tangential, c) {
                            values[slot] += w * st.d_normal_stress[e] * g;
                        }
                    }
                    continue;
                }
                for (c, &slot) in node
                    .normal_stress
                    .values
                    .iter()
                    .zip(&self.ext.normal_slots[k])
                {
                    values[slot] -= w * st.d_normal_stress[e] * c;
                }
            }
        }
    }
}

impl<D, L: FrictionLaw<f64>> ContactRows for ContactModel<D, L> {
    fn node(&self, k: usize) -> &ContactNode {
        self.active_node(k)
    }
    fn bulk(&self) -> &LinearSystem {
        &self.system
    }
    fn pattern(&self) -> &ExtendedPattern {
        &self.ext
    }
    fn reference(&self, dof: usize) -> f64 {
        self.reference_of(dof)
    }
}
