//! Damped Newton on the condensed contact equations `G(s) = 0`.

use capstan_friction::FrictionLaw;
use capstan_solvers::{
    Flow, NewtonDirection, NewtonFailure, NewtonIterate, NewtonSystem, Observer, Progress,
    SolveStage, newton_drive,
};
use faer::Mat;
use faer::linalg::solvers::Solve;

use super::{BoundarySolver, ContactSettings, Converged, Failure};
use crate::contact::loads::EndLoads;
use crate::contact::operator::ContactOperator;

/// A residual within this factor of the rounding floor of its evaluation counts as converged.
pub(super) const ROUNDOFF_FACTOR: f64 = 100.0;

/// The largest relative residual the rounding floor may excuse (see [`ROUNDOFF_FACTOR`]).
pub(super) const MAX_ROUNDOFF_RESIDUAL: f64 = 1e-6;

/// Growth of the slip scale allowed per Newton step (see [`BoundarySolver::slip_step_cap`]).
pub(super) const SLIP_STEP_GROWTH: f64 = 10.0;

/// Stiffness along the rigid mode added to the Newton matrix, relative to the spring (see
/// [`BoundarySolver::eval`]).
pub(super) const RIGID_TETHER: f64 = 1e-8;

impl<D: ContactOperator, L: FrictionLaw<f64>> BoundarySolver<'_, D, L> {
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
    pub(super) fn eval(
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
        // beta d t_i / d x_partner(i) on sites with two entries (a 3-D body)
        let mut cross = vec![0.0; m];
        let (pzs, nzs) = self.condensed_products(&sp);
        let x: Vec<f64> = (0..m)
            .map(|i| {
                let shift = self.rigid_shift.get(i).map_or(0.0, |r| a * r);
                x0[i] + pzs[i] + shift
            })
            .collect();
        let sites = self.model.sites();
        for (j, members) in sites.members.iter().enumerate() {
            let sig = n0[members[0]] + nzs[members[0]];
            // slip homotopy: the law sees beta u (for regularised Coulomb: eps / beta)
            let slip = self.model.site_slip(j, beta, |k| x[k]);
            let st = self.model.site_traction_at_slip(j, slip, sig);
            for (e, &i) in members.iter().enumerate() {
                g[i] = sp[i] - self.bulk.spring[i] * (x0[i] + pzs[i]) - st.covariant[e];
                friction[i] = beta * st.d_tangential[e][e];
                dx[i] = friction[i] + self.bulk.spring[i];
                dn[i] = st.d_normal_stress[e];
                if members.len() == 2 {
                    cross[i] = beta * st.d_tangential[e][1 - e];
                }
            }
        }
        if let Some(jac) = jac {
            for j in 0..m {
                for i in 0..m {
                    jac[(i, j)] = f64::from(u8::from(i == j))
                        - dx[i] * self.bulk.pz[(i, j)]
                        - dn[i] * self.bulk.nz[(i, j)];
                }
            }
            for (i, &(site, e)) in sites.of_active.iter().enumerate() {
                if sites.members[site].len() == 2 {
                    let p = sites.members[site][1 - e];
                    for j in 0..m {
                        jac[(i, j)] -= cross[i] * self.bulk.pz[(p, j)];
                    }
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
                        let (site, e) = sites.of_active[i];
                        let partner = if sites.members[site].len() == 2 {
                            cross[i] * self.rigid_shift[sites.members[site][1 - e]]
                        } else {
                            0.0
                        };
                        jz0[i]
                            + (friction[i] + RIGID_TETHER * self.bulk.spring[i])
                                * self.rigid_shift[i]
                            + partner
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

    /// The rounding-error bound of evaluating `G(s)` in floating point (max over the nodes):
    /// ```text
    /// floor_i = u (|s_p,i| + |t_2,i| + |c_i xb_i| + c_i X_i + |dt_2/dx_i| (X_i + |a x_r,i|) + |dt_2/dsigma_i| S_i)
    /// xb = x0 + P Z s_p,   X_i = |x0_i| + sum_j |PZ_ij s_p,j|,   S_i = |n0_i| + sum_j |NZ_ij s_p,j|
    /// ```
    /// (`u` the machine epsilon, `s = s_p + a z` as in [`BoundarySolver::eval`]): the sums carry a
    /// relative error `u`, amplified by the spring and by the law's stiffness `mu sigma_n / eps`
    /// in the stick zone. No Newton step can reduce the residual below it.
    pub(super) fn roundoff_floor(&self, beta: f64, x0: &[f64], n0: &[f64], s: &[f64]) -> f64 {
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

    /// The largest step fraction `alpha <= 1` whose change of the physical slip stays within
    /// [`SLIP_STEP_GROWTH`] times the current slip scale:
    /// ```text
    /// alpha max_k |beta sqrt(g22_k) (P Z ds)_k| <= SLIP_STEP_GROWTH max(eps, max_k |beta sqrt(g22_k) x_k|)
    /// ```
    /// (`eps` the law's slip threshold). The regularised law changes over a slip of `eps`, so a
    /// Newton step far beyond the current slip scale is an extrapolation; along a rigid
    /// sliding mode held only by friction, it sends the body sliding away, where the saturated
    /// friction leaves a smaller but spurious residual.
    pub(super) fn slip_step_cap(&self, beta: f64, x0: &[f64], s: &[f64], ds: &Mat<f64>) -> f64 {
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

    /// [`BoundarySolver::newton_with`] with the solver's settings.
    pub(super) fn newton(
        &self,
        beta: f64,
        loads: EndLoads,
        s: &mut [f64],
        observer: &mut dyn Observer<f64>,
    ) -> Result<Converged, Failure> {
        self.newton_with(&self.settings, beta, loads, s, observer)
    }

    /// Damped Newton on `G(s) = 0` from `s` ([`capstan_solvers::newton_drive`]: max-norm
    /// residual, Armijo on `|G|_2^2` from the slip-capped step [`BoundarySolver::slip_step_cap`],
    /// every trial rebalanced along the rigid mode). Converged when
    /// `max |G| <= tolerance * scale`, or, once no step decreases `|G|` (or the iterations run
    /// out), when `max |G|` is within [`ROUNDOFF_FACTOR`] of the rounding floor of its own
    /// evaluation ([`BoundarySolver::roundoff_floor`]). Every iterate is reported to
    /// `observer` ([`SolveStage::CondensedNewton`]: the relative residual `max |G| / scale`,
    /// the step length and the stick/slip counts the law sees), which may stop the iteration.
    pub(super) fn newton_with(
        &self,
        settings: &ContactSettings,
        beta: f64,
        loads: EndLoads,
        s: &mut [f64],
        observer: &mut dyn Observer<f64>,
    ) -> Result<Converged, Failure> {
        let (x0, n0) = self.loaded_base(loads);
        let m = s.len();
        let gmax = (0..m)
            .map(|k| self.model.active_node(k).sqrt_g22)
            .fold(0.0f64, f64::max);
        let scale = (loads.magnitude() * gmax).max(f64::MIN_POSITIVE);
        let tol = settings.tolerance * scale;
        // the rounding floor may excuse a residual up to 1e-6 relative, never more (a state
        // drifting along a sliding mode has a huge floor and is no solution)
        let accept_floor =
            |floor: f64| (ROUNDOFF_FACTOR * floor).min(MAX_ROUNDOFF_RESIDUAL * scale);
        self.rebalance(beta, &x0, &n0, s);
        let policy = settings.face_policy(tol);
        let mut system = CondensedSystem {
            solver: self,
            beta,
            x0: &x0,
            n0: &n0,
            scale,
            max_iterations: settings.max_iterations,
            jac: Mat::<f64>::zeros(m, m),
            g: vec![0.0; m],
            observer,
        };
        match newton_drive(&mut system, s, &policy) {
            Ok(done) => Ok((done.iterations, done.residuals[done.iterations] / scale)),
            Err(NewtonFailure::Problem(failure)) => Err(failure),
            Err(NewtonFailure::Interrupted { iteration }) => Err(Failure::Interrupted(iteration)),
            // no descent left: accept if the residual is at its rounding floor
            Err(NewtonFailure::LineSearch {
                iterations: it,
                residual: r,
                ..
            }) => {
                if r <= accept_floor(self.roundoff_floor(beta, &x0, &n0, s)) {
                    Ok((it, r / scale))
                } else {
                    Err(Failure::NotConverged(it + 1, r / scale))
                }
            }
            Err(NewtonFailure::NotConverged {
                iterations: it,
                residual: r,
            }) => {
                if r <= tol.max(accept_floor(self.roundoff_floor(beta, &x0, &n0, s))) {
                    Ok((it, r / scale))
                } else {
                    Err(Failure::NotConverged(it, r / scale))
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
            ) => Err(Failure::NotConverged(it, r / scale)),
            Err(NewtonFailure::NonFinite { iteration, .. }) => {
                Err(Failure::NotConverged(iteration, f64::INFINITY))
            }
        }
    }

    /// `(stick, slip)`: contact sites whose slip as the law sees it, `|beta F x|`, is below
    /// the law's slip threshold, and the others (`x = x0 + P Z s_p + a x_r`).
    fn active_counts(&self, beta: f64, x0: &[f64], s: &[f64]) -> (usize, usize) {
        let (a, sp) = self.split_rigid(s);
        let (pzs, _) = self.condensed_products(&sp);
        let eps = self.model.slip_threshold();
        let x = |i: usize| x0[i] + pzs[i] + self.rigid_shift.get(i).map_or(0.0, |r| a * r);
        let sites = self.model.site_count();
        let stick = (0..sites)
            .filter(|&j| {
                let u = self.model.site_slip(j, beta, x);
                (u[0] * u[0] + u[1] * u[1]).sqrt() < eps
            })
            .count();
        (stick, sites - stick)
    }

    /// `(x0, n0)` for the loads (plus the fixed loads, if any).
    pub(super) fn loaded_base(&self, loads: EndLoads) -> (Vec<f64>, Vec<f64>) {
        let [(xa, na), (xb, nb)] = &self.bulk.base;
        let mut x: Vec<f64> = xa
            .iter()
            .zip(xb)
            .map(|(a, b)| loads.tau0 * a + loads.tau_max * b)
            .collect();
        let mut s: Vec<f64> = na
            .iter()
            .zip(nb)
            .map(|(a, b)| loads.tau0 * a + loads.tau_max * b)
            .collect();
        if let Some(((xf, nf), _)) = &self.bulk.fixed {
            x.iter_mut().zip(xf).for_each(|(x, f)| *x += f);
            s.iter_mut().zip(nf).for_each(|(s, f)| *s += f);
        }
        (x, s)
    }

    /// `(P Z s, N Z s)`: the tangential displacements and normal stresses that the condensed
    /// unknowns `s` add at the contact nodes (two dense matrix-vector products).
    pub(super) fn condensed_products(&self, s: &[f64]) -> (faer::Col<f64>, faer::Col<f64>) {
        let s = faer::ColRef::from_slice(s);
        (
            self.bulk.pz.as_ref().as_ref() * s,
            self.bulk.nz.as_ref().as_ref() * s,
        )
    }
}

/// [`BoundarySolver::newton_with`]'s problem for the driver: `G(s)` at one slip homotopy
/// parameter and load, the dense Newton step by LU, the trials rebalanced along the rigid mode.
struct CondensedSystem<'s, 'b, 'o, D, L: FrictionLaw<f64>> {
    solver: &'s BoundarySolver<'b, D, L>,
    beta: f64,
    x0: &'s [f64],
    n0: &'s [f64],
    /// `max |G|` is reported relative to it.
    scale: f64,
    /// The iteration cap (its iterate is not reported).
    max_iterations: usize,
    jac: Mat<f64>,
    g: Vec<f64>,
    observer: &'o mut dyn Observer<f64>,
}

impl<D: ContactOperator, L: FrictionLaw<f64>> NewtonSystem for CondensedSystem<'_, '_, '_, D, L> {
    type Error = Failure;

    fn residual(&mut self, s: &[f64], g: &mut [f64]) -> Result<(), Failure> {
        self.solver.eval(self.beta, self.x0, self.n0, s, g, None);
        Ok(())
    }

    fn direction(
        &mut self,
        at: &NewtonIterate<'_>,
        ds: &mut [f64],
    ) -> Result<NewtonDirection, Failure> {
        let (solver, beta) = (self.solver, self.beta);
        solver.eval(
            beta,
            self.x0,
            self.n0,
            at.u,
            &mut self.g,
            Some(&mut self.jac),
        );
        let m = ds.len();
        let rhs = Mat::<f64>::from_fn(m, 1, |i, _| -self.g[i]);
        let step = self.jac.partial_piv_lu().solve(&rhs);
        if (0..m).any(|i| !step[(i, 0)].is_finite()) {
            return Err(Failure::NotConverged(at.iteration, at.norm / self.scale));
        }
        for (i, d) in ds.iter_mut().enumerate() {
            *d = step[(i, 0)];
        }
        Ok(NewtonDirection {
            max_step: solver.slip_step_cap(beta, self.x0, at.u, &step),
            ..NewtonDirection::default()
        })
    }

    fn project(&mut self, trial: &mut [f64]) {
        self.solver.rebalance(self.beta, self.x0, self.n0, trial);
    }

    fn accepted(&mut self, at: &NewtonIterate<'_>) -> Result<Flow, Failure> {
        if at.iteration == self.max_iterations {
            return Ok(Flow::Continue);
        }
        let (stick, slip) = self.solver.active_counts(self.beta, self.x0, at.u);
        if report_face_iterate(self.observer, at, self.scale, stick, slip) {
            return Ok(Flow::Interrupt);
        }
        if !at.norm.is_finite() {
            return Err(Failure::NotConverged(at.iteration, f64::INFINITY));
        }
        Ok(Flow::Continue)
    }
}

/// Reports an accepted iterate of a condensed face Newton (the regularised step and the
/// semismooth exact-friction step) to `observer`: stage `CondensedNewton`, the residual norm
/// relative to `scale`, the step length and the stick/slip counts. True when the observer
/// asks to stop.
pub(super) fn report_face_iterate(
    observer: &mut dyn Observer<f64>,
    at: &NewtonIterate<'_>,
    scale: f64,
    stick: usize,
    slip: usize,
) -> bool {
    observer.iteration(
        &Progress::new(
            SolveStage::CondensedNewton,
            at.iteration,
            at.norm / scale,
            at.step,
        )
        .with_active(stick, slip),
    );
    observer.interrupted()
}
