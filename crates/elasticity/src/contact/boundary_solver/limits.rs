//! Limiting equilibrium: the rigid sliding mode of the frictionless condensed operator and
//! the tension ratios at which the whole contact slides.

use capstan_friction::FrictionLaw;
use faer::Mat;
use faer::linalg::solvers::Solve;

use super::condensation::frictionless_operator;
use super::{BoundarySolver, SlidingMode};
use crate::contact::error::ContactError;
use crate::contact::loads::EndLoads;
use crate::contact::model::slide_along;
use crate::contact::operator::ContactOperator;

/// Relative singular value below which the frictionless bulk counts as having a sliding mode.
pub(super) const SLIDING_MODE_THRESHOLD: f64 = 1e-8;

/// Largest share of `sum_k w_k |t_k|` that the full-slip friction may carry *along* the slip
/// (contact in tension under a pressure-proportional law) for its ratio to count as a limit.
/// The corner nodes next to the loaded ends carry a resolution artefact of this kind
/// (measured: below `1e-3` of the total on 125 x 21 to 500 x 81 of the default circle).
pub(super) const WRONG_WAY_SHARE_LIMIT: f64 = 1e-2;

/// Largest wrong-way share (as [`WRONG_WAY_SHARE_LIMIT`]) of a 3-D full slip whose balance
/// still counts as a run-off ratio: below one half the friction resists the sliding as a
/// whole. (Measured: 0.322 on the default cone, `6 x 40 x 5`, where the solutions run off
/// at the balance 1.9363.)
pub(super) const RUNAWAY_WRONG_WAY_SHARE: f64 = 0.5;

/// Newton iterations of the full-slip limit (one suffices for laws affine in `sigma_n`).
pub(super) const FULL_SLIP_ITERATIONS: usize = 50;

/// Relative size of the load term of the frictionless balance along a rigid mode below which
/// the loads do not drive the mode (see [`BoundarySolver::mode_is_driven`]).
pub(super) const UNDRIVEN_MODE: f64 = 1e-8;

impl<D: ContactOperator, L: FrictionLaw<f64>> BoundarySolver<'_, D, L> {
    /// The frictionless condensed operator `I - C P Z`: if it is singular (relative singular
    /// value below [`SLIDING_MODE_THRESHOLD`]), the rigid sliding mode and its limits at
    /// `tau0 = 1`.
    pub(super) fn sliding_mode(&mut self) -> Result<Option<SlidingMode>, ContactError> {
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
        self.rigid_shift = (0..m)
            .map(|i| {
                (0..m)
                    .map(|j| self.bulk.pz[(i, j)] * self.rigid_mode[j])
                    .sum()
            })
            .collect();
        // The singular vector's sign is arbitrary: orient the mode so that the contact slides
        // toward +x2 (the tau_max end) along it, so that `direction = 1` of `limits_at` is the
        // upper limit and an unbounded way is +inf there, -inf the other way. (Found on a 3-D
        // Q1 body, 17 x 65 x 17, where the SVD returned the mode sliding toward -x2 and the
        // unbounded lower limit was reported as +inf: the range [3.51, inf] refused the
        // default ratio 2 as "no static equilibrium".)
        let toward_x2: f64 = (0..self.model.sites().members.len())
            .map(|j| self.model.site_frame_slip(j, 1.0, |k| self.rigid_shift[k])[1])
            .sum();
        if toward_x2 < 0.0 {
            self.rigid_mode.iter_mut().for_each(|z| *z = -*z);
            self.rigid_shift.iter_mut().for_each(|z| *z = -*z);
        }
        // the balance oriented with y . z > 0, so that y . G increases with the rigid amplitude
        // (friction resists the sliding)
        let u = svd.U();
        let y_dot_z: f64 = (0..m).map(|k| u[(k, m - 1)] * self.rigid_mode[k]).sum();
        let orient = if y_dot_z < 0.0 { -1.0 } else { 1.0 };
        self.rigid_balance = (0..m).map(|k| orient * u[(k, m - 1)]).collect();
        self.homogeneous = self.law_is_homogeneous();
        let limits = self.limits_at(1.0, relative);
        if self.model.sites().members.iter().any(|m| m.len() == 2) {
            // A 3-D body: the full slip is not along the rigid mode (the mode's slip crosses
            // the loads' direction), so the amplitude is left to Newton, not split off and
            // rebalanced by the scalar friction balance along the mode (measured: a belt on
            // a cone converges at ratio 3 only without the split).
            self.rigid_mode.clear();
            self.rigid_shift.clear();
            self.rigid_balance.clear();
        }
        limits.map(Some)
    }

    /// [`ContactError::NoEquilibrium`] with the run-off range when `loads` lie past a 3-D body's
    /// run-off ratios ([`SlidingMode::runaway_ratios`], relative tolerance `1e-9`), `None`
    /// otherwise (inside, no such ratios, or `tau0 <= 0`). Called once plain Newton has failed:
    /// the load continuation from `tau_max = tau0` would have to cross the run-off.
    ///
    /// # Errors
    /// The full-slip Newton iteration of [`BoundarySolver::sliding_at`].
    pub(super) fn past_runaway(
        &self,
        loads: EndLoads,
    ) -> Result<Option<ContactError>, ContactError> {
        if loads.tau0 <= 0.0 {
            return Ok(None);
        }
        let Some([lower, upper]) = self.sliding_at(loads.tau0)?.and_then(|m| m.runaway_ratios)
        else {
            return Ok(None);
        };
        let ratio = loads.tension_ratio();
        let tol = 1e-9 * ratio.abs().max(1.0);
        Ok(
            (ratio > upper + tol || ratio < lower - tol).then_some(ContactError::NoEquilibrium {
                ratio,
                lower,
                upper,
            }),
        )
    }

    /// Whether the law's saturated traction is homogeneous of degree 1 in the normal stress
    /// (`t(2 sigma) = 2 t(sigma)`, `t(0) = 0`: Coulomb-type laws). Then the limiting ratios do
    /// not depend on `tau0`; otherwise (Tresca, power laws) they are recomputed per `tau0`.
    pub(super) fn law_is_homogeneous(&self) -> bool {
        let u = 1e6 * self.model.slip_threshold();
        let t = |sigma: f64| {
            self.model
                .site_traction_at_slip(0, [0.0, u], sigma)
                .traction[1]
        };
        let (t0, t1, t2) = (t(0.0), t(-1.0), t(-2.0));
        (t2 - 2.0 * t1).abs() <= 1e-12 * t2.abs() && t0.abs() <= 1e-14 * t1.abs().max(1e-300)
    }

    /// Whether the end loads drive the rigid mode at all: the frictionless balance along it,
    /// `y . C x0(tau)` with `x0 = tau0 x_a + tau_max x_b`, changes with the loads by more than
    /// [`UNDRIVEN_MODE`] of its terms. A mode the loads do not drive (the `x1` translation of
    /// a prism body of finite width under `x2` end loads) has no limiting ratio: friction
    /// holds every ratio along it.
    pub(super) fn mode_is_driven(&self) -> bool {
        let y = &self.rigid_balance;
        let [(xa, _), (xb, _)] = &self.bulk.base;
        [xa, xb].iter().any(|x| {
            let (mut sum, mut size) = (0.0f64, 0.0f64);
            for ((yi, ci), xi) in y.iter().zip(&self.bulk.spring).zip(x.iter()) {
                sum += yi * ci * xi;
                size += (yi * ci * xi).abs();
            }
            size > 0.0 && sum.abs() > UNDRIVEN_MODE * size
        })
    }

    /// The physical slip of site `j` at full slip in `direction`, of size `size`: along the
    /// rigid mode's slip at the site, `direction size F x_r / |F x_r|`, at every site (one
    /// entry or two), so that the whole contact slides one way. The sign of the singular
    /// vector `x_r` is arbitrary; `direction = -1, 1` covers both ways. (Issue 19: a site of
    /// one entry `v^2` used to slide `[0, direction size]` whatever the sign of `x_r`, so on a
    /// 3-D body with plane-strain sides the side-face sites slid against the interior ones
    /// whenever the SVD returned `x_r` with negative slip.) A site the mode does not move
    /// (`F x_r = 0`) slides along `x2`.
    fn full_slip(&self, j: usize, direction: f64, size: f64) -> [f64; 2] {
        let w = self.model.site_frame_slip(j, 1.0, |k| self.rigid_shift[k]);
        slide_along(w, direction, size)
    }

    /// The limiting ratios `tau_max / tau0` of rigid sliding for the given `tau0`, and on a
    /// 3-D body the run-off ratios ([`SlidingMode::runaway_ratios`]).
    pub(super) fn limits_at(&self, tau0: f64, relative: f64) -> Result<SlidingMode, ContactError> {
        let mut ratios = [f64::NEG_INFINITY, f64::INFINITY];
        let mut runaway = ratios;
        let mut any_runaway = false;
        if self.mode_is_driven() {
            for ((r, run), direction) in ratios.iter_mut().zip(&mut runaway).zip([-1.0, 1.0]) {
                let limit = self.full_slip_limit(direction, tau0)?;
                *r = limit.bound;
                *run = limit.runaway.unwrap_or(limit.bound);
                any_runaway |= limit.runaway.is_some();
            }
        }
        Ok(SlidingMode {
            relative_singular_value: relative,
            lower_ratio: ratios[0].min(ratios[1]),
            upper_ratio: ratios[0].max(ratios[1]),
            tau0,
            runaway_ratios: any_runaway
                .then(|| [runaway[0].min(runaway[1]), runaway[0].max(runaway[1])]),
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
    ///
    /// On a 3-D body, a balance `r` refused by the wrong-way share only is kept as
    /// [`FullSlipLimit::runaway`] when the friction as a whole resists the sliding (the
    /// wrong-way share below one half).
    pub(super) fn full_slip_limit(
        &self,
        direction: f64,
        tau0: f64,
    ) -> Result<FullSlipLimit, ContactError> {
        let m = self.bulk.pz.nrows();
        let u = 1e6 * self.model.slip_threshold();
        let z = &self.rigid_mode;
        let [(xa, na), (xb, nb)] = &self.bulk.base;
        let sites = self.model.sites();
        let slips: Vec<[f64; 2]> = (0..sites.members.len())
            .map(|j| self.full_slip(j, direction, u))
            .collect();
        let mut s = vec![0.0; m];
        let mut r = 1.0;
        let mut g = vec![0.0; m + 1];
        let mut t = vec![0.0; m];
        let mut dn = vec![0.0; m];
        let mut along = vec![false; m];
        let mut x = vec![0.0; m];
        let mut sig = vec![0.0; m];
        let mut jac = Mat::<f64>::zeros(m + 1, m + 1);
        let mut residual = f64::INFINITY;
        for it in 0..=FULL_SLIP_ITERATIONS {
            let mut size = 0.0f64;
            for i in 0..m {
                x[i] = tau0 * (xa[i] + r * xb[i]);
                sig[i] = tau0 * (na[i] + r * nb[i]);
                for (j, sj) in s.iter().enumerate() {
                    x[i] += self.bulk.pz[(i, j)] * sj;
                    sig[i] += self.bulk.nz[(i, j)] * sj;
                }
            }
            for (j, members) in sites.members.iter().enumerate() {
                let st = self
                    .model
                    .site_traction_at_slip(j, slips[j], sig[members[0]]);
                // friction pushing along the slip (contact in tension)
                let pushes = st.traction[0] * slips[j][0] + st.traction[1] * slips[j][1] > 0.0;
                for (e, &i) in members.iter().enumerate() {
                    t[i] = st.covariant[e];
                    dn[i] = st.d_normal_stress[e];
                    along[i] = pushes;
                    g[i] = s[i] - t[i] - self.bulk.spring[i] * x[i];
                    size = size.max(s[i].abs() + t[i].abs() + (self.bulk.spring[i] * x[i]).abs());
                }
            }
            g[m] = z.iter().zip(&s).map(|(a, b)| a * b).sum();
            residual = g[..m].iter().fold(0.0f64, |a, x| a.max(x.abs())) / size.max(1e-300);
            if it > 0 && residual <= 1e-11 {
                let bound = self.bound_or_unbounded(direction, r, &t, &along);
                let solid = sites.members.iter().any(|m| m.len() == 2);
                let runaway = (solid && bound.is_infinite() && r.is_finite() && r > 0.0)
                    .then(|| self.wrong_way_share(&t, &along))
                    .filter(|share| *share < RUNAWAY_WRONG_WAY_SHARE)
                    .map(|_| r);
                return Ok(FullSlipLimit { bound, runaway });
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
    /// sliding in `direction` (wrong-way share, the entries whose site's friction pushes
    /// `along` the slip, at most [`WRONG_WAY_SHARE_LIMIT`]), else `direction * inf`.
    pub(super) fn bound_or_unbounded(
        &self,
        direction: f64,
        r: f64,
        t: &[f64],
        along: &[bool],
    ) -> f64 {
        // no friction at all (mu = 0, share 0): the frictionless balance itself is the limit
        let resists = self.wrong_way_share(t, along) <= WRONG_WAY_SHARE_LIMIT;
        if r.is_finite() && r > 0.0 && resists {
            r
        } else {
            direction * f64::INFINITY
        }
    }

    /// The share of `sum_k w_k |t_k|` carried by the entries whose site's friction pushes
    /// `along` the slip (`0` without friction).
    fn wrong_way_share(&self, t: &[f64], along: &[bool]) -> f64 {
        let (mut wrong, mut total) = (0.0, 0.0);
        for (k, (tk, pushes)) in t.iter().zip(along).enumerate() {
            let w = self.model.active_node(k).traction_weight * tk.abs();
            total += w;
            if *pushes {
                wrong += w;
            }
        }
        if total > 0.0 { wrong / total } else { 0.0 }
    }
}

/// The full-slip balance of one direction: the bound it puts on the loads (`direction * inf`
/// if none) and, on a 3-D body, the run-off ratio ([`SlidingMode::runaway_ratios`]).
#[derive(Debug, Clone, Copy)]
pub(super) struct FullSlipLimit {
    /// The limiting ratio, or `direction * inf`.
    pub bound: f64,
    /// The balance `r` where `bound` is infinite by the wrong-way share only (3-D).
    pub runaway: Option<f64>,
}
