//! Semismooth Newton for exact (nonsmooth) friction on the condensed contact face: the
//! Alart–Curnier rows of [`crate::contact::ContactModel::into_exact_friction`] written in the
//! condensed unknowns, reusing a [`BoundarySolver`]'s factorisation and condensed matrices.

use super::newton::report_face_iterate;
use capstan_friction::{FrictionLaw, FrictionState, Projection};
use capstan_solvers::{
    Flow, NewtonDirection, NewtonFailure, NewtonIterate, NewtonSystem, Observer, newton_drive,
};
use faer::Mat;
use faer::linalg::solvers::Solve;

use super::newton::{MAX_ROUNDOFF_RESIDUAL, ROUNDOFF_FACTOR};
use super::rigid::{illinois, set_rigid};
use super::settings::CONDENSED_SEMISMOOTH;
use super::{BoundarySolver, body_difference, solution_of};
use crate::contact::error::ContactError;
use crate::contact::exact_friction::{ExactFriction, SLIP_JACOBIAN_BLEND};
use crate::contact::loads::EndLoads;
use crate::contact::model::{ContactModel, ExactRows};
use crate::contact::operator::ContactOperator;
use crate::contact::solution::ContactSolution;

impl<D: ContactOperator, L: FrictionLaw<f64>> BoundarySolver<'_, D, L> {
    /// Exact (nonsmooth) friction on the condensed contact face: semismooth Newton on the
    /// Alart–Curnier rows of `exact` ([`ContactModel::into_exact_friction`], bilateral), in
    /// the condensed unknowns `s` of this solver, from `start` (the unknowns of a nearby
    /// solution, [`ContactSolution::unknowns`]: typically this solver's own solution of the
    /// law's regularisation). No sparse work but one solve for the field at the end.
    ///
    /// # Math
    /// With the condensed maps of [`BoundarySolver`] (`x = x0 + P Z s` the tangential
    /// displacements, `sigma = n0 + N Z s` the normal stresses at the contact entries) the
    /// covariant friction traction an entry's row carries is `t = s - C x` (the free row
    /// `q = A v - b = W (s - C x)`), and per site (frames `f_e`, `F = [f_e]`)
    /// ```text
    /// tau = F^{-T} t,   u = F (x - x_ref),   G_e(s) = t_e - f_e . P_C(sigma)(tau - r u)
    /// ```
    /// (`r` the site's augmentation): `G = 0` is exactly the full system `R(v) = 0` of
    /// [`ContactModel::into_exact_friction`] at `v = A~^{-1} (b + W s)`. The generalised
    /// Jacobian (`J = dP/dtrial`, blended `(1 - delta) J + delta I` at sliding sites as on the
    /// full system) is dense `m x m`:
    /// ```text
    /// dG_e/ds = (e_e - c_e PZ_e) - sum_f (f_e^T J F^{-T}_f) (e_f - c_f PZ_f)
    ///           + r sum_f (f_e^T J f_f) PZ_f - (f_e . dP/dsigma) NZ_site
    /// ```
    /// so each semismooth step is one dense LU of size `m` (no sparse factorisation). With a
    /// rigid sliding mode `z` the residual is evaluated as in [`BoundarySolver`]'s Newton
    /// (`s = s_p + a z`, `a` only in the displacement), the Jacobian being the same matrix.
    /// When no site of `start` sticks and the body has a rigid mode (the regularised start on
    /// the circle), the iteration starts at the rigid amplitude that balances the loads
    /// against friction along the mode (`y . G = 0`, a scalar root, where the neutral site
    /// sticks), not at `start`'s: there every site slides, `J` has only the blend `delta`
    /// along `z`, and the first full step would slide the body.
    /// Damped by Armijo backtracking on `|G|_2^2`; converged when `max |G| <= tolerance *
    /// scale` (the condensed Newton's test and scale), or at the rounding floor of `G`. Every
    /// iterate reports its active set (stick and slip sites of the projection) to `observer`
    /// ([`capstan_solvers::SolveStage::CondensedNewton`]).
    ///
    /// # Errors
    /// [`ContactError::Unsupported`] naming `friction.law` when `exact` has no exact friction,
    /// or `contact.kind` when it is unilateral; [`ContactError::DifferentBody`] unless `exact`
    /// has this solver's body (bulk operator, unit loads, contact nodes);
    /// [`crate::ElasticityError::DimensionMismatch`] for a start of the wrong length;
    /// [`ContactError::NotConverged`] when the budget `max_iterations` is spent or no step
    /// descends; [`ContactError::Interrupted`] when `observer` stops it.
    pub fn solve_exact_from_observed<L2: FrictionLaw<f64>>(
        &self,
        exact: &ContactModel<D, L2>,
        loads: EndLoads,
        start: &[f64],
        observer: &mut dyn Observer<f64>,
    ) -> Result<ContactSolution, ContactError> {
        loads.check()?;
        let Some(friction) = exact.exact_friction() else {
            return Err(ContactError::Unsupported {
                field: "friction.law",
                message: "the condensed semismooth Newton solves exact (nonsmooth) friction only (`exact-coulomb`, `exact-orthotropic-coulomb`); smooth laws run on the condensed Newton",
            });
        };
        if exact.is_unilateral() {
            return Err(ContactError::Unsupported {
                field: "contact.kind",
                message: "the condensed semismooth Newton keeps v^3 = 0 on the contact face; unilateral contact needs `full-newton`",
            });
        }
        if let Some(what) = body_difference(self.model, exact) {
            return Err(ContactError::DifferentBody { what });
        }
        let (s, iterations) = self.semismooth_face(friction, loads, start, observer)?;
        self.finish_on(exact, loads, &s, iterations, 1, CONDENSED_SEMISMOOTH)
    }

    /// [`BoundarySolver::solve_exact_from_observed`] on exact friction rows built for this
    /// solver's own model ([`ContactModel::exact_rows`]), so that no second (exact) model is
    /// needed while the solver borrows the first: the same semismooth Newton and the same
    /// field, returned before the exact model exists. [`ExactFaceSolution::into_solution`]
    /// then evaluates it on the exact model (this model with `rows` installed,
    /// [`ContactModel::with_exact_rows`]), to the bit the solution of
    /// [`BoundarySolver::solve_exact_from_observed`].
    ///
    /// # Errors
    /// As [`BoundarySolver::solve_exact_from_observed`] ([`ContactError::DifferentBody`] when
    /// `rows` were built for another body, `contact.kind` for a unilateral model).
    pub fn solve_exact_rows_observed(
        &self,
        rows: &ExactRows,
        loads: EndLoads,
        start: &[f64],
        observer: &mut dyn Observer<f64>,
    ) -> Result<ExactFaceSolution, ContactError> {
        loads.check()?;
        if self.model.is_unilateral() {
            return Err(ContactError::Unsupported {
                field: "contact.kind",
                message: "the condensed semismooth Newton keeps v^3 = 0 on the contact face; unilateral contact needs `full-newton`",
            });
        }
        if !rows.built_for(self.model) {
            return Err(ContactError::DifferentBody {
                what: "contact nodes",
            });
        }
        let (unknowns, iterations) =
            self.semismooth_face(&rows.friction, loads, start, observer)?;
        let displacement = self.field_of(self.model, loads, &unknowns)?;
        Ok(ExactFaceSolution {
            unknowns,
            displacement,
            iterations,
            loads,
        })
    }

    /// The semismooth Newton on the condensed face for `friction` (built for this solver's
    /// body) from `start`: the converged unknowns and the iteration count.
    fn semismooth_face(
        &self,
        friction: &ExactFriction,
        loads: EndLoads,
        start: &[f64],
        observer: &mut dyn Observer<f64>,
    ) -> Result<(Vec<f64>, usize), ContactError> {
        let body = self.model;
        let m = self.bulk.pz.nrows();
        if start.len() != m {
            return Err(crate::ElasticityError::DimensionMismatch {
                quantity: "contact unknowns",
                expected: m,
                found: start.len(),
            }
            .into());
        }
        let (x0, n0) = self.loaded_base(loads);
        let gmax = (0..m)
            .map(|k| body.active_node(k).sqrt_g22)
            .fold(0.0f64, f64::max);
        let scale = (loads.magnitude() * gmax).max(f64::MIN_POSITIVE);
        let settings = &self.settings;
        let tol = settings.tolerance * scale;
        let policy = settings.face_policy(tol);
        let mut system = ExactFace {
            solver: self,
            body,
            friction,
            x0: &x0,
            n0: &n0,
            scale,
            max_iterations: settings.max_iterations,
            jac: Mat::<f64>::zeros(m, m),
            g: vec![0.0; m],
            last: (Vec::new(), (0, 0)),
            observer,
        };
        let mut s = start.to_vec();
        // no site on the stick branch (the regularised start): the step has no stiffness
        // along the rigid mode; start from the balanced amplitude instead
        system.balance_unstuck(&mut s);
        let accept_floor =
            |floor: f64| (ROUNDOFF_FACTOR * floor).min(MAX_ROUNDOFF_RESIDUAL * scale);
        let not_converged = |iterations, residual: f64| ContactError::NotConverged {
            iterations,
            residual: residual / scale,
            load_factor: 1.0,
        };
        let iterations = match newton_drive(&mut system, &mut s, &policy) {
            Ok(done) => done.iterations,
            Err(NewtonFailure::Problem(e)) => return Err(e),
            Err(NewtonFailure::Interrupted { iteration }) => {
                return Err(ContactError::Interrupted {
                    iterations: iteration,
                });
            }
            Err(
                NewtonFailure::LineSearch {
                    iterations: it,
                    residual: r,
                    ..
                }
                | NewtonFailure::NotConverged {
                    iterations: it,
                    residual: r,
                },
            ) => {
                if r <= accept_floor(system.roundoff_floor(&s)) {
                    it
                } else {
                    return Err(not_converged(it, r));
                }
            }
            Err(
                NewtonFailure::Stagnated {
                    iterations: it,
                    residual: r,
                }
                | NewtonFailure::Diverged {
                    iteration: it,
                    residual: r,
                },
            ) => return Err(not_converged(it, r)),
            Err(NewtonFailure::NonFinite { iteration, .. }) => {
                return Err(not_converged(iteration, f64::INFINITY));
            }
        };
        Ok((s, iterations))
    }
}

/// Doubling steps of the bracket search of [`ExactFace::balanced_amplitude`].
const BALANCE_DOUBLINGS: usize = 200;

/// The solution of [`BoundarySolver::solve_exact_rows_observed`] before its exact model is
/// installed: the condensed unknowns, the field and the semismooth iterations.
#[derive(Debug, Clone)]
pub struct ExactFaceSolution {
    unknowns: Vec<f64>,
    displacement: Vec<f64>,
    iterations: usize,
    loads: EndLoads,
}

impl ExactFaceSolution {
    /// The semismooth Newton iterations.
    pub fn iterations(&self) -> usize {
        self.iterations
    }

    /// The solution on `exact`, the solver's model with the rows installed
    /// ([`ContactModel::with_exact_rows`]): quantities, stick/slip and the full-system
    /// residual of the exact rows, as [`BoundarySolver::solve_exact_from_observed`] gives them.
    ///
    /// # Errors
    /// [`ContactError::Unsupported`] naming `friction.law` when `exact` has no exact friction;
    /// [`crate::ElasticityError::DimensionMismatch`] for a model of another size;
    /// [`ContactError::NotConverged`] when the full-system residual of `exact` is above the
    /// condensed solver's bound (another body).
    pub fn into_solution<D: ContactOperator, L2: FrictionLaw<f64>>(
        self,
        exact: &ContactModel<D, L2>,
    ) -> Result<ContactSolution, ContactError> {
        if !exact.is_exact_friction() {
            return Err(ContactError::Unsupported {
                field: "friction.law",
                message: "the condensed semismooth solution is evaluated on the model with its exact friction rows installed (`ContactModel::with_exact_rows`)",
            });
        }
        let expected = exact.rhs(self.loads).len();
        if self.displacement.len() != expected || self.unknowns.len() != exact.active().len() {
            return Err(crate::ElasticityError::DimensionMismatch {
                quantity: "unknowns",
                expected,
                found: self.displacement.len(),
            }
            .into());
        }
        solution_of(
            exact,
            self.loads,
            self.displacement,
            &self.unknowns,
            self.iterations,
            1,
            CONDENSED_SEMISMOOTH,
        )
    }
}

/// [`BoundarySolver::solve_exact_from_observed`]'s problem for the Newton driver.
struct ExactFace<'s, 'b, 'o, D, L: FrictionLaw<f64>> {
    solver: &'s BoundarySolver<'b, D, L>,
    /// The solver's model (its sites, frames and slip reference are the exact model's).
    body: &'s ContactModel<D, L>,
    friction: &'s ExactFriction,
    x0: &'s [f64],
    n0: &'s [f64],
    /// `max |G|` is reported relative to it.
    scale: f64,
    /// The iteration cap (its iterate is not reported).
    max_iterations: usize,
    jac: Mat<f64>,
    g: Vec<f64>,
    /// The last point `G` was evaluated at and its `(stick, slip)` counts (the accepted
    /// iterate is the line search's last evaluation: its report needs no new evaluation).
    last: (Vec<f64>, (usize, usize)),
    observer: &'o mut dyn Observer<f64>,
}

/// The condensed quantities at `s`: `x = x0 + P Z s_p + a x_r`, the covariant tractions
/// `t = s_p - C (x0 + P Z s_p)` and the normal stresses `sigma = n0 + N Z s_p`.
struct FaceFields {
    x: Vec<f64>,
    t: Vec<f64>,
    sigma: Vec<f64>,
}

impl<D: ContactOperator, L: FrictionLaw<f64>> ExactFace<'_, '_, '_, D, L> {
    fn fields(&self, s: &[f64]) -> FaceFields {
        let solver = self.solver;
        let m = s.len();
        let (a, sp) = solver.split_rigid(s);
        let (pzs, nzs) = solver.condensed_products(&sp);
        let spring = &solver.bulk.spring;
        let mut f = FaceFields {
            x: vec![0.0; m],
            t: vec![0.0; m],
            sigma: vec![0.0; m],
        };
        for i in 0..m {
            let xb = self.x0[i] + pzs[i];
            f.x[i] = xb + solver.rigid_shift.get(i).map_or(0.0, |r| a * r);
            f.t[i] = sp[i] - spring[i] * xb;
            f.sigma[i] = self.n0[i] + nzs[i];
        }
        f
    }

    /// `(|x0| + sum_j |PZ_ij s_p,j|, |s_p,i|)` per entry `i`: the rounding scales of `x` and
    /// `s_p` (only [`ExactFace::roundoff_floor`] needs them).
    fn rounding_scales(&self, s: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let solver = self.solver;
        let m = s.len();
        let (_, sp) = solver.split_rigid(s);
        let x_abs = (0..m)
            .map(|i| {
                self.x0[i].abs()
                    + (0..m)
                        .map(|j| (solver.bulk.pz[(i, j)] * sp[j]).abs())
                        .sum::<f64>()
            })
            .collect();
        (x_abs, sp.iter().map(|v| v.abs()).collect())
    }

    /// The projection at site `j`: `P_C(sigma)(tau - r u)` with `tau`, `u` of the site.
    fn project(&self, j: usize, f: &FaceFields) -> (Projection<f64>, [f64; 2], [f64; 2]) {
        let members = &self.body.sites().members[j];
        let (inverse, r) = self.friction.site_data(j);
        let mut tau = [0.0; 2];
        for (e, &i) in members.iter().enumerate() {
            for c in 0..2 {
                tau[c] += inverse[e][c] * f.t[i];
            }
        }
        let u = self.body.site_slip(j, 1.0, |k| f.x[k]);
        let trial = [tau[0] - r * u[0], tau[1] - r * u[1]];
        let sigma = f.sigma[members[0]];
        let projection = self
            .friction
            .law()
            .project(trial, sigma)
            .unwrap_or_else(|_| {
                // a non-finite iterate: a non-finite residual, which the line search rejects
                Projection::new([f64::NAN; 2], [[0.0; 2]; 2], [0.0; 2], FrictionState::Slip)
            });
        (projection, tau, u)
    }

    /// `G(s)` into `g` and, optionally, the generalised Jacobian into `jac`; returns the
    /// `(stick, slip)` site counts of the projection.
    #[allow(clippy::needless_range_loop)] // mirrors f_e^T J F^{-T}_f
    fn eval(&self, s: &[f64], g: &mut [f64], mut jac: Option<&mut Mat<f64>>) -> (usize, usize) {
        let m = s.len();
        let f = self.fields(s);
        let bulk = &self.solver.bulk;
        let sites = self.body.sites();
        let (mut stick, mut slip) = (0, 0);
        if let Some(jac) = jac.as_deref_mut() {
            for j in 0..m {
                for i in 0..m {
                    jac[(i, j)] = f64::from(u8::from(i == j)) - bulk.spring[i] * bulk.pz[(i, j)];
                }
            }
        }
        for (j, members) in sites.members.iter().enumerate() {
            let (pr, _, _) = self.project(j, &f);
            match pr.state {
                FrictionState::Stick => stick += 1,
                FrictionState::Slip => slip += 1,
                FrictionState::Separated => {}
            }
            for &i in members {
                let fe = self.body.active_node(i).frame;
                g[i] = f.t[i] - (fe[0] * pr.traction[0] + fe[1] * pr.traction[1]);
            }
            let Some(jac) = jac.as_deref_mut() else {
                continue;
            };
            let mut jp = pr.d_trial;
            if pr.state == FrictionState::Slip {
                let delta = SLIP_JACOBIAN_BLEND;
                for c in 0..2 {
                    for d in 0..2 {
                        jp[c][d] = (1.0 - delta) * jp[c][d] + if c == d { delta } else { 0.0 };
                    }
                }
            }
            let (inverse, r) = self.friction.site_data(j);
            let first = members[0];
            for &i in members {
                let fe = self.body.active_node(i).frame;
                for (ff, &k) in members.iter().enumerate() {
                    let fk = self.body.active_node(k).frame;
                    let (mut mt, mut su) = (0.0, 0.0);
                    for c in 0..2 {
                        for d in 0..2 {
                            mt += fe[c] * jp[c][d] * inverse[ff][d];
                            su += fe[c] * jp[c][d] * fk[d];
                        }
                    }
                    // - mt (e_k - c_k PZ_k) + r su PZ_k
                    jac[(i, k)] -= mt;
                    let coefficient = mt * bulk.spring[k] + r * su;
                    if coefficient != 0.0 {
                        for col in 0..m {
                            jac[(i, col)] += coefficient * bulk.pz[(k, col)];
                        }
                    }
                }
                let dp = fe[0] * pr.d_pressure[0] + fe[1] * pr.d_pressure[1];
                if dp != 0.0 {
                    for col in 0..m {
                        jac[(i, col)] -= dp * bulk.nz[(first, col)];
                    }
                }
            }
        }
        (stick, slip)
    }

    /// The rigid amplitude `a` that balances the loads against friction along the rigid
    /// sliding mode at `s` (its part `s_p` off the mode kept), `None` without a rigid mode or
    /// without a root.
    ///
    /// # Math
    /// With `s = s_p + a z`, the tractions `t` and stresses `sigma` do not depend on `a`
    /// (`(I - C P Z) z = 0`, `N Z z = 0`); only the slip does, `u_j(a) = u_j(0) + a F_j x_r`.
    /// The component of `G` along the left null vector `y` of `I - C P Z` is the balance of
    /// the loads against friction along the mode,
    /// ```text
    /// phi(a) = y . G(s_p + a z) = sum_i y_i (t_i - f_i . P_C(sigma)(tau - r u(a)))
    /// ```
    /// a scalar function that changes only while a site's trial `tau - r u(a)` is inside its
    /// friction set (in 2-D `phi` is piecewise linear, constant where every site slides).
    /// Its root puts at least one site (the neutral point) on the stick branch: the
    /// generalised Jacobian there has stiffness along `z`, where on the slip branch at every
    /// site it has only the blend `delta`. Bracketed by doubling steps from the current
    /// amplitude (the first the amplitude change that reverses the nearest site's trial,
    /// `min_j |tau_j - r u_j| / (r |F_j x_r|)`, over 16), then the Illinois false position.
    /// Each evaluation costs `O(m)` (no matrix product).
    fn balanced_amplitude(&self, s: &[f64]) -> Option<f64> {
        let solver = self.solver;
        let (y, xr) = (&solver.rigid_balance, &solver.rigid_shift);
        if y.is_empty() {
            return None;
        }
        let m = s.len();
        let (a0, _) = solver.split_rigid(s);
        let mut f = self.fields(s);
        let base: Vec<f64> = (0..m).map(|i| f.x[i] - a0 * xr[i]).collect();
        let sites = self.body.sites();
        let mut h = f64::INFINITY;
        for j in 0..sites.members.len() {
            let (_, tau, u) = self.project(j, &f);
            let (_, r) = self.friction.site_data(j);
            let du = self.body.site_frame_slip(j, 1.0, |k| xr[k]);
            let rate = r * du[0].hypot(du[1]);
            if rate > 0.0 {
                h = h.min((tau[0] - r * u[0]).hypot(tau[1] - r * u[1]) / rate);
            }
        }
        h /= 16.0;
        if !(h.is_finite() && h > 0.0) {
            return None;
        }
        let h0 = h;
        let mut phi = |a: f64| -> f64 {
            for i in 0..m {
                f.x[i] = base[i] + a * xr[i];
            }
            let mut sum = 0.0;
            for (j, members) in sites.members.iter().enumerate() {
                let (pr, _, _) = self.project(j, &f);
                for &i in members {
                    let fe = self.body.active_node(i).frame;
                    sum += y[i] * (f.t[i] - (fe[0] * pr.traction[0] + fe[1] * pr.traction[1]));
                }
            }
            sum
        };
        let f0 = phi(a0);
        if f0 == 0.0 {
            return Some(a0);
        }
        if !f0.is_finite() {
            return None;
        }
        // bracket [lo, hi]: phi(lo) on f0's side, phi(hi) across zero
        let (mut lo, mut flo) = (a0, f0);
        let mut bracket = None;
        'search: for _ in 0..BALANCE_DOUBLINGS {
            for a in [a0 + h, a0 - h] {
                let fa = phi(a);
                if !fa.is_finite() {
                    return None;
                }
                if fa.signum() != f0.signum() {
                    bracket = Some((a, fa));
                    break 'search;
                }
            }
            h *= 2.0;
        }
        let (hi, fhi) = bracket?;
        // the last point on f0's side towards `hi` (phi is monotone along the mode)
        let inner = hi - (hi - a0) / 2.0;
        if (hi - a0).abs() > h0 {
            let fi = phi(inner);
            if fi.is_finite() && fi.signum() == f0.signum() {
                (lo, flo) = (inner, fi);
            }
        }
        Some(illinois(phi, (lo, flo), (hi, fhi), h0))
    }

    /// Moves `s` along the rigid mode to the balanced amplitude
    /// ([`ExactFace::balanced_amplitude`], `s_p` kept) when no site of `s` is on the stick
    /// branch of the projection; true when it moved.
    ///
    /// # Math
    /// At the regularised start every site is on the slip branch (also the neutral one,
    /// whose regularised slip `u` is small but `r u` is not), so `J z = delta (..)`: the
    /// Newton step's rigid component is of order `(y . G) / delta` and the full step slides
    /// the body (the line search then backtracked it to `alpha = 2^-9` on the paper's
    /// circle). At the balanced amplitude the neutral site sticks, `J` is regular along `z`
    /// and the Newton steps from there are full (2 steps instead of 3 on the default scene).
    fn balance_unstuck(&mut self, s: &mut [f64]) -> bool {
        if self.solver.rigid_mode.is_empty() {
            return false;
        }
        let mut g = std::mem::take(&mut self.g);
        let (stick, _) = self.eval(s, &mut g, None);
        self.g = g;
        if stick > 0 {
            return false;
        }
        let Some(a) = self.balanced_amplitude(s) else {
            return false;
        };
        let (_, sp) = self.solver.split_rigid(s);
        set_rigid(s, &sp, &self.solver.rigid_mode, a);
        true
    }

    /// Keeps `s` and its `(stick, slip)` counts as the last evaluation.
    fn remember(&mut self, s: &[f64], counts: (usize, usize)) {
        self.last.0.clear();
        self.last.0.extend_from_slice(s);
        self.last.1 = counts;
    }

    /// The rounding-error bound of evaluating `G(s)` (max over the entries):
    /// `u (|s_p| + c X + |t| + |f| (|tau| + r |f| X))` with `X = |x0| + sum_j |PZ_ij s_p,j|`.
    fn roundoff_floor(&self, s: &[f64]) -> f64 {
        let f = self.fields(s);
        let (x_abs, s_abs) = self.rounding_scales(s);
        let sites = self.body.sites();
        let mut floor = 0.0f64;
        for (j, members) in sites.members.iter().enumerate() {
            let (_, tau, _) = self.project(j, &f);
            let (_, r) = self.friction.site_data(j);
            for &i in members {
                let fe = self.body.active_node(i).frame;
                let fnorm = fe[0].hypot(fe[1]);
                let c = self.solver.bulk.spring[i];
                let value = s_abs[i]
                    + c * x_abs[i]
                    + f.t[i].abs()
                    + fnorm * (tau[0].hypot(tau[1]) + r * fnorm * x_abs[i]);
                floor = floor.max(f64::EPSILON * value);
            }
        }
        floor
    }
}

impl<D: ContactOperator, L: FrictionLaw<f64>> NewtonSystem for ExactFace<'_, '_, '_, D, L> {
    type Error = ContactError;

    fn residual(&mut self, s: &[f64], g: &mut [f64]) -> Result<(), ContactError> {
        let counts = self.eval(s, g, None);
        self.remember(s, counts);
        Ok(())
    }

    fn direction(
        &mut self,
        at: &NewtonIterate<'_>,
        ds: &mut [f64],
    ) -> Result<NewtonDirection, ContactError> {
        let mut g = std::mem::take(&mut self.g);
        let mut jac = std::mem::replace(&mut self.jac, Mat::<f64>::zeros(0, 0));
        let counts = self.eval(at.u, &mut g, Some(&mut jac));
        self.remember(at.u, counts);
        let m = ds.len();
        let rhs = Mat::<f64>::from_fn(m, 1, |i, _| -g[i]);
        let step = jac.partial_piv_lu().solve(&rhs);
        self.g = g;
        self.jac = jac;
        if (0..m).any(|i| !step[(i, 0)].is_finite()) {
            return Err(ContactError::NotConverged {
                iterations: at.iteration,
                residual: at.norm / self.scale,
                load_factor: 1.0,
            });
        }
        for (i, d) in ds.iter_mut().enumerate() {
            *d = step[(i, 0)];
        }
        Ok(NewtonDirection {
            max_step: 1.0,
            ..NewtonDirection::default()
        })
    }

    fn accepted(&mut self, at: &NewtonIterate<'_>) -> Result<Flow, ContactError> {
        if at.iteration == self.max_iterations {
            return Ok(Flow::Continue);
        }
        let (stick, slip) = if self.last.0 == at.u {
            self.last.1
        } else {
            let mut g = std::mem::take(&mut self.g);
            let counts = self.eval(at.u, &mut g, None);
            self.g = g;
            counts
        };
        if report_face_iterate(self.observer, at, self.scale, stick, slip) {
            return Ok(Flow::Interrupt);
        }
        if !at.norm.is_finite() {
            return Err(ContactError::NotConverged {
                iterations: at.iteration,
                residual: f64::INFINITY,
                load_factor: 1.0,
            });
        }
        Ok(Flow::Continue)
    }
}
