//! The full-system contact residual and Jacobian on one process's rows of a model assembled
//! over several processes ([`ContactModel::is_distributed`]): the iterate, residual and
//! Newton update are this process's rows only, plus the ghosts its rows read (the columns of
//! its rows of `A` across the slab boundary, the displacement and normal-stress stencils of
//! its contact sites), fetched from their owners at each evaluation. Solved by
//! [`capstan_solvers::DistributedNewton`].

use std::cell::Cell;
use std::ops::Range;
use std::sync::Arc;

use capstan_friction::FrictionLaw;
use capstan_solvers::row_distribution::RowDistribution;
use capstan_solvers::{ActiveSet, OwnedRowsProblem, SolverError, SparsityPattern};

use crate::contact::loads::EndLoads;
use crate::contact::model::ContactModel;

/// One process's rows of the full-system contact problem `R(v) = 0` under fixed loads (a
/// regularised law, bilateral contact, the bulk assembled over the processes).
///
/// # Math
/// With `p` this process's rows, `g` its ghosts (the other unknowns its rows read):
/// ```text
/// R_p(v) = (A v)_p - b_p - sum_{k: row_k in p} w_k e_row_k t_k(v_{p+g})
/// dR_p/dv = A_p. - sum_{k: row_k in p} w_k e_row_k (dt_k/dv^2 e_tdof_k^T + dt_k/dsigma N_k)
/// ```
/// the same rows, in the same order of terms, as [`crate::contact::FullSystemProblem`]
/// computes on whole vectors.
pub(crate) struct OwnedContact<'a, D, L: FrictionLaw<f64>> {
    model: &'a ContactModel<D, L>,
    distribution: Arc<dyn RowDistribution>,
    block: usize,
    n: usize,
    rows: Range<usize>,
    /// The unknowns this process's rows read but do not own, increasing.
    ghosts: Vec<usize>,
    /// The contact sites with a tangential row this process owns.
    sites: Vec<usize>,
    /// This process's rows of `b`.
    rhs: Vec<f64>,
    /// The stick/slip counts (over all processes) at the last residual evaluation.
    last_set: Cell<Option<ActiveSet>>,
}

impl<'a, D, L: FrictionLaw<f64>> OwnedContact<'a, D, L> {
    /// The problem for `loads`, `None` when the model is not one it solves (one process,
    /// exact friction, unilateral contact, a matrix-free bulk) or the distribution asks for
    /// whole vectors ([`RowDistribution::newton_on_owned_rows`]).
    pub(crate) fn new(model: &'a ContactModel<D, L>, loads: EndLoads) -> Option<Self> {
        let (distribution, block) = model.row_distribution()?;
        if model.is_exact_friction()
            || model.is_unilateral()
            || model.is_matrix_free()
            || !distribution.newton_on_owned_rows()
        {
            return None;
        }
        let n = model.dof_count();
        let rows = distribution.owned(n, block);
        let owned_row = |row: Option<usize>| row.is_some_and(|r| rows.contains(&r));
        let sites: Vec<usize> = (0..model.site_count())
            .filter(|&j| {
                model
                    .site_members(j)
                    .iter()
                    .any(|&k| owned_row(model.active_node(k).tangential_row))
            })
            .collect();
        let mut ghosts = Vec::new();
        let pattern = &model.system().pattern;
        let (col_ptr, row_idx) = (pattern.col_ptr(), pattern.row_idx());
        for j in (0..n).filter(|j| !rows.contains(j)) {
            if row_idx[col_ptr[j]..col_ptr[j + 1]]
                .iter()
                .any(|i| rows.contains(i))
            {
                ghosts.push(j);
            }
        }
        for &j in &sites {
            for &k in model.site_members(j) {
                let node = model.active_node(k);
                ghosts.push(node.tangential_dof);
                ghosts.extend_from_slice(&node.normal_stress.columns);
            }
        }
        ghosts.retain(|g| !rows.contains(g));
        ghosts.sort_unstable();
        ghosts.dedup();
        let rhs = model.rhs_rows(loads, rows.clone());
        Some(Self {
            model,
            distribution,
            block,
            n,
            rows,
            ghosts,
            sites,
            rhs,
            last_set: Cell::new(None),
        })
    }

    /// The stick/slip counts (over all processes) at the last residual evaluation.
    pub(crate) fn last_set(&self) -> &Cell<Option<ActiveSet>> {
        &self.last_set
    }

    /// This process's rows of `b`.
    pub(crate) fn rhs(&self) -> &[f64] {
        &self.rhs
    }

    /// `v` (this process's rows set, the others anything) made whole on every process
    /// (collective).
    ///
    /// # Errors
    /// The gather's failure.
    pub(crate) fn gather(&self, v: &mut [f64]) -> Result<(), SolverError> {
        self.distribution.gather(v, self.block)
    }

    /// The ghost entries of the distributed vector whose rows here are `owned`.
    fn fetch_ghosts(&self, owned: &[f64]) -> Result<Vec<f64>, SolverError> {
        let mut out = vec![0.0; self.ghosts.len()];
        self.distribution
            .fetch(owned, self.n, self.block, &self.ghosts, &mut out)?;
        Ok(out)
    }

    /// `v_i` from this process's rows `owned` and the ghosts' values `ghost`.
    ///
    /// # Panics
    /// If `i` is neither owned nor a ghost (the ghost set is built from every unknown the
    /// rows read).
    #[track_caller]
    fn value(&self, owned: &[f64], ghost: &[f64], i: usize) -> f64 {
        if self.rows.contains(&i) {
            return owned[i - self.rows.start];
        }
        let g = self
            .ghosts
            .binary_search(&i)
            .expect("an unknown read by this process's rows is a ghost");
        ghost[g]
    }

    /// The stick/slip counts of the sites whose first tangential row this process owns,
    /// summed over the processes ([`ContactModel::active_set_reduced`] on owned rows).
    fn count_sites(&self, owned: &[f64], ghost: &[f64]) -> Result<ActiveSet, SolverError> {
        let model = self.model;
        let (mut stick, mut slip) = (0usize, 0usize);
        for &j in &self.sites {
            let first = model.active_node(model.site_members(j)[0]);
            if !first
                .tangential_row
                .is_some_and(|row| self.rows.contains(&row))
            {
                continue;
            }
            let u = model.site_slip(j, 1.0, |k| {
                self.value(owned, ghost, model.active_node(k).tangential_dof)
            });
            if (u[0] * u[0] + u[1] * u[1]).sqrt() < model.slip_threshold() {
                stick += 1;
            } else {
                slip += 1;
            }
        }
        let base = (model.site_count() + 1) as f64;
        let both = self.distribution.sum(stick as f64 + base * slip as f64)?;
        let slip = (both / base).floor();
        Ok(ActiveSet {
            stick: (both - slip * base) as usize,
            slip: slip as usize,
            separated: 0,
        })
    }

    /// The law at site `j` for the displacement given by this process's rows and ghosts.
    fn traction(&self, j: usize, owned: &[f64], ghost: &[f64]) -> crate::contact::SiteTraction {
        let model = self.model;
        let first = model.active_node(model.site_members(j)[0]);
        let slip = model.site_slip(j, 1.0, |k| {
            self.value(owned, ghost, model.active_node(k).tangential_dof)
        });
        let sigma = first
            .normal_stress
            .columns
            .iter()
            .zip(&first.normal_stress.values)
            .map(|(&c, &a)| a * self.value(owned, ghost, c))
            .sum();
        model.site_traction_at_slip(j, slip, sigma)
    }
}

impl<D, L: FrictionLaw<f64>> OwnedRowsProblem for OwnedContact<'_, D, L> {
    fn distribution(&self) -> &dyn RowDistribution {
        &*self.distribution
    }

    fn rows(&self) -> Range<usize> {
        self.rows.clone()
    }

    fn pattern(&self) -> &SparsityPattern {
        &self.model.extended().pattern
    }

    fn residual_owned(&self, u: &[f64], r: &mut [f64]) -> Result<(), SolverError> {
        let ghost = self.fetch_ghosts(u)?;
        let system = self.model.system();
        let pattern = &system.pattern;
        let (col_ptr, row_idx) = (pattern.col_ptr(), pattern.row_idx());
        let first = self.rows.start;
        r.iter_mut().for_each(|x| *x = 0.0);
        // (A v)_p column by column, as the whole matvec; the ghost columns in increasing order
        let mut g = 0;
        for j in 0..self.n {
            let (a, b) = (col_ptr[j], col_ptr[j + 1]);
            if a == b {
                continue;
            }
            let xj = if self.rows.contains(&j) {
                u[j - first]
            } else {
                while g < self.ghosts.len() && self.ghosts[g] < j {
                    g += 1;
                }
                if g < self.ghosts.len() && self.ghosts[g] == j {
                    ghost[g]
                } else {
                    continue; // no entry in this process's rows
                }
            };
            for (&i, &a_ij) in row_idx[a..b].iter().zip(&system.values[a..b]) {
                if self.rows.contains(&i) {
                    r[i - first] += a_ij * xj;
                }
            }
        }
        for (ri, bi) in r.iter_mut().zip(&self.rhs) {
            *ri -= bi;
        }
        for &j in &self.sites {
            let st = self.traction(j, u, &ghost);
            for (e, &k) in self.model.site_members(j).iter().enumerate() {
                let node = self.model.active_node(k);
                let row = node.tangential_row.expect("active nodes have a row");
                if self.rows.contains(&row) {
                    r[row - first] -= node.traction_weight * st.covariant[e];
                }
            }
        }
        self.last_set.set(Some(self.count_sites(u, &ghost)?));
        Ok(())
    }

    fn jacobian_owned(&self, u: &[f64], values: &mut [f64]) -> Result<(), SolverError> {
        let ghost = self.fetch_ghosts(u)?;
        let model = self.model;
        let ext = model.extended();
        values.iter_mut().for_each(|x| *x = 0.0);
        for (k, &a) in model.system().values.iter().enumerate() {
            values[ext.a_slot[k]] += a;
        }
        for &j in &self.sites {
            let st = self.traction(j, u, &ghost);
            for (e, &k) in model.site_members(j).iter().enumerate() {
                let node = model.active_node(k);
                let w = node.traction_weight;
                values[ext.tangential_slot[k]] -= w * st.d_tangential[e][e];
                if let Some(slot) = ext.partner_slot[k] {
                    values[slot] -= w * st.d_tangential[e][1 - e];
                }
                for (c, &slot) in node.normal_stress.values.iter().zip(&ext.normal_slots[k]) {
                    values[slot] -= w * st.d_normal_stress[e] * c;
                }
            }
        }
        Ok(())
    }
}
