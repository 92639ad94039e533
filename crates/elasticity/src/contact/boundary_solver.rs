//! The boundary-only (condensed) contact solver: factor the bulk once, Newton on the contact
//! tractions only.

use std::sync::{Arc, Mutex};

use capstan_friction::FrictionLaw;
use capstan_solvers::{LinearSolver, SparseLu};
use faer::Mat;
use faer::linalg::solvers::Solve;

use crate::contact::error::ContactError;
use crate::contact::model::{ContactModel, EndLoads, ExtendedPattern};
use crate::contact::solution::{ContactSolution, SolveStats};
use crate::discretisation::Discretisation;

/// Settings of the contact Newton iterations (both solvers) and of the load continuation.
///
/// # Math
/// ```text
/// converged when max_k |G_k| <= tolerance * max(|tau0|, |tau_max|) * max_k sqrt(g_22)
/// continuation: lambda = 0 -> 1 on the loads, step x1.5 after success, /2 after failure
/// ```
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ContactSettings {
    /// Newton iterations per continuation step.
    pub max_iterations: usize,
    /// Relative tolerance on the condensed residual (see above).
    pub tolerance: f64,
    /// First load step of the continuation (used only when plain Newton fails).
    pub initial_load_step: f64,
    /// Smallest load step before giving up.
    pub min_load_step: f64,
    /// Cap on continuation steps.
    pub max_continuation_steps: usize,
}

impl Default for ContactSettings {
    fn default() -> Self {
        Self {
            max_iterations: 60,
            tolerance: 1e-10,
            initial_load_step: 0.25,
            min_load_step: 1e-4,
            max_continuation_steps: 400,
        }
    }
}

impl ContactSettings {
    /// Checks every field.
    ///
    /// # Errors
    /// [`ContactError::InvalidParameter`] naming the first bad field.
    pub fn validate(&self) -> Result<(), ContactError> {
        let bad = |field, value, allowed| {
            Err(ContactError::InvalidParameter {
                field,
                value,
                allowed,
            })
        };
        if self.max_iterations == 0 {
            return bad("max_iterations", 0.0, "[1, inf)");
        }
        if !(self.tolerance > 0.0 && self.tolerance < 1.0) {
            return bad("tolerance", self.tolerance, "(0, 1)");
        }
        if !(self.initial_load_step > 0.0 && self.initial_load_step <= 1.0) {
            return bad("initial_load_step", self.initial_load_step, "(0, 1]");
        }
        if !(self.min_load_step > 0.0 && self.min_load_step <= self.initial_load_step) {
            return bad(
                "min_load_step",
                self.min_load_step,
                "(0, initial_load_step]",
            );
        }
        Ok(())
    }
}

/// The rigid sliding mode of the bilaterally constrained body (a circular obstacle) and the
/// range of tension ratios friction can hold against it.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SlidingMode {
    /// Smallest singular value over the largest of the frictionless condensed operator.
    pub relative_singular_value: f64,
    /// `tau_max / tau0` at which the whole contact slides in the negative direction.
    pub lower_ratio: f64,
    /// `tau_max / tau0` at which the whole contact slides in the positive direction.
    pub upper_ratio: f64,
    /// The `tau0` of these ratios (they depend on it unless the law is homogeneous in the
    /// normal stress, as Coulomb's is; [`BoundarySolver::sliding`] reports `tau0 = 1`).
    pub tau0: f64,
}

/// Work done once by [`BoundarySolver::new`].
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SetupStats {
    /// Contact unknowns `m`.
    pub contact_unknowns: usize,
    /// Bulk unknowns `n`.
    pub bulk_unknowns: usize,
    /// Sparse LU factorisations of the bulk (1; 2 when the spring was softened, see
    /// [`BoundarySolver`]; 0 for a solver from [`BoundarySolver::with_model`]).
    pub factorisations: usize,
    /// Sparse solves with the bulk factors (`m` per factorisation, `+ 2`).
    pub bulk_solves: usize,
}

/// Relative singular value below which the frictionless bulk counts as having a sliding mode.
const SLIDING_MODE_THRESHOLD: f64 = 1e-8;

/// Largest share of `sum_k w_k |t_k|` that the full-slip friction may carry *along* the slip
/// (contact in tension under a pressure-proportional law) for its ratio to count as a limit.
/// The corner nodes next to the loaded ends carry a resolution artefact of this kind
/// (measured: below `1e-3` of the total on 125 x 21 to 500 x 81 of the default circle).
const WRONG_WAY_SHARE_LIMIT: f64 = 1e-2;

/// A residual within this factor of the rounding floor of its evaluation counts as converged.
const ROUNDOFF_FACTOR: f64 = 100.0;

/// The largest relative residual the rounding floor may excuse (see [`ROUNDOFF_FACTOR`]).
const MAX_ROUNDOFF_RESIDUAL: f64 = 1e-6;

/// Largest relative residual of the full system accepted for a converged contact solution
/// (a safety net behind the condensed Newton's own test).
const MAX_FULL_RESIDUAL: f64 = 1e-6;

/// Largest singular value of `I - C P Z` below which the spring dominates every boundary mode
/// and is softened (see [`BoundarySolver`]).
const SPRING_DOMINANCE: f64 = 0.1;

/// Growth of the slip scale allowed per Newton step (see [`BoundarySolver::slip_step_cap`]).
const SLIP_STEP_GROWTH: f64 = 10.0;

/// Stiffness along the rigid mode added to the Newton matrix, relative to the spring (see
/// [`BoundarySolver::eval`]).
const RIGID_TETHER: f64 = 1e-8;

/// False-position iterations of [`BoundarySolver::rebalance`].
const REBALANCE_ITERATIONS: usize = 100;

/// Power iterations of [`largest_singular_value`].
const SINGULAR_VALUE_ITERATIONS: usize = 30;

/// Workspace (doubles) of one block of condensation solves: 2^24 (128 MiB).
const CONDENSATION_BLOCK_ENTRIES: usize = 1 << 24;

/// Newton iterations of the full-slip limit (one suffices for laws affine in `sigma_n`).
const FULL_SLIP_ITERATIONS: usize = 50;

/// The law-independent part of [`BoundarySolver`]: the factorised stabilised bulk and the
/// condensed matrices (cheap to clone: the large parts are shared).
#[derive(Clone)]
struct Condensation {
    lu: Arc<Mutex<SparseLu>>,
    spring: Vec<f64>,
    pz: Arc<Mat<f64>>,
    nz: Arc<Mat<f64>>,
    /// `(P v_i, N v_i)` for unit `tau0` (`i = 0`) and unit `tau_max` (`i = 1`).
    base: [(Vec<f64>, Vec<f64>); 2],
    /// The stuck state (`v^2 = 0` at every contact node) for the unit loads: Newton's start.
    stuck: [Vec<f64>; 2],
}

/// The boundary-only contact solver.
///
/// # Math
/// The friction traction acts only on the `m` tangential contact rows. With a stabilising
/// spring `c_k` on those rows (so the bulk stays invertible even when the body can slide
/// rigidly, as on a circle) and the unknowns `s_k = t_2,k + c_k v^2_k`:
/// ```text
/// A~ = A + sum_k w_k c_k e_row_k e_tdof_k^T         factorised once (sparse LU)
/// v(s) = v_a tau0 + v_b tau_max + Z s,   Z = A~^-1 W  (m solves; only P Z, N Z are kept)
/// x = P v = x0 + (P Z) s        (v^2 at the contact nodes)
/// sigma = N v = n0 + (N Z) s    (T^3_3 at the contact nodes)
/// G(s) = s - t_2(sqrt(g22) x, sigma) - C x = 0      m equations, dense Newton
/// dG/ds = I - diag(dt_2/dv^2 + c) P Z - diag(dt_2/dsigma) N Z
/// ```
/// The spring cancels exactly: `G = 0` is `A v - b - W t_2 = 0`. Because `b` is linear in the
/// loads, every tension ratio reuses the same factorisation and the same `m x m` matrices; a
/// point of a ratio sweep costs only dense `m x m` work and one sparse solve for the field.
///
/// If the frictionless condensed operator `I - C P Z` is singular (the bulk admits a rigid
/// sliding along the contact: the circle), equilibrium needs friction to balance the loads:
/// the full-slip operators `I - diag(g kappa+-) N Z - C P Z` (`kappa` = `dt/dsigma` at large
/// slip, `mu` sign for Coulomb) are singular too, and their left null vectors `y` give the
/// solvability conditions `y . q(tau) = 0`, i.e. the limiting ratios (a discrete moment
/// balance). Loads outside are [`ContactError::NoEquilibrium`].
///
/// The spring starts at `c_k = A_kk / w_k`. If it dominates every boundary mode of the body
/// (largest singular value of `I - C P Z` below 0.1: thin bodies, whose
/// diagonal grows like `1 / dx3^2` while their boundary stiffness falls like `h`), `s - C x`
/// would cancel to rounding; the spring is then scaled by that singular value (down to the
/// stiffest boundary mode) and the bulk condensed again. With a rigid mode `z` (`s = s_p + a z`),
/// Newton keeps the amplitude `a` out of `s - C x` (it cancels there exactly) and, at every
/// iterate, solves the scalar friction balance `y . G = 0` along the mode for `a` (`y` the left
/// null vector of `I - C P Z`), where saturated friction leaves the Newton matrix no stiffness.
pub struct BoundarySolver<'a, D, L: FrictionLaw<f64>> {
    model: &'a ContactModel<D, L>,
    /// The condensed bulk (law-independent), shared by the solvers of
    /// [`BoundarySolver::with_model`].
    bulk: Condensation,
    sliding: Option<SlidingMode>,
    /// Right null vector `z` of `I - C P Z` (the rigid mode in `s`, unit length), when there
    /// is one.
    rigid_mode: Vec<f64>,
    /// `P Z z`: the tangential contact displacements of the rigid mode (empty without one).
    rigid_shift: Vec<f64>,
    /// Left null vector `y` of `I - C P Z` (unit length): `y . G = 0` is the balance of the
    /// loads against friction along the rigid mode (empty without one).
    rigid_balance: Vec<f64>,
    /// Whether the saturated law is homogeneous in `sigma_n` (limits independent of `tau0`).
    homogeneous: bool,
    setup: SetupStats,
    settings: ContactSettings,
}

impl<D, L: FrictionLaw<f64>> core::fmt::Debug for BoundarySolver<'_, D, L> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("BoundarySolver")
            .field("setup", &self.setup)
            .field("sliding", &self.sliding)
            .finish_non_exhaustive()
    }
}

impl<'a, D: Discretisation, L: FrictionLaw<f64>> BoundarySolver<'a, D, L> {
    /// Factorises the stabilised bulk and forms the condensed matrices.
    ///
    /// # Errors
    /// Solver failures (a singular stabilised bulk); invalid settings.
    pub fn new(
        model: &'a ContactModel<D, L>,
        settings: ContactSettings,
    ) -> Result<Self, ContactError> {
        settings.validate()?;
        let ext = model.extended();
        let m = model.active().len();
        let n = model.dof_count();
        let mut values = vec![0.0; ext.pattern.nnz()];
        for (k, &a) in model.system().values.iter().enumerate() {
            values[ext.a_slot[k]] += a;
        }
        let mut spring: Vec<f64> = (0..m)
            .map(|k| {
                let node = model.active_node(k);
                let diag = values[ext.tangential_slot[k]].abs();
                let diag = if diag > 0.0 {
                    diag
                } else {
                    row_max(&ext.pattern, &values, node.tangential_row.expect("active"))
                };
                diag / node.traction_weight
            })
            .collect();
        let mut lu = SparseLu::new(capstan_solvers::DirectParams {
            ordering: model.discretisation().lu_ordering(),
            ..Default::default()
        })?;
        lu.analyse(&ext.pattern)?;
        let (mut pz, mut nz) = condense(model, ext, &values, &spring, &mut lu)?;
        let mut factorisations = 1;
        // A spring far stiffer than every boundary mode of the body (thin bodies: the diagonal
        // grows like 1 / dx3^2, the boundary stiffness like h) makes `s - C x` cancel to
        // rounding noise: soften it to the body's stiffest boundary mode and condense again.
        let top = largest_singular_value(&frictionless_operator(&spring, &pz));
        if top.is_finite() && top > 0.0 && top < SPRING_DOMINANCE {
            for c in &mut spring {
                *c *= top;
            }
            (pz, nz) = condense(model, ext, &values, &spring, &mut lu)?;
            factorisations += 1;
        }
        let base = [0, 1].map(|i| -> Result<(Vec<f64>, Vec<f64>), ContactError> {
            let mut v = model.rhs_basis(i).to_vec();
            lu.solve_in_place(&mut v)?;
            Ok(project(model, &v))
        });
        let [b0, b1] = base;
        let (b0, b1) = (b0?, b1?);
        // P Z s = -x_i: the contact tractions that hold every contact node in place.
        let lu_pz = pz.partial_piv_lu();
        let stuck = [&b0.0, &b1.0].map(|x| {
            let rhs = Mat::<f64>::from_fn(m, 1, |i, _| -x[i]);
            let s = lu_pz.solve(&rhs);
            (0..m).map(|i| s[(i, 0)]).collect::<Vec<f64>>()
        });
        if stuck.iter().flatten().any(|x| !x.is_finite()) {
            return Err(capstan_solvers::SolverError::Singular { pivot: None }.into());
        }
        let bulk = Condensation {
            lu: Arc::new(Mutex::new(lu)),
            spring,
            pz: Arc::new(pz),
            nz: Arc::new(nz),
            base: [b0, b1],
            stuck,
        };
        let setup = SetupStats {
            contact_unknowns: m,
            bulk_unknowns: n,
            factorisations,
            bulk_solves: factorisations * m + 2,
        };
        Self::with_condensation(model, bulk, setup, settings)
    }

    /// The solver of `model` on a condensed bulk, with the sliding-mode analysis of its law.
    fn with_condensation(
        model: &'a ContactModel<D, L>,
        bulk: Condensation,
        setup: SetupStats,
        settings: ContactSettings,
    ) -> Result<Self, ContactError> {
        let mut solver = Self {
            model,
            bulk,
            sliding: None,
            rigid_mode: Vec::new(),
            rigid_shift: Vec::new(),
            rigid_balance: Vec::new(),
            homogeneous: true,
            setup,
            settings,
        };
        solver.sliding = solver.sliding_mode()?;
        Ok(solver)
    }

    /// A solver for `model`, the same body and contact surface with another friction law or
    /// other friction parameters (`mu`, `eps`), that reuses this solver's factorisation and
    /// condensed matrices: no sparse work, only the `m x m` sliding-mode analysis.
    ///
    /// # Math
    /// `A~`, `P Z`, `N Z` and the unit-load states depend on the bulk operator, the contact
    /// rows and the spring only, never on the law: with `A` and `b_0`, `b_1` equal, the
    /// condensed equations `G(s) = s - t_2(sqrt(g22) x, sigma) - C x` of the new law are
    /// exact. Only the limiting ratios (which depend on the law) are computed again.
    ///
    /// # Errors
    /// [`ContactError::DifferentBody`] unless `model` has the same bulk operator, the same
    /// unit-load right-hand sides and the same contact nodes (compared exactly); failures of
    /// the sliding-mode analysis.
    pub fn with_model<'b, L2: FrictionLaw<f64>>(
        &self,
        model: &'b ContactModel<D, L2>,
    ) -> Result<BoundarySolver<'b, D, L2>, ContactError> {
        let (old, new) = (self.model, model);
        let differs = if old.system().pattern != new.system().pattern {
            Some("sparsity patterns")
        } else if old.system().values != new.system().values {
            Some("bulk operators")
        } else if (0..2).any(|i| old.rhs_basis(i) != new.rhs_basis(i)) {
            Some("unit-load right-hand sides")
        } else if old.contact_nodes() != new.contact_nodes() || old.active() != new.active() {
            Some("contact nodes")
        } else {
            None
        };
        if let Some(what) = differs {
            return Err(ContactError::DifferentBody { what });
        }
        BoundarySolver::with_condensation(
            model,
            self.bulk.clone(),
            SetupStats {
                factorisations: 0,
                bulk_solves: 0,
                ..self.setup
            },
            self.settings,
        )
    }

    /// The work done at construction.
    pub fn setup(&self) -> SetupStats {
        self.setup
    }

    /// The rigid sliding mode and the limiting tension ratios at `tau0 = 1`, if the bulk has one.
    pub fn sliding(&self) -> Option<SlidingMode> {
        self.sliding
    }

    /// The rigid sliding mode with its limiting ratios for the given `tau0` (the same as
    /// [`BoundarySolver::sliding`] for laws homogeneous in the normal stress).
    ///
    /// # Errors
    /// [`ContactError::NotConverged`] if the full-slip Newton iteration fails.
    pub fn sliding_at(&self, tau0: f64) -> Result<Option<SlidingMode>, ContactError> {
        match self.sliding {
            Some(mode) if !self.homogeneous && tau0 != mode.tau0 => {
                self.limits_at(tau0, mode.relative_singular_value).map(Some)
            }
            other => Ok(other),
        }
    }

    /// The settings.
    pub fn settings(&self) -> &ContactSettings {
        &self.settings
    }

    /// The frictionless condensed operator `I - C P Z`: if it is singular (relative singular
    /// value below [`SLIDING_MODE_THRESHOLD`]), the rigid sliding mode and its limits at
    /// `tau0 = 1`.
    fn sliding_mode(&mut self) -> Result<Option<SlidingMode>, ContactError> {
        let m = self.bulk.pz.nrows();
        let h0 = frictionless_operator(&self.bulk.spring, &self.bulk.pz);
        let svd = h0.svd().map_err(|_| ContactError::NotConverged {
            iterations: 0,
            residual: f64::NAN,
            load_factor: 0.0,
        })?;
        let sv = svd.S().column_vector();
        let relative = sv[m - 1] / sv[0];
        if relative.is_nan() || relative >= SLIDING_MODE_THRESHOLD {
            return Ok(None);
        }
        let v = svd.V();
        self.rigid_mode = (0..m).map(|k| v[(k, m - 1)]).collect();
        // oriented with y . z > 0, so that y . G increases with the rigid amplitude (friction
        // resists the sliding)
        let u = svd.U();
        let orient = if (0..m).map(|k| u[(k, m - 1)] * v[(k, m - 1)]).sum::<f64>() < 0.0 {
            -1.0
        } else {
            1.0
        };
        self.rigid_balance = (0..m).map(|k| orient * u[(k, m - 1)]).collect();
        self.rigid_shift = (0..m)
            .map(|i| {
                (0..m)
                    .map(|j| self.bulk.pz[(i, j)] * self.rigid_mode[j])
                    .sum()
            })
            .collect();
        self.homogeneous = self.law_is_homogeneous();
        self.limits_at(1.0, relative).map(Some)
    }

    /// Whether the law's saturated traction is homogeneous of degree 1 in the normal stress
    /// (`t(2 sigma) = 2 t(sigma)`, `t(0) = 0`: Coulomb-type laws). Then the limiting ratios do
    /// not depend on `tau0`; otherwise (Tresca, power laws) they are recomputed per `tau0`.
    fn law_is_homogeneous(&self) -> bool {
        let node = self.model.active_node(0);
        let u = 1e6 * self.model.slip_threshold();
        let t = |sigma: f64| self.model.traction_at(node, u, sigma).t2;
        let (t0, t1, t2) = (t(0.0), t(-1.0), t(-2.0));
        (t2 - 2.0 * t1).abs() <= 1e-12 * t2.abs() && t0.abs() <= 1e-14 * t1.abs().max(1e-300)
    }

    /// The limiting ratios `tau_max / tau0` of rigid sliding for the given `tau0`.
    fn limits_at(&self, tau0: f64, relative: f64) -> Result<SlidingMode, ContactError> {
        let mut ratios = [0.0; 2];
        for (r, direction) in ratios.iter_mut().zip([-1.0, 1.0]) {
            *r = self.full_slip_limit(direction, tau0)?;
        }
        Ok(SlidingMode {
            relative_singular_value: relative,
            lower_ratio: ratios[0].min(ratios[1]),
            upper_ratio: ratios[0].max(ratios[1]),
            tau0,
        })
    }

    /// The tension ratio at which the whole contact slides in `direction` (the limiting
    /// equilibrium), or `direction * inf` if friction holds every ratio that way.
    ///
    /// # Math
    /// At full slip the law's traction is saturated, `t_k = t(u_sat, sigma_k)`, independent of
    /// the slip. The condensed equations are then singular along the rigid mode `z` of
    /// `I - C P Z`, and equilibrium fixes the ratio `r`: Newton on the `m + 1` unknowns `(s, r)`
    /// ```text
    /// G_k(s, r) = s_k - t(u_sat, sigma_k) - c_k x_k = 0,    z . s = 0
    /// x = tau0 (x_a + r x_b) + P Z s,   sigma = tau0 (n_a + r n_b) + N Z s
    /// dG/ds = I - diag(dt/dsigma) N Z - C P Z,   dG/dr = -tau0 (diag(dt/dsigma) n_b + C x_b)
    /// ```
    /// (one step for laws affine in `sigma`: Coulomb, Tresca). The ratio bounds the loads only if
    /// the full-slip friction resists the sliding at (nearly) every node: with the paper's
    /// regularised Coulomb law, `t = mu sigma_n u / |u|` pushes *along* the slip where the contact
    /// is in tension, so a full-slip state whose wrong-way friction carries more than
    /// [`WRONG_WAY_SHARE_LIMIT`] of `sum_k w_k |t_k|` is no bound (`direction * inf`).
    fn full_slip_limit(&self, direction: f64, tau0: f64) -> Result<f64, ContactError> {
        let m = self.bulk.pz.nrows();
        let u = direction * 1e6 * self.model.slip_threshold();
        let z = &self.rigid_mode;
        let [(xa, na), (xb, nb)] = &self.bulk.base;
        let mut s = vec![0.0; m];
        let mut r = 1.0;
        let mut g = vec![0.0; m + 1];
        let mut t = vec![0.0; m];
        let mut dn = vec![0.0; m];
        let mut jac = Mat::<f64>::zeros(m + 1, m + 1);
        let mut residual = f64::INFINITY;
        for it in 0..=FULL_SLIP_ITERATIONS {
            let mut size = 0.0f64;
            for i in 0..m {
                let mut x = tau0 * (xa[i] + r * xb[i]);
                let mut sig = tau0 * (na[i] + r * nb[i]);
                for (j, sj) in s.iter().enumerate() {
                    x += self.bulk.pz[(i, j)] * sj;
                    sig += self.bulk.nz[(i, j)] * sj;
                }
                let nt = self.model.traction_at(self.model.active_node(i), u, sig);
                t[i] = nt.t2;
                dn[i] = nt.d_normal_stress;
                g[i] = s[i] - nt.t2 - self.bulk.spring[i] * x;
                size = size.max(s[i].abs() + nt.t2.abs() + (self.bulk.spring[i] * x).abs());
            }
            g[m] = z.iter().zip(&s).map(|(a, b)| a * b).sum();
            residual = g[..m].iter().fold(0.0f64, |a, x| a.max(x.abs())) / size.max(1e-300);
            if it > 0 && residual <= 1e-11 {
                return Ok(self.bound_or_unbounded(direction, r, &t));
            }
            if it == FULL_SLIP_ITERATIONS {
                break;
            }
            for i in 0..m {
                for j in 0..m {
                    jac[(i, j)] = f64::from(u8::from(i == j))
                        - dn[i] * self.bulk.nz[(i, j)]
                        - self.bulk.spring[i] * self.bulk.pz[(i, j)];
                }
                jac[(i, m)] = -tau0 * (dn[i] * nb[i] + self.bulk.spring[i] * xb[i]);
                jac[(m, i)] = z[i];
            }
            jac[(m, m)] = 0.0;
            // Row equilibration keeps the solve accurate when dt/dsigma is large.
            let scale: Vec<f64> = (0..=m)
                .map(|i| {
                    let a = (0..=m).fold(0.0f64, |a, j| a.max(jac[(i, j)].abs()));
                    if a > 0.0 { 1.0 / a } else { 1.0 }
                })
                .collect();
            let a = Mat::<f64>::from_fn(m + 1, m + 1, |i, j| scale[i] * jac[(i, j)]);
            let rhs = Mat::<f64>::from_fn(m + 1, 1, |i, _| -scale[i] * g[i]);
            let d = a.full_piv_lu().solve(&rhs);
            if (0..=m).any(|i| !d[(i, 0)].is_finite()) {
                break;
            }
            for i in 0..m {
                s[i] += d[(i, 0)];
            }
            r += d[(m, 0)];
        }
        Err(ContactError::NotConverged {
            iterations: FULL_SLIP_ITERATIONS,
            residual,
            load_factor: 0.0,
        })
    }

    /// `r` if it is a positive ratio and the friction of the full-slip state `t` resists the
    /// sliding in `direction` (wrong-way share at most [`WRONG_WAY_SHARE_LIMIT`]), else
    /// `direction * inf`.
    fn bound_or_unbounded(&self, direction: f64, r: f64, t: &[f64]) -> f64 {
        let (mut wrong, mut total) = (0.0, 0.0);
        for (k, tk) in t.iter().enumerate() {
            let w = self.model.active_node(k).traction_weight * tk.abs();
            total += w;
            if tk * direction > 0.0 {
                wrong += w;
            }
        }
        // no friction at all (mu = 0): the frictionless balance itself is the limit
        let resists = wrong <= WRONG_WAY_SHARE_LIMIT * total;
        if r.is_finite() && r > 0.0 && resists {
            r
        } else {
            direction * f64::INFINITY
        }
    }

    /// `(x0, n0)` for the loads.
    fn loaded_base(&self, loads: EndLoads) -> (Vec<f64>, Vec<f64>) {
        let [(xa, na), (xb, nb)] = &self.bulk.base;
        let x = xa
            .iter()
            .zip(xb)
            .map(|(a, b)| loads.tau0 * a + loads.tau_max * b)
            .collect();
        let s = na
            .iter()
            .zip(nb)
            .map(|(a, b)| loads.tau0 * a + loads.tau_max * b)
            .collect();
        (x, s)
    }

    /// Splits `s = s_p + a z` along the rigid mode `z` (`a = 0`, `s_p = s` without one).
    fn split_rigid(&self, s: &[f64]) -> (f64, Vec<f64>) {
        let z = &self.rigid_mode;
        if z.is_empty() {
            return (0.0, s.to_vec());
        }
        let a: f64 = z.iter().zip(s).map(|(z, s)| z * s).sum();
        (a, s.iter().zip(z).map(|(s, z)| s - a * z).collect())
    }

    /// `G(s)` and, optionally, `dG/ds`; returns `d t_2/d v^2` (spring included) and
    /// `d t_2 / d sigma` per node.
    ///
    /// # Math
    /// With a rigid mode `z` (`(I - C P Z) z = 0`, `N Z z = 0` exactly; `P Z z = x_r` the rigid
    /// displacement) and `s = s_p + a z`, the rigid amplitude `a` enters only through the
    /// displacement, never through `s - C x`, where it would cancel to rounding noise of size
    /// `|a|` (large while the slip homotopy lets friction hold the body softly):
    /// ```text
    /// x = x0 + P Z s_p + a x_r,   sigma = n0 + N Z s_p
    /// G = s_p - C P Z s_p - C x0 - t_2(sqrt(g22) beta x, sigma)
    /// dG/ds = J0 (I - z z^T) - diag(beta dt/dv) x_r z^T,   J0 = I - diag(dt/dv + c) P Z - diag(dt/dsigma) N Z
    /// ```
    /// (without a rigid mode `a = 0`: `G = s - t_2 - C x`, `dG/ds = J0`).
    fn eval(
        &self,
        beta: f64,
        x0: &[f64],
        n0: &[f64],
        s: &[f64],
        g: &mut [f64],
        jac: Option<&mut Mat<f64>>,
    ) -> (Vec<f64>, Vec<f64>) {
        let m = s.len();
        let (a, sp) = self.split_rigid(s);
        let mut dx = vec![0.0; m];
        let mut dn = vec![0.0; m];
        let mut friction = vec![0.0; m];
        let (pzs, nzs) = self.condensed_products(&sp);
        for (i, gi) in g.iter_mut().enumerate() {
            let zs = pzs[i];
            let sig = n0[i] + nzs[i];
            let shift = self.rigid_shift.get(i).map_or(0.0, |r| a * r);
            let x = x0[i] + zs + shift;
            let node = self.model.active_node(i);
            // slip homotopy: the law sees beta u (for regularised Coulomb: eps / beta)
            let nt = self.model.traction_at(node, beta * node.sqrt_g22 * x, sig);
            *gi = sp[i] - self.bulk.spring[i] * (x0[i] + zs) - nt.t2;
            friction[i] = beta * nt.d_tangential;
            dx[i] = friction[i] + self.bulk.spring[i];
            dn[i] = nt.d_normal_stress;
        }
        if let Some(jac) = jac {
            for j in 0..m {
                for i in 0..m {
                    jac[(i, j)] = f64::from(u8::from(i == j))
                        - dx[i] * self.bulk.pz[(i, j)]
                        - dn[i] * self.bulk.nz[(i, j)];
                }
            }
            let z = &self.rigid_mode;
            if !z.is_empty() {
                // J0 (I - z z^T) - diag(friction + tether) x_r z^T: the tether keeps the
                // matrix regular where the friction is saturated everywhere (the rigid
                // amplitude of the step is then replaced by `rebalance`)
                let jz0 = jac.as_ref() * faer::ColRef::from_slice(z);
                let jz: Vec<f64> = (0..m)
                    .map(|i| {
                        jz0[i]
                            + (friction[i] + RIGID_TETHER * self.bulk.spring[i])
                                * self.rigid_shift[i]
                    })
                    .collect();
                for j in 0..m {
                    for i in 0..m {
                        jac[(i, j)] -= jz[i] * z[j];
                    }
                }
            }
        }
        (dx, dn)
    }

    /// `(P Z s, N Z s)`: the tangential displacements and normal stresses that the condensed
    /// unknowns `s` add at the contact nodes (two dense matrix-vector products).
    fn condensed_products(&self, s: &[f64]) -> (faer::Col<f64>, faer::Col<f64>) {
        let s = faer::ColRef::from_slice(s);
        (
            self.bulk.pz.as_ref().as_ref() * s,
            self.bulk.nz.as_ref().as_ref() * s,
        )
    }

    /// The rounding-error bound of evaluating `G(s)` in floating point (max over the nodes):
    /// ```text
    /// floor_i = u (|s_p,i| + |t_2,i| + |c_i xb_i| + c_i X_i + |dt_2/dx_i| (X_i + |a x_r,i|) + |dt_2/dsigma_i| S_i)
    /// xb = x0 + P Z s_p,   X_i = |x0_i| + sum_j |PZ_ij s_p,j|,   S_i = |n0_i| + sum_j |NZ_ij s_p,j|
    /// ```
    /// (`u` the machine epsilon, `s = s_p + a z` as in [`BoundarySolver::eval`]): the sums carry a
    /// relative error `u`, amplified by the spring and by the law's stiffness `mu sigma_n / eps`
    /// in the stick zone. No Newton step can reduce the residual below it.
    fn roundoff_floor(&self, beta: f64, x0: &[f64], n0: &[f64], s: &[f64]) -> f64 {
        let m = s.len();
        let mut g = vec![0.0; m];
        let (dx, dn) = self.eval(beta, x0, n0, s, &mut g, None);
        let (a, sp) = self.split_rigid(s);
        (0..m)
            .map(|i| {
                let shift = self.rigid_shift.get(i).map_or(0.0, |r| (a * r).abs());
                let (mut ax, mut an, mut xb) = (x0[i].abs(), n0[i].abs(), x0[i]);
                for (j, sj) in sp.iter().enumerate() {
                    ax += (self.bulk.pz[(i, j)] * sj).abs();
                    an += (self.bulk.nz[(i, j)] * sj).abs();
                    xb += self.bulk.pz[(i, j)] * sj;
                }
                let c = self.bulk.spring[i];
                // G_i = s_p,i - c_i xb_i - t_2,i, so eval's residual gives the traction back
                let t2 = sp[i] - g[i] - c * xb;
                let friction = dx[i] - c;
                f64::EPSILON
                    * (sp[i].abs()
                        + t2.abs()
                        + (c * xb).abs()
                        + c * ax
                        + friction.abs() * (ax + shift)
                        + dn[i].abs() * an)
            })
            .fold(0.0, f64::max)
    }

    /// Moves `s` along the rigid mode (`s = s_p + a z`, `s_p` kept) so that the loads balance
    /// the friction along it, `phi(a) = y . G(s_p + a z) = 0`, within a slip change of
    /// [`SLIP_STEP_GROWTH`] times the current slip scale (as [`BoundarySolver::slip_step_cap`]).
    ///
    /// # Math
    /// `y^T (I - C P Z) = 0`, so `phi(a) = -y . C x0 - sum_k y_k t_2,k(x_k(a), sigma_k)` with
    /// `x(a) = x0 + P Z s_p + a x_r` and `sigma` independent of `a`: a scalar equation,
    /// non-decreasing in `a` while the contact is compressive (friction resists the sliding).
    /// Bracketed by doubling slip steps from `eps`, then solved by the Illinois false position.
    /// Without a bracket inside the slip limit, `a` moves to the limit if that lowers `|phi|`.
    /// Each evaluation costs `O(m)`: this keeps the rigid amplitude, which the Newton
    /// linearisation cannot fix where the friction is saturated (no stiffness along `z`),
    /// in balance at every iterate.
    fn rebalance(&self, beta: f64, x0: &[f64], n0: &[f64], s: &mut [f64]) {
        let (y, z, xr) = (&self.rigid_balance, &self.rigid_mode, &self.rigid_shift);
        if z.is_empty() {
            return;
        }
        let m = s.len();
        let (a0, sp) = self.split_rigid(s);
        let mut lin = vec![0.0; m];
        let mut xb = vec![0.0; m];
        let mut sig = vec![0.0; m];
        let (pzs, nzs) = self.condensed_products(&sp);
        for i in 0..m {
            xb[i] = x0[i] + pzs[i];
            lin[i] = sp[i] - self.bulk.spring[i] * xb[i];
            sig[i] = n0[i] + nzs[i];
        }
        let weight: Vec<f64> = (0..m)
            .map(|i| beta * self.model.active_node(i).sqrt_g22)
            .collect();
        let phi = |a: f64| -> f64 {
            (0..m)
                .map(|i| {
                    let node = self.model.active_node(i);
                    let t = self
                        .model
                        .traction_at(node, weight[i] * (xb[i] + a * xr[i]), sig[i]);
                    y[i] * (lin[i] - t.t2)
                })
                .sum()
        };
        let per_a = (0..m).fold(0.0f64, |u, i| u.max((weight[i] * xr[i]).abs()));
        let current = (0..m).fold(0.0f64, |u, i| {
            u.max((weight[i] * (xb[i] + a0 * xr[i])).abs())
        });
        let eps = self.model.slip_threshold();
        if !(per_a > 0.0 && per_a.is_finite()) {
            return;
        }
        let limit = SLIP_STEP_GROWTH * current.max(eps) / per_a;
        let f0 = phi(a0);
        if f0 == 0.0 || !f0.is_finite() {
            return;
        }
        let direction = -f0.signum();
        // bracket [lo, hi] with phi(lo) = f0 side and phi(hi) across zero
        let (mut lo, mut flo) = (a0, f0);
        let mut step = (eps / per_a).min(limit);
        let (mut hi, mut fhi);
        loop {
            hi = a0 + direction * step;
            fhi = phi(hi);
            if !fhi.is_finite() {
                return;
            }
            if fhi.signum() != f0.signum() {
                break;
            }
            if step >= limit {
                let a = if fhi.abs() < f0.abs() { hi } else { a0 };
                set_rigid(s, &sp, z, a);
                return;
            }
            (lo, flo) = (hi, fhi);
            step = (2.0 * step).min(limit);
        }
        // Illinois false position on [lo, hi]
        let mut side = 0i8;
        for _ in 0..REBALANCE_ITERATIONS {
            let a = (lo * fhi - hi * flo) / (fhi - flo);
            let fa = phi(a);
            if fa == 0.0 || (hi - lo).abs() <= 1e-15 * a.abs().max(per_a.recip() * eps) {
                lo = a;
                break;
            }
            if fa.signum() == flo.signum() {
                (lo, flo) = (a, fa);
                if side == -1 {
                    fhi *= 0.5;
                }
                side = -1;
            } else {
                (hi, fhi) = (a, fa);
                if side == 1 {
                    flo *= 0.5;
                }
                side = 1;
            }
        }
        let a = if flo.abs() <= fhi.abs() { lo } else { hi };
        set_rigid(s, &sp, z, a);
    }

    /// The largest step fraction `alpha <= 1` whose change of the physical slip stays within
    /// [`SLIP_STEP_GROWTH`] times the current slip scale:
    /// ```text
    /// alpha max_k |beta sqrt(g22_k) (P Z ds)_k| <= SLIP_STEP_GROWTH max(eps, max_k |beta sqrt(g22_k) x_k|)
    /// ```
    /// (`eps` the law's slip threshold). The regularised law changes over a slip of `eps`, so a
    /// Newton step far beyond the current slip scale is an extrapolation; along a rigid
    /// sliding mode held only by friction, it sends the body sliding away, where the saturated
    /// friction leaves a smaller but spurious residual.
    fn slip_step_cap(&self, beta: f64, x0: &[f64], s: &[f64], ds: &Mat<f64>) -> f64 {
        let m = s.len();
        let (mut current, mut step) = (0.0f64, 0.0f64);
        for (i, x0) in x0.iter().enumerate().take(m) {
            let (mut x, mut dx) = (*x0, 0.0);
            for j in 0..m {
                x += self.bulk.pz[(i, j)] * s[j];
                dx += self.bulk.pz[(i, j)] * ds[(j, 0)];
            }
            let w = beta * self.model.active_node(i).sqrt_g22;
            current = current.max((w * x).abs());
            step = step.max((w * dx).abs());
        }
        let bound = SLIP_STEP_GROWTH * current.max(self.model.slip_threshold());
        if step > bound { bound / step } else { 1.0 }
    }

    /// Damped Newton on `G(s) = 0` from `s`; `Ok(iterations)` or `Err((iterations, residual))`.
    /// Converged when `max |G| <= tolerance * scale`, or, once no step decreases `|G|` (or the
    /// iterations run out), when `max |G|` is within [`ROUNDOFF_FACTOR`] of the rounding floor
    /// of its own evaluation ([`BoundarySolver::roundoff_floor`]).
    fn newton(&self, beta: f64, loads: EndLoads, s: &mut [f64]) -> Result<usize, (usize, f64)> {
        self.newton_with(&self.settings, beta, loads, s)
    }

    fn newton_with(
        &self,
        settings: &ContactSettings,
        beta: f64,
        loads: EndLoads,
        s: &mut [f64],
    ) -> Result<usize, (usize, f64)> {
        let (x0, n0) = self.loaded_base(loads);
        let m = s.len();
        let gmax = (0..m)
            .map(|k| self.model.active_node(k).sqrt_g22)
            .fold(0.0f64, f64::max);
        let scale = (loads.magnitude() * gmax).max(f64::MIN_POSITIVE);
        let tol = settings.tolerance * scale;
        let mut g = vec![0.0; m];
        let mut trial = vec![0.0; m];
        let mut gt = vec![0.0; m];
        let mut jac = Mat::<f64>::zeros(m, m);
        // the rounding floor may excuse a residual up to 1e-6 relative, never more (a state
        // drifting along a sliding mode has a huge floor and is no solution)
        let accept_floor =
            |floor: f64| (ROUNDOFF_FACTOR * floor).min(MAX_ROUNDOFF_RESIDUAL * scale);
        let norm2 = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>();
        let max_norm = |v: &[f64]| v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        self.rebalance(beta, &x0, &n0, s);
        for it in 0..settings.max_iterations {
            self.eval(beta, &x0, &n0, s, &mut g, Some(&mut jac));
            let r = max_norm(&g);
            if !r.is_finite() {
                return Err((it, f64::INFINITY));
            }
            if r <= tol {
                return Ok(it);
            }
            let rhs = Mat::<f64>::from_fn(m, 1, |i, _| -g[i]);
            let ds = jac.partial_piv_lu().solve(&rhs);
            if (0..m).any(|i| !ds[(i, 0)].is_finite()) {
                return Err((it, r / scale));
            }
            let phi0 = norm2(&g);
            let alpha0 = self.slip_step_cap(beta, &x0, s, &ds);
            let mut alpha = alpha0;
            loop {
                for i in 0..m {
                    trial[i] = s[i] + alpha * ds[(i, 0)];
                }
                self.rebalance(beta, &x0, &n0, &mut trial);
                self.eval(beta, &x0, &n0, &trial, &mut gt, None);
                let phi = norm2(&gt);
                if phi.is_finite() && phi <= (1.0 - 1e-4 * alpha) * phi0 {
                    break;
                }
                alpha *= 0.5;
                if alpha < 1e-8 * alpha0 {
                    // no descent left: accept if the residual is at its rounding floor
                    return if r <= accept_floor(self.roundoff_floor(beta, &x0, &n0, s)) {
                        Ok(it)
                    } else {
                        Err((it + 1, r / scale))
                    };
                }
            }
            s.copy_from_slice(&trial);
        }
        self.eval(beta, &x0, &n0, s, &mut g, None);
        let r = max_norm(&g);
        if r <= tol.max(accept_floor(self.roundoff_floor(beta, &x0, &n0, s))) {
            Ok(settings.max_iterations)
        } else {
            Err((settings.max_iterations, r / scale))
        }
    }

    /// Checks the loads against the limiting ratios of a sliding mode.
    ///
    /// # Errors
    /// [`ContactError::NoEquilibrium`] outside the range.
    pub fn check_equilibrium(&self, loads: EndLoads) -> Result<(), ContactError> {
        if loads.tau0 <= 0.0 {
            return Ok(());
        }
        let Some(mode) = self.sliding_at(loads.tau0)? else {
            return Ok(());
        };
        let r = loads.tension_ratio();
        let tol = 1e-9 * r.abs().max(1.0);
        if r > mode.upper_ratio + tol || r < mode.lower_ratio - tol {
            return Err(ContactError::NoEquilibrium {
                ratio: r,
                lower: mode.lower_ratio,
                upper: mode.upper_ratio,
            });
        }
        Ok(())
    }

    /// The stuck contact unknowns for the loads (every contact node held in place).
    pub fn stuck_unknowns(&self, loads: EndLoads) -> Vec<f64> {
        self.bulk.stuck[0]
            .iter()
            .zip(&self.bulk.stuck[1])
            .map(|(a, b)| loads.tau0 * a + loads.tau_max * b)
            .collect()
    }

    /// Solves for the loads: plain Newton from the stuck state, then load continuation if
    /// that fails.
    ///
    /// # Errors
    /// [`ContactError::NoEquilibrium`] beyond limiting equilibrium; [`ContactError::NotConverged`].
    pub fn solve(&self, loads: EndLoads) -> Result<ContactSolution, ContactError> {
        self.solve_from(loads, None)
    }

    /// As [`BoundarySolver::solve`], starting Newton from the contact unknowns `s` of a nearby
    /// solution ([`ContactSolution::unknowns`]).
    ///
    /// # Errors
    /// See [`BoundarySolver::solve`].
    pub fn solve_from(
        &self,
        loads: EndLoads,
        guess: Option<&[f64]>,
    ) -> Result<ContactSolution, ContactError> {
        loads.check()?;
        self.check_equilibrium(loads)?;
        let m = self.bulk.pz.nrows();
        let mut s = guess.map_or_else(|| self.stuck_unknowns(loads), <[f64]>::to_vec);
        if s.len() != m {
            return Err(crate::ElasticityError::DimensionMismatch {
                quantity: "contact unknowns",
                expected: m,
                found: s.len(),
            }
            .into());
        }
        let mut iterations = 0;
        let mut steps = 1;
        let plain = ContactSettings {
            max_iterations: self.settings.max_iterations.min(25),
            ..self.settings
        };
        match self.newton_with(&plain, 1.0, loads, &mut s) {
            Ok(it) => iterations += it,
            Err((it, _)) => {
                iterations += it;
                match self.slip_homotopy(loads) {
                    Ok((it, st, sh)) => {
                        iterations += it;
                        steps = st;
                        s = sh;
                    }
                    Err(it) => {
                        iterations += it;
                        let (it, st) = self.continuation(loads, &mut s)?;
                        iterations += it;
                        steps = st;
                    }
                }
            }
        }
        self.finish(loads, &s, iterations, steps)
    }

    /// Continuation in the slip scale `beta` (the law sees `beta u`; for regularised Coulomb
    /// this is `eps / beta`) from the stuck state: `beta_0 = min(1e-3, eps / (10 U))`, where `U`
    /// is the largest physical tangential displacement of the spring-held linear solution
    /// (`s = 0`), so that every contact point starts on the smooth branch of the law
    /// (`|beta u| < eps`: all stick) however small `eps` is; then decade steps (halved on
    /// failure) up to `beta = 1`, each from the previous solution.
    /// `Ok((iterations, steps, s))` or `Err(iterations)`.
    fn slip_homotopy(&self, loads: EndLoads) -> Result<(usize, usize, Vec<f64>), usize> {
        let mut s = self.stuck_unknowns(loads);
        let (x0, _) = self.loaded_base(loads);
        let scale = x0.iter().enumerate().fold(0.0f64, |a, (k, x)| {
            a.max((self.model.active_node(k).sqrt_g22 * x).abs())
        });
        let start = if scale > 0.0 {
            (0.1 * self.model.slip_threshold() / scale).min(1e-3)
        } else {
            1e-3
        };
        let mut log_beta = start.log10();
        let mut step = 1.0f64;
        let mut iterations = 0;
        let mut steps = 0;
        let mut first = true;
        loop {
            steps += 1;
            if steps > self.settings.max_continuation_steps {
                return Err(iterations);
            }
            let target = if first {
                log_beta
            } else {
                (log_beta + step).min(0.0)
            };
            let mut trial = s.clone();
            match self.newton(10f64.powf(target), loads, &mut trial) {
                Ok(it) => {
                    iterations += it;
                    s = trial;
                    log_beta = target;
                    first = false;
                    if log_beta >= 0.0 {
                        return Ok((iterations, steps, s));
                    }
                    step = (step * 1.5).min(1.0);
                }
                Err((it, _)) => {
                    iterations += it;
                    if first {
                        return Err(iterations);
                    }
                    step *= 0.5;
                    if step < 1e-3 {
                        return Err(iterations);
                    }
                }
            }
        }
    }

    fn continuation(&self, loads: EndLoads, s: &mut [f64]) -> Result<(usize, usize), ContactError> {
        let m = s.len();
        let mut lambda = 0.0;
        let mut current = vec![0.0; m];
        let mut step = self.settings.initial_load_step;
        let mut iterations = 0;
        let mut steps = 0;
        let mut last_residual = f64::INFINITY;
        while lambda < 1.0 {
            if steps >= self.settings.max_continuation_steps {
                break;
            }
            steps += 1;
            let next = (lambda + step).min(1.0);
            let mut trial: Vec<f64> = if lambda > 0.0 {
                current.iter().map(|x| x * next / lambda).collect()
            } else {
                self.stuck_unknowns(loads.scaled(next))
            };
            match self.newton(1.0, loads.scaled(next), &mut trial) {
                Ok(it) => {
                    iterations += it;
                    lambda = next;
                    current = trial;
                    step = (step * 1.5).min(1.0);
                }
                Err((it, r)) => {
                    iterations += it;
                    last_residual = r;
                    step *= 0.5;
                    if step < self.settings.min_load_step {
                        break;
                    }
                }
            }
        }
        if lambda < 1.0 {
            return Err(ContactError::NotConverged {
                iterations,
                residual: last_residual,
                load_factor: lambda,
            });
        }
        s.copy_from_slice(&current);
        Ok((iterations, steps))
    }

    fn finish(
        &self,
        loads: EndLoads,
        s: &[f64],
        iterations: usize,
        steps: usize,
    ) -> Result<ContactSolution, ContactError> {
        let mut v = self.model.rhs(loads);
        for (k, sk) in s.iter().enumerate() {
            let node = self.model.active_node(k);
            v[node.tangential_row.expect("active")] += node.traction_weight * sk;
        }
        self.bulk
            .lu
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .solve_in_place(&mut v)?;
        let mut sol = ContactSolution::new(
            self.model,
            loads,
            v,
            SolveStats {
                method: "condensed",
                newton_iterations: iterations,
                continuation_steps: steps,
                residual: 0.0,
                linear_iterations: 0,
                factorisations: 0,
            },
        );
        if sol.stats.residual.is_nan() || sol.stats.residual > MAX_FULL_RESIDUAL {
            return Err(ContactError::NotConverged {
                iterations,
                residual: sol.stats.residual,
                load_factor: 1.0,
            });
        }
        sol.unknowns = s.to_vec();
        Ok(sol)
    }
}

/// `s = s_p + a z`.
fn set_rigid(s: &mut [f64], sp: &[f64], z: &[f64], a: f64) {
    for ((s, p), z) in s.iter_mut().zip(sp).zip(z) {
        *s = p + a * z;
    }
}

/// Factorises the stabilised bulk `A + sum_k w_k c_k e_row_k e_tdof_k^T` (`values` holds `A` on
/// the extended pattern) and returns `(P Z, N Z)`, `Z = A~^-1 W`, by blocked multi-right-hand-side
/// solves (at most [`CONDENSATION_BLOCK_ENTRIES`] doubles of workspace per block).
fn condense<D: Discretisation, L: FrictionLaw<f64>>(
    model: &ContactModel<D, L>,
    ext: &ExtendedPattern,
    values: &[f64],
    spring: &[f64],
    lu: &mut SparseLu,
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
fn frictionless_operator(spring: &[f64], pz: &Mat<f64>) -> Mat<f64> {
    let m = pz.nrows();
    Mat::<f64>::from_fn(m, m, |i, j| {
        f64::from(u8::from(i == j)) - spring[i] * pz[(i, j)]
    })
}

/// An estimate (power iteration on `H^T H`, within a few percent) of the largest singular
/// value of `h`.
fn largest_singular_value(h: &Mat<f64>) -> f64 {
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
fn project<D: Discretisation, L: FrictionLaw<f64>>(
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

fn row_max(pattern: &capstan_solvers::SparsityPattern, values: &[f64], row: usize) -> f64 {
    pattern
        .entries()
        .zip(values)
        .filter(|((r, _), _)| *r == row)
        .fold(0.0f64, |m, (_, v)| m.max(v.abs()))
        .max(1.0)
}
