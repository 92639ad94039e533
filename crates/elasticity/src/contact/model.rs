//! The frictional contact model: a linear bulk operator, end loads, and a pointwise friction
//! law on the contact rows of any [`Discretisation`].

use std::sync::Arc;

use capstan_friction::FrictionLaw;
use capstan_solvers::row_distribution::RowDistribution;

use crate::contact::error::ContactError;
use crate::contact::exact_friction::ExactFriction;
use crate::contact::operator::{ContactOperator, MatrixFreeBulk};
use crate::contact::pattern::{ExtendedPattern, Sites, extended_pattern};
use crate::contact::unilateral::{Gap, Unilateral};
use crate::discretisation::{ContactNode, LinearSystem};
use crate::error::ElasticityError;

use crate::contact::loads::{END_LOADS, EndLoads};
use capstan_friction::nonsmooth_law::DynNonsmoothLaw;

// the slip reference of a load path: a child module (it sets the model's private field),
// kept in its own file beside the path solver
#[path = "slip_reference.rs"]
mod slip_reference;
pub(crate) use slip_reference::slide_along;

// the friction law on the contact rows: site tractions, the residual and its Jacobian (a
// child module: it reads the model's private fields)
#[path = "site_law.rs"]
mod site_law;

/// The friction law at one contact site (a contact node; one or two tangential entries, see
/// [`ContactNode`]): the physical slip and traction, and for each entry of the site the
/// covariant traction and its derivatives, which enter the discrete balance rows.
///
/// # Math
/// With `F` the `2 x b` matrix of the entries' frames (columns `frame_e`), `x` the entries'
/// `v^alpha` and `beta` a slip scale (1 but in the slip homotopy):
/// ```text
/// u = beta F x,   tau = t(u, sigma_n)         (physical, from the law)
/// t_e = frame_e . tau                          (covariant)
/// d t_e / d x_f = frame_e^T (d tau / d u) frame_f       (times beta for the scaled slip)
/// d t_e / d sigma_n = frame_e . d tau / d p
/// ```
/// Plane strain (`b = 1`, `frame = [0, sqrt(g22)]`): `t_2 = sqrt(g22) t`,
/// `d t_2 / d v^2 = g22 d t / d u`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SiteTraction {
    /// Physical slip `u = beta F x` in the frame `[e_1, e_2]`.
    pub slip: [f64; 2],
    /// `sigma_n = T^3_3` (negative in compression).
    pub normal_stress: f64,
    /// Physical traction on the body `t(u, sigma_n)` in the frame `[e_1, e_2]`.
    pub traction: [f64; 2],
    /// Covariant traction `t_e` of each entry of the site (in the site's entry order).
    pub covariant: [f64; 2],
    /// `d t_e / d x_f` per unit physical slip scale (multiply by `beta`).
    pub d_tangential: [[f64; 2]; 2],
    /// `d t_e / d sigma_n`.
    pub d_normal_stress: [f64; 2],
}

/// `u += (beta frame) x`, skipping zero frame components (plane strain: `u = [0, beta sqrt(g22) x]`
/// exactly).
pub(crate) fn add_slip(u: &mut [f64; 2], beta: f64, frame: [f64; 2], x: f64) {
    for c in 0..2 {
        if frame[c] != 0.0 {
            u[c] += beta * frame[c] * x;
        }
    }
}

/// Exact (nonsmooth) friction rows built for one body ([`ContactModel::exact_rows`]): the
/// projection law, the per-site data (frames, augmentation) and the extended pattern of the
/// full-system Jacobian, to be installed by [`ContactModel::with_exact_rows`].
#[derive(Debug, Clone)]
pub struct ExactRows {
    pub(crate) friction: ExactFriction,
    /// The extended pattern with the rows' cross-entry slots (`None`: the model's own).
    ext: Option<ExtendedPattern>,
    /// The number of unknowns of the body the rows were built for.
    dimension: usize,
    /// Its active contact entries.
    active: Vec<usize>,
}

impl ExactRows {
    /// Whether the rows were built for `model`'s body (its number of unknowns and active
    /// contact entries).
    pub(crate) fn built_for<D, L: FrictionLaw<f64>>(&self, model: &ContactModel<D, L>) -> bool {
        self.dimension == model.system.dimension() && self.active == model.active
    }
}

/// A frictional contact problem on a discretised thick body.
///
/// # Math
/// The bulk operator is linear; the friction law acts only on the tangential balance rows of
/// the contact nodes (see [`ContactNode`]):
/// ```text
/// R(v) = A v - b(tau) - sum_k w_k e_{row_k} t_2,k(v) = 0
/// t_2,k = sqrt(g_22) t(u_k, sigma_k)      u_k = sqrt(g_22) v^2_k,  sigma_k = T^3_3(v) at node k
/// b(m) = sum_k m_k b_k                     (b linear in the loads; the end tractions
///                                          tau0, tau_max are the first two)
/// ```
/// `t(u, sigma)` is the physical traction on the body from the [`FrictionLaw`], evaluated with
/// slip `(0, u)` (the `x1` slip of plane strain is zero) and normal stress `sigma = T^3_3`
/// (unit outward normal `n = -g^3` on `x3 = 0`, so `n.T.n = T^3_3`; negative in compression).
/// For regularised Coulomb `t = mu sigma u / max(|u|, eps)`: opposite to the slip when `sigma < 0`.
///
/// The model is built from one discretisation of the same body per load at unit magnitude
/// (the end loads `(1, 0)` and `(0, 1)` in the paper's case, [`ContactModel::with_loads`] for
/// a list); it checks they share one bulk operator `A`, which is what lets the condensed
/// solver ([`crate::contact::BoundarySolver`]) handle every tension ratio with two bulk
/// solves.
pub struct ContactModel<D, L: FrictionLaw<f64>> {
    /// Shared by the models of [`ContactModel::with_params`].
    disc: std::sync::Arc<D>,
    law: L,
    params: L::Params,
    slip_threshold: f64,
    system: LinearSystem,
    /// The names of the loads (scene keys), one per right-hand side of `rhs_basis`.
    loads: Vec<&'static str>,
    rhs_basis: Vec<Vec<f64>>,
    /// The magnitudes of the loads after the end loads that every solve applies
    /// ([`ContactModel::with_fixed_loads`]; empty: zero).
    fixed: Vec<f64>,
    nodes: Vec<ContactNode>,
    active: Vec<usize>,
    sites: Sites,
    ext: ExtendedPattern,
    /// The Signorini rows of unilateral contact (`None`: bilateral, `v^3 = 0`).
    unilateral: Option<Unilateral>,
    /// Exact (nonsmooth) friction in place of `law` ([`ContactModel::into_exact_friction`]).
    exact: Option<ExactFriction>,
    /// `system` holds this process's rows only ([`ContactOperator::row_distribution`]):
    /// residuals are completed by gathering the owners' rows.
    distribution: Option<(Arc<dyn RowDistribution>, usize)>,
    /// The matrix-free bulk operator ([`ContactOperator::matrix_free`]), `None`: assembled.
    bulk: Option<std::sync::Arc<dyn MatrixFreeBulk + Send + Sync>>,
    /// The displacement of the previous load state of a path ([`ContactModel::with_slip_reference`]):
    /// the law sees the slip increment from it; `None`: from rest.
    reference: Option<Arc<Vec<f64>>>,
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

impl<D: ContactOperator, L: FrictionLaw<f64>> ContactModel<D, L> {
    /// Builds the model from `build(tau0, tau_max)`, which returns the discretisation of the
    /// body with those end loads and zero tangential traction on `x3 = 0`: the load list
    /// [`END_LOADS`] of [`ContactModel::with_loads`].
    ///
    /// `slip_threshold` classifies stick and slip (the regularisation width `eps` for
    /// regularised Coulomb).
    ///
    /// # Errors
    /// See [`ContactModel::with_loads`].
    pub fn new(
        build: impl Fn(f64, f64) -> Result<D, crate::error::ElasticityError>,
        law: L,
        params: L::Params,
        slip_threshold: f64,
    ) -> Result<Self, ContactError> {
        Self::with_loads(
            |m: &[f64]| build(m[0], m[1]),
            &END_LOADS,
            law,
            params,
            slip_threshold,
        )
    }

    /// Builds the model from a list of loads (boundary or body loads, named by `loads`) and
    /// `build(magnitudes)`, the discretisation of the body with load `k` scaled by
    /// `magnitudes[k]` and zero tangential traction on `x3 = 0`.
    ///
    /// # Math
    /// The bulk operator does not depend on the loads and the right-hand side is linear in
    /// them, so the model keeps one unit right-hand side per load (superposition):
    /// ```text
    /// b(m) = sum_k m_k b_k,   b_k = b(e_k)   (one build per load, e_k the k-th unit vector)
    /// ```
    /// The first two loads are what [`EndLoads`] scales (the solvers drive the tension ratio
    /// through them); further loads enter [`ContactModel::rhs_of`].
    ///
    /// # Errors
    /// Errors of `build`; [`ContactError::InconsistentLoads`] if the unit-load operators
    /// differ; [`ContactError::NoContactNodes`]; [`ElasticityError::InvalidParameter`] for a
    /// non-positive `slip_threshold` or fewer than two loads.
    pub fn with_loads(
        build: impl Fn(&[f64]) -> Result<D, crate::error::ElasticityError>,
        loads: &[&'static str],
        law: L,
        params: L::Params,
        slip_threshold: f64,
    ) -> Result<Self, ContactError> {
        if !(slip_threshold.is_finite() && slip_threshold > 0.0) {
            return Err(ContactError::from(ElasticityError::InvalidParameter {
                field: "slip_threshold",
                value: slip_threshold,
                allowed: "(0, inf)",
            }));
        }
        if loads.len() < 2 {
            return Err(ContactError::from(ElasticityError::InvalidParameter {
                field: "loads",
                value: loads.len() as f64,
                allowed: "at least the two end tractions (tau0, tau_max) first",
            }));
        }
        let unit = |k: usize| {
            let mut m = vec![0.0; loads.len()];
            m[k] = 1.0;
            m
        };
        let disc = build(&unit(0))?;
        let system = disc.contact_system()?;
        let scale = system
            .values
            .iter()
            .fold(0.0f64, |m, x| m.max(x.abs()))
            .max(f64::MIN_POSITIVE);
        let mut rhs_basis = vec![system.rhs.clone()];
        for k in 1..loads.len() {
            let other = build(&unit(k))?.contact_system()?;
            if other.pattern != system.pattern || other.values.len() != system.values.len() {
                return Err(ContactError::InconsistentLoads {
                    what: "sparsity pattern",
                });
            }
            if system
                .values
                .iter()
                .zip(&other.values)
                .any(|(a, b)| (a - b).abs() > 1e-12 * scale)
            {
                return Err(ContactError::InconsistentLoads {
                    what: "matrix values",
                });
            }
            rhs_basis.push(other.rhs);
        }
        let nodes = disc.contact_entries()?;
        let active: Vec<usize> = (0..nodes.len())
            .filter(|&k| nodes[k].tangential_row.is_some())
            .collect();
        if active.is_empty() {
            return Err(ContactError::NoContactNodes);
        }
        let sites = Sites::new(&nodes, &active)?;
        let ext = extended_pattern(&system.pattern, &nodes, &active, &sites)?;
        let distribution = disc.row_distribution();
        let bulk = disc.matrix_free();
        Ok(Self {
            disc: std::sync::Arc::new(disc),
            law,
            params,
            slip_threshold,
            system,
            loads: loads.to_vec(),
            rhs_basis,
            fixed: Vec::new(),
            nodes,
            active,
            sites,
            ext,
            unilateral: None,
            exact: None,
            distribution,
            bulk,
            reference: None,
        })
    }

    /// The model with unilateral (Signorini) contact on `x3 = 0`: `self` must be built from
    /// the body with a **traction-free** contact face (both components free, e.g.
    /// [`crate::contact::Body::model`] with [`crate::contact::ContactKind::Unilateral`]), so
    /// that the normal balance row of every contact node is its free row.
    ///
    /// # Math
    /// With `a_k . v = b_k` the free normal row of contact node `k` (`s_k = sign(a_kk)`,
    /// `d_k = |a_kk|`) and `g_k` the gap, the contact reaction (compression positive, in
    /// units of displacement) and the row of the residual are
    /// ```text
    /// lambda_k(v) = s_k (a_k . v - b_k) / d_k
    /// R_k(v)      = d_k min(v^3_k + g_k, lambda_k(v))      (NCP function of Signorini)
    /// ```
    /// `R_k = 0` iff `v^3_k + g_k >= 0`, `lambda_k >= 0`, `(v^3_k + g_k) lambda_k = 0`. Its
    /// generalised Jacobian is `d_k e_k` where the node is in contact
    /// (`v^3_k + g_k <= lambda_k`) and `s_k a_k` where it has separated, so Newton on `R` is
    /// the semismooth Newton (primal-dual active set) method. The friction traction acts only
    /// on sites in contact, with `sigma_n -> min(sigma_n, 0)`.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `contact.gap` for a negative gap, naming
    /// `contact.kind` for a contact node without a free normal row.
    pub fn into_unilateral(mut self, gap: &Gap) -> Result<Self, ContactError> {
        if self.distribution.is_some() {
            // the Signorini rows read whole rows of A on every process
            return Err(ContactError::from(ElasticityError::InvalidParameter {
                field: "contact.kind",
                value: f64::NAN,
                allowed: "`bilateral` when the body is assembled over several processes (solver.linear = \"petsc\" on more than one rank); `unilateral` on one",
            }));
        }
        let active_of: std::collections::HashMap<usize, usize> = self
            .active
            .iter()
            .enumerate()
            .map(|(k, &a)| (a, k))
            .collect();
        let sites = &self.sites;
        let index_of =
            |a: usize| -> Option<usize> { active_of.get(&a).map(|&k| sites.of_active[k].0) };
        let unilateral = Unilateral::new(
            &mut self.system,
            &self.nodes,
            index_of,
            self.sites.members.len(),
            gap,
        )?;
        self.unilateral = Some(unilateral);
        Ok(self)
    }
}

impl<D, L: FrictionLaw<f64>> ContactModel<D, L> {
    /// The model with the loads after the end loads held at `magnitudes` in every solve (a
    /// body force at its full value: `&[1.0]`), while the solvers drive the end loads.
    ///
    /// # Math
    /// ```text
    /// b(tau) = tau0 b_0 + tau_max b_1 + sum_k m_k b_{k+2}      (m = magnitudes)
    /// ```
    /// The right-hand side is then affine in the end loads: a load continuation scales only
    /// `tau0`, `tau_max`, and the condensed solver's limiting ratios (which assume
    /// `b` linear in them) are not computed.
    ///
    /// # Panics
    /// If there are more magnitudes than loads after the end loads.
    #[must_use]
    #[track_caller]
    pub fn with_fixed_loads(mut self, magnitudes: &[f64]) -> Self {
        assert!(
            magnitudes.len() + 2 <= self.rhs_basis.len(),
            "{} fixed magnitudes for {} loads after the end loads",
            magnitudes.len(),
            self.rhs_basis.len() - 2
        );
        self.fixed = magnitudes.to_vec();
        self
    }

    /// `sum_k m_k b_{k+2}`, the right-hand side of the fixed loads
    /// ([`ContactModel::with_fixed_loads`]); `None` without any, or when it is exactly zero
    /// (a zero body force: the model then behaves as one without it, limiting ratios
    /// included).
    pub fn fixed_rhs(&self) -> Option<Vec<f64>> {
        if self.fixed.iter().all(|&m| m == 0.0) {
            return None;
        }
        let mut b = vec![0.0; self.system.dimension()];
        for (m, basis) in self.fixed.iter().zip(&self.rhs_basis[2..]) {
            for (bi, x) in b.iter_mut().zip(basis) {
                *bi += m * x;
            }
        }
        b.iter().any(|&x| x != 0.0).then_some(b)
    }

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
            loads: self.loads.clone(),
            rhs_basis: self.rhs_basis.clone(),
            fixed: self.fixed.clone(),
            nodes: self.nodes.clone(),
            active: self.active.clone(),
            sites: self.sites.clone(),
            ext: self.ext.clone(),
            unilateral: self.unilateral.clone(),
            exact: self.exact.clone(),
            distribution: self.distribution.clone(),
            bulk: self.bulk.clone(),
            reference: self.reference.clone(),
        }
    }

    pub(crate) fn unilateral(&self) -> Option<&Unilateral> {
        self.unilateral.as_ref()
    }

    pub(crate) fn exact_friction(&self) -> Option<&ExactFriction> {
        self.exact.as_ref()
    }

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
        self,
        law: std::sync::Arc<dyn DynNonsmoothLaw>,
    ) -> Result<Self, ContactError> {
        let rows = self.exact_rows(law)?;
        self.with_exact_rows(rows)
    }

    /// The exact friction rows of [`ContactModel::into_exact_friction`] built for this body
    /// without taking (or copying) the model: a [`crate::contact::BoundarySolver`] on this
    /// model solves them on its condensed face
    /// ([`crate::contact::BoundarySolver::solve_exact_rows_observed`]) and
    /// [`ContactModel::with_exact_rows`] then installs them, so the exact model is this one
    /// with its friction rows replaced and nothing assembled or copied twice.
    ///
    /// # Errors
    /// As [`ContactModel::into_exact_friction`].
    pub fn exact_rows(
        &self,
        law: std::sync::Arc<dyn DynNonsmoothLaw>,
    ) -> Result<ExactRows, ContactError> {
        let (friction, ext) =
            ExactFriction::build(self, &self.sites.members, self.active.len(), law)?;
        Ok(ExactRows {
            friction,
            ext,
            dimension: self.system.dimension(),
            active: self.active.clone(),
        })
    }

    /// This model with the exact friction rows `rows` ([`ContactModel::exact_rows`]) in place
    /// of its pointwise law: the same model as [`ContactModel::into_exact_friction`].
    ///
    /// # Errors
    /// [`ContactError::DifferentBody`] when `rows` were built for another body (other
    /// unknowns or contact entries).
    pub fn with_exact_rows(mut self, rows: ExactRows) -> Result<Self, ContactError> {
        if !rows.built_for(&self) {
            return Err(ContactError::DifferentBody {
                what: "contact nodes",
            });
        }
        if let Some(ext) = rows.ext {
            self.ext = ext;
        }
        self.exact = Some(rows.friction);
        Ok(self)
    }

    /// Whether the model has exact (nonsmooth) friction ([`ContactModel::into_exact_friction`]).
    pub fn is_exact_friction(&self) -> bool {
        self.exact.is_some()
    }

    /// `A v - b` for the right-hand side `rhs`.
    pub(crate) fn free_residual(&self, rhs: &[f64], v: &[f64]) -> Vec<f64> {
        let mut r = vec![0.0; v.len()];
        self.system.pattern.matvec(&self.system.values, v, &mut r);
        for (ri, bi) in r.iter_mut().zip(rhs) {
            *ri -= bi;
        }
        r
    }

    /// The contact active set at `v`: sites that stick (`|u| < eps`), slip, and have lifted
    /// off (unilateral contact) under the loads' right-hand side `rhs`.
    pub fn active_set(&self, rhs: &[f64], v: &[f64]) -> capstan_solvers::ActiveSet {
        let separated = self.separated_sites(rhs, v);
        if let Some(x) = &self.exact {
            let r = self.free_residual(rhs, v);
            return x.active_set(self, v, &r, separated.as_deref());
        }
        let mut set = capstan_solvers::ActiveSet::default();
        for j in 0..self.sites.members.len() {
            if separated.as_ref().is_some_and(|s| s[j]) {
                set.separated += 1;
                continue;
            }
            let u = self.site_slip(j, 1.0, |k| v[self.active_node(k).tangential_dof]);
            if (u[0] * u[0] + u[1] * u[1]).sqrt() < self.slip_threshold {
                set.stick += 1;
            } else {
                set.slip += 1;
            }
        }
        set
    }

    /// Whether the bulk operator holds this process's rows only (a distributed solve:
    /// [`ContactOperator::row_distribution`]); [`ContactModel::system`] and the Jacobians then
    /// have entries in those rows alone, the residuals are whole.
    pub fn is_distributed(&self) -> bool {
        self.distribution.is_some()
    }

    /// The distribution of a model assembled over several processes and the unknowns per
    /// node its rows are owned in ([`ContactModel::is_distributed`]); `None` on one process.
    pub(crate) fn row_distribution(&self) -> Option<(Arc<dyn RowDistribution>, usize)> {
        self.distribution.clone()
    }

    /// Whether the model has unilateral (Signorini) contact.
    pub fn is_unilateral(&self) -> bool {
        self.unilateral.is_some()
    }

    /// Whether the bulk is matrix-free ([`ContactOperator::matrix_free`]; [`ContactModel::system`]
    /// holds only the right-hand side; solved by [`crate::contact::MatrixFreeNewton`]).
    pub fn is_matrix_free(&self) -> bool {
        self.bulk.is_some()
    }
    /// The matrix-free bulk operator, `None` when it is assembled.
    pub fn matrix_free_bulk(&self) -> Option<&(dyn MatrixFreeBulk + Send + Sync)> {
        self.bulk.as_deref()
    }

    /// [`ContactError::Unsupported`] naming `solver.linear` for a matrix-free model, which
    /// `solver` (a solver that reads the assembled matrix) cannot solve.
    pub(crate) fn require_assembled(&self, solver: &'static str) -> Result<(), ContactError> {
        if self.is_matrix_free() {
            return Err(ContactError::Unsupported {
                field: "solver.linear",
                message: solver,
            });
        }
        Ok(())
    }

    /// Per contact site (in site order), whether it has separated from the obstacle at `v`
    /// under the loads' right-hand side `rhs` (`None` for bilateral contact).
    pub fn separated_sites(&self, rhs: &[f64], v: &[f64]) -> Option<Vec<bool>> {
        let u = self.unilateral.as_ref()?;
        let contact = u.contact_set(v, rhs);
        Some(
            u.site_row
                .iter()
                .map(|row| row.is_some_and(|k| !contact[k]))
                .collect(),
        )
    }

    /// Per contact node (one entry per distinct normal dof, in the order of
    /// [`ContactModel::contact_nodes`]): its normal dof and whether it has separated at `v`
    /// (`None` for bilateral contact).
    pub fn separated_nodes(&self, rhs: &[f64], v: &[f64]) -> Option<Vec<(usize, bool)>> {
        let u = self.unilateral.as_ref()?;
        Some(
            u.rows
                .iter()
                .map(|r| (r.dof, !r.in_contact(v, rhs)))
                .collect(),
        )
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

    /// `b(tau) = tau0 b_0 + tau_max b_1`, plus the fixed loads
    /// ([`ContactModel::with_fixed_loads`]; further loads at zero).
    pub fn rhs(&self, loads: EndLoads) -> Vec<f64> {
        if self.fixed.is_empty() {
            return self.rhs_of(&loads.magnitudes());
        }
        let mut m = loads.magnitudes().to_vec();
        m.extend_from_slice(&self.fixed);
        self.rhs_of(&m)
    }

    /// Rows `rows` of [`ContactModel::rhs`] (the same arithmetic, entry by entry), without
    /// the whole vector.
    ///
    /// # Panics
    /// If `rows` reaches past the unknowns.
    #[track_caller]
    pub(crate) fn rhs_rows(&self, loads: EndLoads, rows: core::ops::Range<usize>) -> Vec<f64> {
        let mut m = loads.magnitudes().to_vec();
        m.extend_from_slice(&self.fixed);
        let mut b: Vec<f64> = self.rhs_basis[0][rows.clone()]
            .iter()
            .map(|x| m[0] * x)
            .collect();
        for (mk, basis) in m.iter().zip(&self.rhs_basis).skip(1) {
            for (bi, x) in b.iter_mut().zip(&basis[rows.clone()]) {
                *bi += mk * x;
            }
        }
        b
    }

    /// `b(m) = sum_k m_k b_k` over the first `magnitudes.len()` loads (the others at zero).
    ///
    /// # Panics
    /// If `magnitudes` is empty or longer than [`ContactModel::loads`].
    #[track_caller]
    pub fn rhs_of(&self, magnitudes: &[f64]) -> Vec<f64> {
        assert!(
            !magnitudes.is_empty() && magnitudes.len() <= self.rhs_basis.len(),
            "one magnitude per load, at most {}",
            self.rhs_basis.len()
        );
        let mut b: Vec<f64> = self.rhs_basis[0]
            .iter()
            .map(|x| magnitudes[0] * x)
            .collect();
        for (m, basis) in magnitudes.iter().zip(&self.rhs_basis).skip(1) {
            for (bi, x) in b.iter_mut().zip(basis) {
                *bi += m * x;
            }
        }
        b
    }

    /// The loads of the model, by name (scene keys), in the order of their right-hand sides:
    /// [`END_LOADS`] first.
    pub fn loads(&self) -> &[&'static str] {
        &self.loads
    }

    /// The right-hand side of load `i` at unit magnitude (`i = 0`: unit `tau0`, `i = 1`: unit
    /// `tau_max`).
    ///
    /// # Panics
    /// If `i` is not below the number of loads.
    #[track_caller]
    pub fn rhs_basis(&self, i: usize) -> &[f64] {
        &self.rhs_basis[i]
    }

    pub(crate) fn sites(&self) -> &Sites {
        &self.sites
    }
}
