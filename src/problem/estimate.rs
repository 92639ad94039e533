//! The error estimate of a quantity from its values along a refinement ladder (the accuracy
//! targets of [`crate::problem::AccuracyTarget`]): Richardson extrapolation with the observed
//! rate where the sequence is in its asymptotic range, the plain last change where it is not.
//!
//! A leaf module: it knows sequences of numbers, nothing of problems or solvers.
//!
//! # Math
//! The values `Q_0, ..., Q_k` of a quantity on the ladder's steps, their changes
//! `d_j = Q_j - Q_{j-1}` and observed rates `r_j = d_j / d_{j-1}`. In the asymptotic range the
//! error falls geometrically, `Q_j = Q + C r^j` (`0 < |r| < 1`; `r < 0`: the values alternate
//! about the limit), so `d_j = C r^(j-1) (r - 1)`, `r_j = r` and the error of `Q_k` is
//! ```text
//! Q_k - Q = d_k r / (1 - r),        |E_k| = |d_k| |r| / |1 - r|
//! ```
//! (Richardson extrapolation with the observed rate). The estimate of a quantity that
//! converges at a rate ([`Behaviour::Smooth`]) at step `k >= 2` with a falling change
//! (`|r_k| < 1`) is
//! ```text
//! e_k = SAFETY max(|d_k|, R_MIN |d_{k-1}|) |r| / |1 - r|              (rule `richardson`)
//! ```
//! with the rate `r`:
//! - the slower (larger `|r_j|`) of the last two rates `r_{k-1}`, `r_k` when they agree (the
//!   same sign, both `|r_j| < 1`, within a factor [`CONSISTENT`]): the asymptotic range;
//! - else the last rate `r_k` alone (at step 2, which has one rate, and after a feature is
//!   resolved between two steps: a change that falls 65x in one step on the default scene);
//! - and never faster than [`R_MIN`] `= 2^-6` in modulus: halving the elements of the order-6
//!   mesh (the ladder's `h` steps) lowers the error of a stress by `2^-p = 1/64` in the
//!   asymptotic range, the fastest contraction the ladder makes; a faster observed fall is
//!   taken as a landing near the limit by accident (the `max` with `R_MIN |d_{k-1}|` keeps a
//!   change of zero from giving a zero estimate).
//!
//! [`SAFETY`] `= 2` covers a next rate up to twice as slow as the one used (the estimate is
//! then still at least the error) and keeps the estimate at most `2 * CONSISTENT = 6` times
//! the error when the next rate is as fast as the faster observed one. On the default scene's
//! threshold ladder (rates 0.12, 0.20, 0.21) it is 1.1x ... 1.7x the error; on its contact
//! quantities at the step `tol = 1e-3` chooses, 0.57x ... 5.0x against one of the two finest
//! solves at least (docs/verification.md, "The contact tolerance table").
//!
//! The estimate is the last change `e_k = |d_k|` (rule `last-change`) where no rate can be
//! read:
//! - at step 1 (one change);
//! - where the change grew (`|r_k| >= 1`: not converging on these steps) or the change before
//!   was zero;
//! - where the change is at the level of the solvers' tolerances (`|d_k| <= NOISE |Q_k|`,
//!   [`NOISE`] `= 1e-8`: the contact Newton stops at `1e-10` relative residual), so its rate is
//!   noise;
//! - for a quantity *located between nodes* ([`Behaviour::Located`]: the slip measure and the
//!   stick-zone ends, whose transitions the locator places inside an element): it converges
//!   with a grid-dependent jitter on top of its trend (on the default scene the slip measure
//!   moves by `1.6e-5` of the face between the 673- and 1345-node steps and by as much between
//!   meshes of 112 and 120 elements), so a rate read from its changes is the jitter's, not the
//!   error's. The last change is the size of that jitter.
//!
//! The estimate is of the error of `Q_k` against the ladder's limit from the changes alone: a
//! quantity that stagnates for several steps (its changes small while its error is not: a
//! stick zone not yet resolved) is underestimated by any such rule; docs/verification.md
//! records where that happens on the default scene (the slip measure at `tol = 1e-2`).

/// The safety factor of the Richardson estimate (see the module docs).
pub const SAFETY: f64 = 2.0;

/// The largest ratio between the last two observed rates of a sequence counted as asymptotic.
pub const CONSISTENT: f64 = 3.0;

/// The fastest contraction per step the estimate believes: `2^-6`, a stress under one halving
/// of the order-6 mesh (see the module docs).
pub const R_MIN: f64 = 1.0 / 64.0;

/// Changes at most this times the value are at the solvers' tolerances: no rate is read.
pub const NOISE: f64 = 1e-8;

/// How a quantity converges along a ladder, for its estimate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Behaviour {
    /// A functional of the solution that converges at a rate (a threshold, a displacement or a
    /// stress at a point): Richardson with the observed rate.
    Smooth,
    /// A quantity set by a stick/slip transition located between nodes (slip measure,
    /// stick-zone ends): the last change.
    Located,
}

/// Which rule made an estimate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Rule {
    /// `SAFETY max(|d_k|, R_MIN |d_{k-1}|) |r| / |1 - r|` with the observed rate `r`.
    Richardson,
    /// `|d_k|`: one change, a growing change, a change at the solvers' tolerances, or a
    /// located quantity.
    LastChange,
}

/// The estimate of the error of the last value of a sequence.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SequenceEstimate {
    /// The estimated error `e_k` (absolute, non-negative).
    pub error: f64,
    /// The rule that made it.
    pub rule: Rule,
    /// The observed rate `r` the Richardson rule used (`None` for the last change).
    pub rate: Option<f64>,
}

/// The estimate of the error of the last of `values` (a quantity along the ladder, coarsest
/// first; see the module docs). `None` with fewer than two values or a non-finite change.
pub fn estimate(values: &[f64], behaviour: Behaviour) -> Option<SequenceEstimate> {
    let n = values.len();
    if n < 2 {
        return None;
    }
    let d = |j: usize| values[j] - values[j - 1];
    let last = d(n - 1);
    if !last.is_finite() {
        return None;
    }
    let plain = SequenceEstimate {
        error: last.abs(),
        rule: Rule::LastChange,
        rate: None,
    };
    if behaviour == Behaviour::Located || n < 3 || last.abs() <= NOISE * values[n - 1].abs() {
        return Some(plain);
    }
    let before = d(n - 2);
    let r1 = last / before;
    if before == 0.0 || r1.abs() >= 1.0 {
        return Some(plain);
    }
    let mut r = r1;
    if n >= 4 {
        let r0 = before / d(n - 3);
        let agree = r0 * r1 > 0.0
            && r0.abs() < 1.0
            && r0.abs().max(r1.abs()) <= CONSISTENT * r0.abs().min(r1.abs());
        if agree && r0.abs() > r1.abs() {
            r = r0;
        }
    }
    let r = r.signum() * r.abs().max(R_MIN);
    let change = last.abs().max(R_MIN * before.abs());
    Some(SequenceEstimate {
        error: SAFETY * change * r.abs() / (1.0 - r).abs(),
        rule: Rule::Richardson,
        rate: Some(r),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `Q_j = c r^j`, `j = 0 .. n` (limit 0, no cancellation against an offset).
    fn geometric(c: f64, r: f64, n: usize) -> Vec<f64> {
        (0..n).map(|j| c * r.powi(j as i32)).collect()
    }

    #[test]
    fn richardson_on_a_geometric_sequence_is_the_safety_factor_times_the_error() {
        for r in [0.5, 0.2, 1.0 / 64.0, -1.0 / 3.0, -0.8, 0.9] {
            let q = geometric(0.1, r, 6);
            let e = estimate(&q, Behaviour::Smooth).unwrap();
            let truth = q[5].abs();
            assert_eq!(e.rule, Rule::Richardson, "{r}");
            assert!(
                (e.error / truth - SAFETY).abs() < 1e-9,
                "{r}: {}",
                e.error / truth
            );
            assert!((e.rate.unwrap() - r).abs() < 1e-12);
            // step 2: the one rate there is, exact on a geometric sequence
            let e = estimate(&q[..3], Behaviour::Smooth).unwrap();
            assert!((e.error / q[2].abs() - SAFETY).abs() < 1e-9, "{r}");
        }
    }

    #[test]
    fn the_slower_of_two_agreeing_rates_and_the_last_of_two_disagreeing() {
        // changes 1, 0.5, 0.125: rates 0.5 then 0.25 agree (2x): the slower, 0.5
        let q = [0.0, 1.0, 1.5, 1.625];
        let e = estimate(&q, Behaviour::Smooth).unwrap();
        assert_eq!(e.rate, Some(0.5));
        assert!((e.error - SAFETY * 0.125).abs() < 1e-12);
        // rates 0.5 then 0.1 (5x): the last, 0.1
        let q = [0.0, 1.0, 1.5, 1.55];
        let e = estimate(&q, Behaviour::Smooth).unwrap();
        assert!((e.rate.unwrap() - 0.1).abs() < 1e-12);
        assert!((e.error - SAFETY * 0.05 * 0.1 / 0.9).abs() < 1e-12);
        // a fall faster than R_MIN is taken as R_MIN: 1e-6 after 1 is not a 1e-6 rate
        let q = [0.0, 1.0, 1.0 + 1e-6];
        let e = estimate(&q, Behaviour::Smooth).unwrap();
        assert_eq!(e.rate, Some(R_MIN));
        let expected = SAFETY * R_MIN * R_MIN / (1.0 - R_MIN);
        assert!((e.error - expected).abs() < 1e-15, "{}", e.error);
    }

    #[test]
    fn one_change_a_growing_change_noise_and_located_quantities_take_the_last_change() {
        assert_eq!(estimate(&[1.0], Behaviour::Smooth), None);
        let e = estimate(&[1.0, 1.5], Behaviour::Smooth).unwrap();
        assert_eq!((e.error, e.rule), (0.5, Rule::LastChange));
        // a change that grew: not converging on these steps
        let e = estimate(&[0.0, 0.1, 0.3], Behaviour::Smooth).unwrap();
        assert_eq!(e.rule, Rule::LastChange);
        assert!((e.error - 0.2).abs() < 1e-15);
        let e = estimate(&[0.0, 0.1, -0.1], Behaviour::Smooth).unwrap();
        assert_eq!(e.rule, Rule::LastChange);
        // a change at the solvers' tolerances
        let e = estimate(&[1.0, 1.0 + 1e-6, 1.0 + 1e-6 + 1e-9], Behaviour::Smooth).unwrap();
        assert_eq!(e.rule, Rule::LastChange);
        // located: the last change even on a geometric sequence
        let q = geometric(0.1, 0.5, 6);
        let e = estimate(&q, Behaviour::Located).unwrap();
        assert_eq!(e.rule, Rule::LastChange);
        assert!((e.error - (q[5] - q[4]).abs()).abs() < 1e-15);
        assert_eq!(estimate(&[1.0, f64::NAN], Behaviour::Smooth), None);
    }
}
