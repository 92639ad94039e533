//! The rigid sliding mode in the condensed unknowns: `s = s_p + a z`, and the friction
//! balance along it that fixes the amplitude `a` at every Newton iterate.

use capstan_friction::FrictionLaw;

use super::BoundarySolver;
use super::newton::SLIP_STEP_GROWTH;
use crate::contact::operator::ContactOperator;

/// False-position iterations of [`BoundarySolver::rebalance`].
pub(super) const REBALANCE_ITERATIONS: usize = 100;

/// The Illinois false position on a bracket `[lo, hi]` of a scalar `phi` (`phi(lo)` and
/// `phi(hi)` of opposite signs, given as `flo`, `fhi`):
/// ```text
/// a = (lo phi(hi) - hi phi(lo)) / (phi(hi) - phi(lo)),
/// ```
/// the end on `phi(a)`'s side replaced by `a`; when the same end is kept twice in a row, the
/// other end's value is halved (Illinois), which keeps the convergence superlinear where plain
/// false position would stall at one end. Stops at `phi(a) = 0` or a bracket shorter than
/// `1e-15 max(|a|, scale)` and returns `a`; after [`REBALANCE_ITERATIONS`] the end with the
/// smaller `|phi|`.
pub(super) fn illinois(
    mut phi: impl FnMut(f64) -> f64,
    (mut lo, mut flo): (f64, f64),
    (mut hi, mut fhi): (f64, f64),
    scale: f64,
) -> f64 {
    let mut side = 0i8;
    for _ in 0..REBALANCE_ITERATIONS {
        let a = (lo * fhi - hi * flo) / (fhi - flo);
        let fa = phi(a);
        if fa == 0.0 || (hi - lo).abs() <= 1e-15 * a.abs().max(scale) {
            return a;
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
    if flo.abs() <= fhi.abs() { lo } else { hi }
}

/// `s = s_p + a z`.
pub(super) fn set_rigid(s: &mut [f64], sp: &[f64], z: &[f64], a: f64) {
    for ((s, p), z) in s.iter_mut().zip(sp).zip(z) {
        *s = p + a * z;
    }
}

impl<D: ContactOperator, L: FrictionLaw<f64>> BoundarySolver<'_, D, L> {
    /// Splits `s = s_p + a z` along the rigid mode `z` (`a = 0`, `s_p = s` without one).
    pub(super) fn split_rigid(&self, s: &[f64]) -> (f64, Vec<f64>) {
        let z = &self.rigid_mode;
        if z.is_empty() {
            return (0.0, s.to_vec());
        }
        let a: f64 = z.iter().zip(s).map(|(z, s)| z * s).sum();
        (a, s.iter().zip(z).map(|(s, z)| s - a * z).collect())
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
    pub(super) fn rebalance(&self, beta: f64, x0: &[f64], n0: &[f64], s: &mut [f64]) {
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
        let sites = self.model.sites();
        let phi = |a: f64| -> f64 {
            sites
                .members
                .iter()
                .enumerate()
                .map(|(j, members)| {
                    let slip = self.model.site_slip(j, beta, |k| xb[k] + a * xr[k]);
                    let t = self.model.site_traction_at_slip(j, slip, sig[members[0]]);
                    members
                        .iter()
                        .enumerate()
                        .map(|(e, &i)| y[i] * (lin[i] - t.covariant[e]))
                        .sum::<f64>()
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
        let a = illinois(phi, (lo, flo), (hi, fhi), per_a.recip() * eps);
        set_rigid(s, &sp, z, a);
    }
}
