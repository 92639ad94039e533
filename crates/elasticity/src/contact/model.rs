//! The frictional contact model: a linear bulk operator, end loads, and a pointwise friction
//! law on the contact rows of any [`Discretisation`].

use capstan_friction::{ContactState, FrictionLaw};
use capstan_solvers::SparsityPattern;

use crate::contact::error::ContactError;
use crate::discretisation::{ContactNode, Discretisation, LinearSystem};

/// End tractions `T^2_2 = tau0` at `x2 = theta0` and `T^2_2 = tau_max` at `x2 = theta1`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct EndLoads {
    /// `tau0` (the paper's minimum traction).
    pub tau0: f64,
    /// `tau_max`.
    pub tau_max: f64,
}

impl EndLoads {
    /// The loads `(tau0, tau_max)`.
    pub fn new(tau0: f64, tau_max: f64) -> Self {
        Self { tau0, tau_max }
    }

    /// `tau0 = 1`, `tau_max = ratio`.
    pub fn ratio(ratio: f64) -> Self {
        Self::new(1.0, ratio)
    }

    /// `tau_max / tau0`.
    pub fn tension_ratio(&self) -> f64 {
        self.tau_max / self.tau0
    }

    /// Both loads times `s`.
    pub fn scaled(&self, s: f64) -> Self {
        Self::new(s * self.tau0, s * self.tau_max)
    }

    /// `max(|tau0|, |tau_max|)`.
    pub fn magnitude(&self) -> f64 {
        self.tau0.abs().max(self.tau_max.abs())
    }

    pub(crate) fn check(&self) -> Result<(), ContactError> {
        for (field, value) in [("loads.tau0", self.tau0), ("loads.tau_max", self.tau_max)] {
            if !value.is_finite() {
                return Err(ContactError::InvalidParameter {
                    field,
                    value,
                    allowed: "finite values",
                });
            }
        }
        Ok(())
    }
}

/// The friction law's traction on one contact node and its derivatives, in the covariant
/// component `t_2` that enters the discrete balance rows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodeTraction {
    /// Physical tangential slip `u = sqrt(g_22) v^2`.
    pub slip: f64,
    /// `sigma_n = T^3_3` (negative in compression).
    pub normal_stress: f64,
    /// Covariant traction `t_2 = sqrt(g_22) t_phys`.
    pub t2: f64,
    /// `d t_2 / d v^2`.
    pub d_tangential: f64,
    /// `d t_2 / d sigma_n`.
    pub d_normal_stress: f64,
}

/// The extended sparsity pattern: `A` plus every friction entry of the contact rows.
#[derive(Debug, Clone)]
pub(crate) struct ExtendedPattern {
    pub pattern: SparsityPattern,
    /// Slot in `pattern` of slot `k` of `A`.
    pub a_slot: Vec<usize>,
    /// Slot of `(tangential_row, tangential_dof)` per active node.
    pub tangential_slot: Vec<usize>,
    /// Slots of `(tangential_row, normal_stress.columns[..])` per active node.
    pub normal_slots: Vec<Vec<usize>>,
}

/// A frictional contact problem on a discretised thick body.
///
/// # Math
/// The bulk operator is linear; the friction law acts only on the tangential balance rows of
/// the contact nodes (see [`ContactNode`]):
/// ```text
/// R(v) = A v - b(tau) - sum_k w_k e_{row_k} t_2,k(v) = 0
/// t_2,k = sqrt(g_22) t(u_k, sigma_k)      u_k = sqrt(g_22) v^2_k,  sigma_k = T^3_3(v) at node k
/// b(tau) = tau0 b_0 + tau_max b_1          (b linear in the end loads)
/// ```
/// `t(u, sigma)` is the physical traction on the body from the [`FrictionLaw`], evaluated with
/// slip `(0, u)` (the `x1` slip of plane strain is zero) and normal stress `sigma = T^3_3`
/// (unit outward normal `n = -g^3` on `x3 = 0`, so `n.T.n = T^3_3`; negative in compression).
/// For regularised Coulomb `t = mu sigma u / max(|u|, eps)`: opposite to the slip when `sigma < 0`.
///
/// The model is built from two discretisations of the same body with unit end loads
/// `(1, 0)` and `(0, 1)`; it checks they share one bulk operator `A`, which is what lets the
/// condensed solver ([`crate::contact::BoundarySolver`]) handle every tension ratio with two
/// bulk solves.
pub struct ContactModel<D, L: FrictionLaw<f64>> {
    /// Shared by the models of [`ContactModel::with_params`].
    disc: std::sync::Arc<D>,
    law: L,
    params: L::Params,
    slip_threshold: f64,
    system: LinearSystem,
    rhs_basis: [Vec<f64>; 2],
    nodes: Vec<ContactNode>,
    active: Vec<usize>,
    ext: ExtendedPattern,
}

impl<D, L: FrictionLaw<f64>> core::fmt::Debug for ContactModel<D, L> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("ContactModel")
            .field("dofs", &self.system.dimension())
            .field("contact_nodes", &self.nodes.len())
            .field("active", &self.active.len())
            .field("params", &self.params)
            .finish_non_exhaustive()
    }
}

impl<D: Discretisation, L: FrictionLaw<f64>> ContactModel<D, L> {
    /// Builds the model from `build(tau0, tau_max)`, which returns the discretisation of the
    /// body with those end loads and zero tangential traction on `x3 = 0`.
    ///
    /// `slip_threshold` classifies stick and slip (the regularisation width `eps` for
    /// regularised Coulomb).
    ///
    /// # Errors
    /// Errors of `build`; [`ContactError::InconsistentLoads`] if the two unit-load operators
    /// differ; [`ContactError::NoContactNodes`]; [`ContactError::InvalidParameter`] for a
    /// non-positive `slip_threshold`.
    pub fn new(
        build: impl Fn(f64, f64) -> Result<D, crate::error::ElasticityError>,
        law: L,
        params: L::Params,
        slip_threshold: f64,
    ) -> Result<Self, ContactError> {
        if !(slip_threshold.is_finite() && slip_threshold > 0.0) {
            return Err(ContactError::InvalidParameter {
                field: "friction.eps",
                value: slip_threshold,
                allowed: "(0, inf)",
            });
        }
        let disc = build(1.0, 0.0)?;
        let other = build(0.0, 1.0)?;
        let system = disc.system()?;
        let system1 = other.system()?;
        if system1.pattern != system.pattern || system1.values.len() != system.values.len() {
            return Err(ContactError::InconsistentLoads {
                what: "sparsity pattern",
            });
        }
        let scale = system
            .values
            .iter()
            .fold(0.0f64, |m, x| m.max(x.abs()))
            .max(f64::MIN_POSITIVE);
        if system
            .values
            .iter()
            .zip(&system1.values)
            .any(|(a, b)| (a - b).abs() > 1e-12 * scale)
        {
            return Err(ContactError::InconsistentLoads {
                what: "matrix values",
            });
        }
        let rhs_basis = [system.rhs.clone(), system1.rhs];
        let nodes = disc.contact_nodes()?;
        let active: Vec<usize> = (0..nodes.len())
            .filter(|&k| nodes[k].tangential_row.is_some())
            .collect();
        if active.is_empty() {
            return Err(ContactError::NoContactNodes);
        }
        let ext = extended_pattern(&system.pattern, &nodes, &active)?;
        Ok(Self {
            disc: std::sync::Arc::new(disc),
            law,
            params,
            slip_threshold,
            system,
            rhs_basis,
            nodes,
            active,
            ext,
        })
    }
}

impl<D, L: FrictionLaw<f64>> ContactModel<D, L> {
    /// The same body and contact surface with other parameters of the law (`mu`, `eps`; the
    /// stick/slip threshold is kept): nothing is assembled again (the discretisation is shared, the assembled operator
    /// copied). Its [`crate::contact::BoundarySolver`] can reuse this model's factorisation
    /// ([`crate::contact::BoundarySolver::with_model`]).
    pub fn with_params(&self, params: L::Params) -> Self
    where
        L: Clone,
    {
        Self {
            disc: std::sync::Arc::clone(&self.disc),
            law: self.law.clone(),
            params,
            slip_threshold: self.slip_threshold,
            system: self.system.clone(),
            rhs_basis: self.rhs_basis.clone(),
            nodes: self.nodes.clone(),
            active: self.active.clone(),
            ext: self.ext.clone(),
        }
    }

    /// The discretisation (built with unit load `tau0 = 1`, `tau_max = 0`; only its operator,
    /// numbering, contact rows and field evaluation are used).
    pub fn discretisation(&self) -> &D {
        &self.disc
    }

    /// The friction law.
    pub fn law(&self) -> &L {
        &self.law
    }

    /// The friction law's parameters.
    pub fn params(&self) -> &L::Params {
        &self.params
    }

    /// The stick/slip threshold on the physical tangential displacement.
    pub fn slip_threshold(&self) -> f64 {
        self.slip_threshold
    }

    /// The bulk system `A` (with the right-hand side of unit `tau0`).
    pub fn system(&self) -> &LinearSystem {
        &self.system
    }

    /// Number of unknowns.
    pub fn dof_count(&self) -> usize {
        self.system.dimension()
    }

    /// All contact nodes, in increasing `x2`.
    pub fn contact_nodes(&self) -> &[ContactNode] {
        &self.nodes
    }

    /// Indices into [`ContactModel::contact_nodes`] of the nodes with a free tangential row
    /// (where friction acts).
    pub fn active(&self) -> &[usize] {
        &self.active
    }

    /// The active contact node number `k` (`k < active().len()`).
    #[track_caller]
    pub fn active_node(&self, k: usize) -> &ContactNode {
        &self.nodes[self.active[k]]
    }

    pub(crate) fn extended(&self) -> &ExtendedPattern {
        &self.ext
    }

    /// `b(tau) = tau0 b_0 + tau_max b_1`.
    pub fn rhs(&self, loads: EndLoads) -> Vec<f64> {
        self.rhs_basis[0]
            .iter()
            .zip(&self.rhs_basis[1])
            .map(|(a, b)| loads.tau0 * a + loads.tau_max * b)
            .collect()
    }

    /// The right-hand side for unit `tau0` (`i = 0`) or unit `tau_max` (`i = 1`).
    #[track_caller]
    pub fn rhs_basis(&self, i: usize) -> &[f64] {
        &self.rhs_basis[i]
    }

    /// The friction traction at a contact node given its slip and normal stress.
    pub fn traction_at(&self, node: &ContactNode, slip: f64, normal_stress: f64) -> NodeTraction {
        let state = ContactState::new([0.0, slip], normal_stress);
        let t = self.law.traction(&state, &self.params)[1];
        let d = self.law.traction_derivatives(&state, &self.params);
        let g = node.sqrt_g22;
        NodeTraction {
            slip,
            normal_stress,
            t2: g * t,
            d_tangential: g * g * d.d_slip[1][1],
            d_normal_stress: g * d.d_pressure[1],
        }
    }

    /// The friction traction at a contact node for the displacement `v`.
    #[track_caller]
    pub fn node_traction(&self, node: &ContactNode, v: &[f64]) -> NodeTraction {
        let slip = node.sqrt_g22 * v[node.tangential_dof];
        self.traction_at(node, slip, node.normal_stress.dot(v))
    }

    /// The full residual `R(v) = A v - b(tau) - sum_k w_k e_row t_2,k(v)`.
    ///
    /// # Panics
    /// If `v`, `rhs` or `r` have the wrong length.
    #[track_caller]
    pub fn residual_into(&self, rhs: &[f64], v: &[f64], r: &mut [f64]) {
        self.system.pattern.matvec(&self.system.values, v, r);
        for (ri, bi) in r.iter_mut().zip(rhs) {
            *ri -= bi;
        }
        for &a in &self.active {
            let node = &self.nodes[a];
            let row = node.tangential_row.expect("active nodes have a row");
            r[row] -= node.traction_weight * self.node_traction(node, v).t2;
        }
    }

    /// `max_i |R(v)_i| / max(1, max_i |b_i|)`.
    pub fn relative_residual(&self, loads: EndLoads, v: &[f64]) -> f64 {
        let rhs = self.rhs(loads);
        let mut r = vec![0.0; v.len()];
        self.residual_into(&rhs, v, &mut r);
        let b = rhs.iter().fold(0.0f64, |m, x| m.max(x.abs())).max(1.0);
        r.iter().fold(0.0f64, |m, x| m.max(x.abs())) / b
    }

    /// Values of the full Jacobian `dR/dv` on the extended pattern.
    ///
    /// # Panics
    /// If `v` or `values` have the wrong length.
    #[track_caller]
    pub(crate) fn jacobian_into(&self, v: &[f64], values: &mut [f64]) {
        values.iter_mut().for_each(|x| *x = 0.0);
        for (k, &a) in self.system.values.iter().enumerate() {
            values[self.ext.a_slot[k]] += a;
        }
        for (k, &a) in self.active.iter().enumerate() {
            let node = &self.nodes[a];
            let nt = self.node_traction(node, v);
            let w = node.traction_weight;
            values[self.ext.tangential_slot[k]] -= w * nt.d_tangential;
            for (c, &slot) in node
                .normal_stress
                .values
                .iter()
                .zip(&self.ext.normal_slots[k])
            {
                values[slot] -= w * nt.d_normal_stress * c;
            }
        }
    }
}

fn extended_pattern(
    a: &SparsityPattern,
    nodes: &[ContactNode],
    active: &[usize],
) -> Result<ExtendedPattern, ContactError> {
    let mut entries: Vec<(usize, usize)> = a.entries().collect();
    let na = entries.len();
    let mut marks = Vec::with_capacity(active.len());
    for &k in active {
        let node = &nodes[k];
        let row = node.tangential_row.expect("active");
        marks.push(entries.len());
        entries.push((row, node.tangential_dof));
        entries.extend(node.normal_stress.columns.iter().map(|&c| (row, c)));
    }
    let n = a.nrows();
    let (pattern, slots) =
        SparsityPattern::from_entries(n, n, &entries).map_err(crate::ElasticityError::from)?;
    let a_slot = slots[..na].to_vec();
    let tangential_slot = marks.iter().map(|&m| slots[m]).collect();
    let normal_slots = active
        .iter()
        .zip(&marks)
        .map(|(&k, &m)| slots[m + 1..m + 1 + nodes[k].normal_stress.columns.len()].to_vec())
        .collect();
    Ok(ExtendedPattern {
        pattern,
        a_slot,
        tangential_slot,
        normal_slots,
    })
}
