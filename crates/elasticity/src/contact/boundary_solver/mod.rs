//! The boundary-only (condensed) contact solver: factor the bulk once, Newton on the contact
//! tractions only. Submodules: the condensation, the Newton iteration, the rigid mode, the
//! limiting ratios, the continuations, and the settings.

mod condensation;
mod continuation;
pub(crate) mod exact_start;
mod limits;
mod newton;
mod rigid;
pub(crate) mod semismooth;
mod settings;

pub use settings::{CONDENSED_SEMISMOOTH, ContactSettings, SetupStats, SlidingMode};

use std::sync::{Arc, Mutex};

use capstan_friction::FrictionLaw;
use capstan_solvers::{
    LinearBackend, LinearSettings, LinearSolver, Observer, Progress, SetUpPhase, SilentObserver,
};
use faer::Mat;
use faer::linalg::solvers::Solve;

use crate::contact::bulk_multigrid::{BackendCache, build_backend};
use crate::contact::error::ContactError;
use crate::contact::loads::EndLoads;
use crate::contact::model::ContactModel;
use crate::contact::operator::ContactOperator;
use crate::contact::solution::{ContactSolution, SolveStats};
use condensation::{
    Condensation, SchurInput, condense, condense_factored, factor_stabilised,
    frictionless_operator, largest_singular_value, project, row_max,
};

/// A converged condensed Newton run: `(iterations, relative residual)`.
pub(super) type Converged = (usize, f64);

/// Why a condensed Newton run (or a continuation of them) stopped without converging.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Failure {
    /// `(iterations, relative residual)` when it gave up.
    NotConverged(usize, f64),
    /// The observer asked to stop after this many iterations.
    Interrupted(usize),
}

impl Failure {
    /// Iterations spent.
    pub(super) fn iterations(self) -> usize {
        match self {
            Self::NotConverged(it, _) | Self::Interrupted(it) => it,
        }
    }
}

/// Largest relative residual of the full system accepted for a converged contact solution
/// (a safety net behind the condensed Newton's own test).
const MAX_FULL_RESIDUAL: f64 = 1e-6;

/// Largest singular value of `I - C P Z` below which the spring dominates every boundary mode
/// and is softened (see [`BoundarySolver`]).
const SPRING_DOMINANCE: f64 = 0.1;

/// Largest spread `max c_k / min c_k` of the per-node spring `c_k = A_kk / w_k` kept as it is
/// (see [`even_out_spring`]).
const SPRING_SPREAD: f64 = 100.0;

/// Replaces the per-node spring `c_k = A_kk / w_k` by its face average
/// `c = sum_k w_k c_k / sum_k w_k` (the stabilising force per unit traction weight) when it
/// spreads over more than [`SPRING_SPREAD`].
///
/// # Math
/// On a locally refined face (the corner mesh `fem-qp-corner`: 5 layers of ratio 0.3 give face
/// weights from about `1e-3` of a cell to a cell) `A_kk` stays of order one while `w_k` falls
/// with the element, so `c_k` spans three decades (4.3e4 to 4.6e7 on 12 x 2 cells, p = 5).
/// The unknown `s_k = t_2,k + c_k v^2_k` of the stiff nodes then carries the traction only in
/// its last digits, the stuck start `P Z s = -x` is solved from a matrix whose rows differ by
/// that factor, and the condensed Newton stalled (relative residual 19 from the stuck start,
/// at every load step). The solution does not depend on the spring (`G = 0` is
/// `A v - b - W t_2 = 0` for any `c`), so an even spring changes only the conditioning. Faces
/// with a spread below the bound (every uniform tensor grid and the default FD grid) keep
/// `A_kk / w_k` bit for bit.
fn even_out_spring<D: ContactOperator, L: FrictionLaw<f64>>(
    model: &ContactModel<D, L>,
    spring: &mut [f64],
) {
    let (lo, hi) = spring.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &c| {
        (lo.min(c), hi.max(c))
    });
    if !(lo > 0.0 && hi > SPRING_SPREAD * lo) {
        return;
    }
    let (mut force, mut weight) = (0.0, 0.0);
    for (k, c) in spring.iter().enumerate() {
        let w = model.active_node(k).traction_weight;
        force += w * c;
        weight += w;
    }
    if weight > 0.0 && (force / weight).is_finite() {
        spring.fill(force / weight);
    }
}

/// The boundary-only contact solver.
///
/// # Math
/// The friction traction acts only on the `m` tangential contact rows. With a stabilising
/// spring `c_k` on those rows (so the bulk stays invertible even when the body can slide
/// rigidly, as on a circle) and the unknowns `s_k = t_2,k + c_k v^2_k`:
/// ```text
/// A~ = A + sum_k w_k c_k e_row_k e_tdof_k^T         factorised once (`settings.linear`)
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
/// stiffest boundary mode) and the bulk condensed again. A spring spreading over more than
/// 100x along the face (a locally refined face: `fem-qp-corner`) is first replaced by its
/// face average `sum_k w_k c_k / sum_k w_k` (the solution does not depend on it). With a rigid mode `z` (`s = s_p + a z`),
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

impl<'a, D: ContactOperator, L: FrictionLaw<f64>> BoundarySolver<'a, D, L> {
    /// Factorises the stabilised bulk and forms the condensed matrices.
    ///
    /// # Errors
    /// Solver failures (a singular stabilised bulk); invalid settings.
    pub fn new(
        model: &'a ContactModel<D, L>,
        settings: ContactSettings,
    ) -> Result<Self, ContactError> {
        Self::new_observed(model, settings, &mut SilentObserver)
    }

    /// [`BoundarySolver::new`], reporting the factorisation and the condensation (one event
    /// per block of solves: `done` of `m` contact columns) to `observer` as
    /// [`capstan_solvers::SolveStage::SetUp`] events; on large 3-D bodies this set-up is most
    /// of the run.
    ///
    /// # Errors
    /// As [`BoundarySolver::new`]; [`ContactError::Interrupted`] when `observer` stops the
    /// set-up (polled between blocks of solves).
    pub fn new_observed(
        model: &'a ContactModel<D, L>,
        settings: ContactSettings,
        observer: &mut dyn Observer<f64>,
    ) -> Result<Self, ContactError> {
        settings.validate()?;
        refuse_unilateral(model)?;
        model.require_assembled(
            "the condensed solver needs the assembled bulk operator: solver.linear = \"matrix-free-mg\" runs with solver.nonlinear = \"full-newton\" or \"auto\"",
        )?;
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
        even_out_spring(model, &mut spring);
        let mut lu = build_backend(
            settings.linear,
            &LinearSettings::default(),
            model.discretisation(),
            &BackendCache::default(),
            false,
        )?;
        lu.analyse(&ext.pattern)?;
        // the direct default condenses plane bodies from the Schur complements (one partial
        // factorisation, no solves); other backends and 3-D bodies by `m` solves (on a 3-D Q2
        // box with a rigid sliding mode the Schur route moved a limiting ratio by 2%: the
        // near-singular frictionless operator amplifies its round-off; to be understood)
        let schur_input = if settings.linear == LinearBackend::LU
            && (model.discretisation().plane().is_some() || model.discretisation().mesh().is_some())
        {
            Some(SchurInput::new(model)?)
        } else {
            None
        };
        // the partial factorisation for the Schur complements on a second thread, beside the
        // factorisation of the stabilised bulk on this one
        observer.iteration(&Progress::set_up(SetUpPhase::Factorisation, 0, 1));
        let (schur, factored) = std::thread::scope(|scope| {
            let side = schur_input.map(|input| scope.spawn(move || input.compute()));
            let factored = factor_stabilised(model, ext, &values, &spring, &mut *lu);
            let schur = side.map(|side| {
                side.join()
                    .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
            });
            (schur, factored)
        });
        factored?;
        let schur = schur.transpose()?.flatten();
        observer.iteration(&Progress::set_up(SetUpPhase::Factorisation, 1, 1));
        let (mut pz, mut nz) =
            condense_factored(model, &spring, &mut *lu, schur.as_ref(), observer)?;
        // `(P Z, N Z)` for a spring, with the bulk factorised (again) for it
        let mut condense_with = |spring: &[f64], lu: &mut dyn LinearSolver<f64>| {
            condense(model, ext, &values, spring, lu, schur.as_ref(), observer)
        };
        let mut factorisations = 1;
        // A spring far stiffer than every boundary mode of the body (thin bodies: the diagonal
        // grows like 1 / dx3^2, the boundary stiffness like h) makes `s - C x` cancel to
        // rounding noise: soften it to the body's stiffest boundary mode and condense again.
        let top = largest_singular_value(&frictionless_operator(&spring, &pz));
        if top.is_finite() && top > 0.0 && top < SPRING_DOMINANCE {
            for c in &mut spring {
                *c *= top;
            }
            (pz, nz) = condense_with(&spring, &mut lu)?;
            factorisations += 1;
        }
        let mut unit_state = |mut v: Vec<f64>| -> Result<(Vec<f64>, Vec<f64>), ContactError> {
            lu.solve_in_place(&mut v)?;
            Ok(project(model, &v))
        };
        let b0 = unit_state(model.rhs_basis(0).to_vec())?;
        let b1 = unit_state(model.rhs_basis(1).to_vec())?;
        let fixed_state = model.fixed_rhs().map(&mut unit_state).transpose()?;
        // P Z s = -x_i: the contact tractions that hold every contact node in place.
        let lu_pz = pz.partial_piv_lu();
        let hold = |x: &[f64]| {
            let rhs = Mat::<f64>::from_fn(m, 1, |i, _| -x[i]);
            let s = lu_pz.solve(&rhs);
            (0..m).map(|i| s[(i, 0)]).collect::<Vec<f64>>()
        };
        let stuck = [hold(&b0.0), hold(&b1.0)];
        let fixed = fixed_state.map(|f| {
            let s = hold(&f.0);
            (f, s)
        });
        if stuck
            .iter()
            .chain(fixed.iter().map(|f| &f.1))
            .flatten()
            .any(|x| !x.is_finite())
        {
            return Err(capstan_solvers::SolverError::Singular { pivot: None }.into());
        }
        let bulk = Condensation {
            lu: Arc::new(Mutex::new(lu)),
            spring,
            pz: Arc::new(pz),
            nz: Arc::new(nz),
            base: [b0, b1],
            stuck,
            fixed,
        };
        let setup = SetupStats {
            contact_unknowns: m,
            bulk_unknowns: n,
            factorisations,
            bulk_solves: usize::from(model.fixed_rhs().is_some())
                + if schur.is_some() {
                    2
                } else {
                    factorisations * m + 2
                },
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
        let sliding = solver.sliding_mode();
        // Fixed loads (a body force) make the right-hand side affine in the end loads: the
        // limiting ratios, computed for `b` linear in them, do not apply (the rigid mode and
        // its balance, set above, still do).
        solver.sliding = if solver.bulk.fixed.is_some() {
            None
        } else {
            sliding?
        };
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
        refuse_unilateral(model)?;
        let differs = body_difference(self.model, model);
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
        let mut s: Vec<f64> = self.bulk.stuck[0]
            .iter()
            .zip(&self.bulk.stuck[1])
            .map(|(a, b)| loads.tau0 * a + loads.tau_max * b)
            .collect();
        if let Some((_, fixed)) = &self.bulk.fixed {
            s.iter_mut().zip(fixed).for_each(|(s, f)| *s += f);
        }
        s
    }

    /// Solves for the loads: plain Newton from the stuck state, then load continuation if
    /// that fails.
    ///
    /// # Errors
    /// [`ContactError::NoEquilibrium`] beyond limiting equilibrium; [`ContactError::NotConverged`].
    pub fn solve(&self, loads: EndLoads) -> Result<ContactSolution, ContactError> {
        self.solve_from_observed(loads, None, &mut SilentObserver)
    }

    /// As [`BoundarySolver::solve`], reporting every Newton iterate and continuation step to
    /// `observer` (stages [`capstan_solvers::SolveStage::CondensedNewton`] with stick/slip counts and
    /// [`capstan_solvers::SolveStage::Continuation`]); [`ContactError::Interrupted`] when it asks to stop.
    ///
    /// # Errors
    /// See [`BoundarySolver::solve`].
    pub fn solve_observed(
        &self,
        loads: EndLoads,
        observer: &mut dyn Observer<f64>,
    ) -> Result<ContactSolution, ContactError> {
        self.solve_from_observed(loads, None, observer)
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
        self.solve_from_observed(loads, guess, &mut SilentObserver)
    }

    /// [`BoundarySolver::solve_from`] with an observer (see [`BoundarySolver::solve_observed`]).
    ///
    /// # Errors
    /// See [`BoundarySolver::solve`]; [`ContactError::Interrupted`].
    pub fn solve_from_observed(
        &self,
        loads: EndLoads,
        guess: Option<&[f64]>,
        observer: &mut dyn Observer<f64>,
    ) -> Result<ContactSolution, ContactError> {
        let (s, iterations, steps) =
            self.unknowns_from(loads, guess, self.settings.tolerance, observer)?;
        self.finish_on(self.model, loads, &s, iterations, steps, "condensed")
    }

    /// The contact unknowns of [`BoundarySolver::solve_from_observed`] without the field:
    /// `(s, Newton iterations, continuation steps)`. The plain Newton from `guess` (or the
    /// stuck state) stops at `max |G| <= plain_tolerance * scale`; the slip homotopy and the
    /// load continuation it falls back to keep `settings.tolerance`.
    fn unknowns_from(
        &self,
        loads: EndLoads,
        guess: Option<&[f64]>,
        plain_tolerance: f64,
        observer: &mut dyn Observer<f64>,
    ) -> Result<(Vec<f64>, usize, usize), ContactError> {
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
        let interrupted = |iterations| ContactError::Interrupted { iterations };
        let mut iterations = 0;
        let mut steps = 1;
        let plain = ContactSettings {
            max_iterations: self.settings.max_iterations.min(25),
            tolerance: plain_tolerance,
            ..self.settings
        };
        match self.newton_with(&plain, 1.0, loads, &mut s, observer) {
            Ok((it, _)) => iterations += it,
            Err(Failure::Interrupted(it)) => return Err(interrupted(it)),
            Err(Failure::NotConverged(it, _)) => {
                iterations += it;
                if let Some(no_equilibrium) = self.past_runaway(loads)? {
                    return Err(no_equilibrium);
                }
                match self.slip_homotopy(loads, observer) {
                    Ok((it, st, sh)) => {
                        iterations += it;
                        steps = st;
                        s = sh;
                    }
                    Err(Failure::Interrupted(it)) => return Err(interrupted(iterations + it)),
                    Err(failure) => {
                        iterations += failure.iterations();
                        let (it, st) = self.continuation(loads, &mut s, observer)?;
                        iterations += it;
                        steps = st;
                    }
                }
            }
        }
        Ok((s, iterations, steps))
    }

    /// The solution of `model` (this solver's body) for the contact unknowns `s`:
    /// `v = A~^{-1} (b + W s)`, checked against the full residual of `model`.
    fn finish_on<L2: FrictionLaw<f64>>(
        &self,
        model: &ContactModel<D, L2>,
        loads: EndLoads,
        s: &[f64],
        iterations: usize,
        steps: usize,
        method: &'static str,
    ) -> Result<ContactSolution, ContactError> {
        let v = self.field_of(model, loads, s)?;
        solution_of(model, loads, v, s, iterations, steps, method)
    }

    /// The field `v = A~^{-1} (b + W s)` of the condensed unknowns `s` on `model`'s body (one
    /// solve on this solver's factorisation).
    fn field_of<L2: FrictionLaw<f64>>(
        &self,
        model: &ContactModel<D, L2>,
        loads: EndLoads,
        s: &[f64],
    ) -> Result<Vec<f64>, ContactError> {
        let mut v = model.rhs(loads);
        for (k, sk) in s.iter().enumerate() {
            let node = model.active_node(k);
            v[node.tangential_row.expect("active")] += node.traction_weight * sk;
        }
        self.bulk
            .lu
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .solve_in_place(&mut v)?;
        Ok(v)
    }
}

/// The solution of `model` with the field `v` of the condensed unknowns `s`; refused
/// ([`ContactError::NotConverged`]) when its full-system residual is above
/// `MAX_FULL_RESIDUAL`.
fn solution_of<D: ContactOperator, L2: FrictionLaw<f64>>(
    model: &ContactModel<D, L2>,
    loads: EndLoads,
    v: Vec<f64>,
    s: &[f64],
    iterations: usize,
    steps: usize,
    method: &'static str,
) -> Result<ContactSolution, ContactError> {
    let mut sol = ContactSolution::new(
        model,
        loads,
        v,
        SolveStats {
            method,
            newton_iterations: iterations,
            continuation_steps: steps,
            residual: 0.0,
            linear_iterations: 0,
            factorisations: 0,
        },
    )?;
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

/// What differs between the bodies of two models (`None`: the same bulk operator, unit-load
/// right-hand sides and contact nodes, compared exactly), so that a condensation of one is
/// exact for the other.
fn body_difference<D, L: FrictionLaw<f64>, L2: FrictionLaw<f64>>(
    old: &ContactModel<D, L>,
    new: &ContactModel<D, L2>,
) -> Option<&'static str> {
    if old.system().pattern != new.system().pattern {
        Some("sparsity patterns")
    } else if old.system().values != new.system().values {
        Some("bulk operators")
    } else if old.loads().len() != new.loads().len()
        || (0..old.loads().len()).any(|i| old.rhs_basis(i) != new.rhs_basis(i))
        || old.fixed_rhs() != new.fixed_rhs()
    {
        Some("unit-load right-hand sides")
    } else if old.contact_nodes() != new.contact_nodes() || old.active() != new.active() {
        Some("contact nodes")
    } else {
        None
    }
}

/// The condensed solver keeps `v^3 = 0` on the contact face (it condenses onto the tangential
/// tractions only) and solves smooth laws: a unilateral model or one with exact friction is
/// refused, naming the key that picks another solver.
fn refuse_unilateral<D, L: FrictionLaw<f64>>(
    model: &ContactModel<D, L>,
) -> Result<(), ContactError> {
    if model.is_unilateral() {
        return Err(ContactError::Unsupported {
            field: "solver.nonlinear",
            message: "the condensed `newton` keeps v^3 = 0 on the contact face; unilateral contact (`contact.kind = \"unilateral\"`) needs `full-newton` or `jacobi-newton`",
        });
    }
    if model.is_exact_friction() {
        return Err(ContactError::Unsupported {
            field: "solver.nonlinear",
            message: "the condensed `newton` solves regularised laws only; exact (nonsmooth) friction (`friction.law = \"exact-coulomb\"`, ...) needs `full-newton`",
        });
    }
    Ok(())
}
