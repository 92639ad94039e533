//! The error estimate of a quantity from its values along a refinement ladder (the accuracy
//! targets of [`crate::problem::AccuracyTarget`]): Richardson extrapolation with the observed
//! rate where the sequence is in its asymptotic range, the plain last change where it is not,
//! and on a ladder graded toward the stick/slip transitions the ladder's rate where a
//! quantity's own rate is faster than the ladder allows; at the stop of that ladder, the
//! difference from a twin solve of the same order on a mesh refined toward the contact face.
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
//! quantities along the hp ladder at the step `tol = 1e-3` chooses, 0.57x ... 5.0x against one
//! of the two finest solves at least (docs/verification.md, "The contact tolerance table").
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
//! # The ladder's rate (the transition-graded ladder)
//! On the transition-graded ladder (`Problem::transition_step`: order `p = 2 + k` on one mesh
//! with an element line at each stick/slip transition the step before located) every
//! quantity's error has a part set by the transitions. The kink of the friction traction at
//! `|u| = eps` lies a distance `delta_{k-1}` (the location error of step `k - 1`) from the
//! element line meant for it; the element holding it converges only algebraically, and the
//! whole solution, the displacements and the stresses at the probes too, carries an error of
//! the order of that misfit. The quantities set by the transitions (the slip measure and the
//! stick-zone ends: [`Behaviour::Transition`]) measure the misfit itself, which falls at the
//! rate `rho` of the location (`0.46 ... 0.52` per order on the default scene). The rest of
//! the error (the smooth field; the end corners, with `p + 3` layers) falls exponentially in
//! `p`, faster (Schwab, *p- and hp-FEM*, section 4.4). So every quantity's error is
//! `A rho^k + B s^k` with `|s| < rho`, and its asymptotic rate is `rho`: on the default scene
//! the last changes (`p = 9` to `10`) of max `|v2|` and of probes 1 and 2 are `0.47 ... 0.50`
//! times the ones before, like the slip measure's `0.52`. The ladder's rate is
//! ```text
//! rho = max |r_k|   over the Transition quantities with a rate                 (ladder_rate)
//! ```
//! their *last* rates: the one before may still carry the relocation from the first pass
//! (`stick_from`: `-0.05, 0.63, 0.48` at steps 2, 3, 4 on the default scene).
//!
//! A quantity whose rate `r` (the one the Richardson rule would use) agrees with `rho` within
//! [`CONSISTENT`] (`|r| >= rho / CONSISTENT`, as two rates of one sequence must agree; a
//! slower rate is a quantity not yet asymptotic, which its own rate covers) keeps rule
//! `richardson`. A faster rate contradicts the ladder: the part falling at `rho` cannot have
//! fallen so fast, so step `k` landed near the limit by a cancellation between the parts, and
//! the changes cannot say how much of the error is left. Two readings span it:
//! ```text
//! lower:  c_k rho / (1 - rho),          c_k = max(|d_k|, R_MIN |d_{k-1}|)
//!         the fall was real, the error falls at rho from step k on
//! upper:  rho |d_{k-1}| rho / (1 - rho)
//!         the fall was a landing, the part at rho goes on from d_{k-1}
//! ```
//! They differ by the factor `rho / max(|r|, R_MIN) > CONSISTENT`. With the error anywhere
//! between them, the estimate off by the least factor in the worst case is their geometric
//! mean, off by at most `w = sqrt(rho / max(|r|, R_MIN)) <= sqrt(64 rho)` (5.5 at
//! `rho = 0.47`):
//! ```text
//! e_k = SAFETY sqrt(c_k rho |d_{k-1}|) rho / (1 - rho)                      (rule `ladder-rate`)
//! ```
//! (`rho / (1 - rho)`: the monotone reading, larger than the alternating `rho / (1 + rho)`),
//! within `SAFETY / w ... SAFETY w` of an error between the readings (`0.36 ... 11` at worst
//! for `rho = 0.47`). An error outside them (a quantity that stagnates, or lands closer than
//! the lower reading) is outside this bracket, as it is outside any rule's on the changes.
//! On the default scene at `tol = 1e-5` (step 6, `p = 8`) the true errors of max `|v2|`,
//! max `|v3|` and the probes (`1.9e-8 ... 6.9e-7`) all lie between the two readings and the
//! estimates are 2.2x ... 5.9x them, where `richardson` with the `R_MIN` cap gave
//! 0.008x ... 0.26x; at step 2 the stick ends, whose first change is the relocation from the
//! first pass (rates `-0.05`, `0.06` after it), get 3.3x and 5.2x where `richardson` gave
//! 0.08x and 0.17x (docs/verification.md, "The transition-graded ladder"). A plain floor
//! `|r| >= rho` would also overrule rates within the band: probe 0 at step 2 (rate `0.19`,
//! `rho = 0.41`) from 2.1x its true error to 6.4x and above `1e-3`, moving that tolerance's
//! stop a step later for nothing. A ladder without Transition quantities (the hp ladder, the
//! threshold's) has no `rho` and keeps the rules above.
//!
//! # The twin at the stop
//! A quantity that lands near its limit at step `k` (its error `e_k` far below the change
//! `d_k`, which is about `e_{k-1}`) shows it only in the next change `d_{k+1}`: no rule on
//! `d_1 ... d_k` can tell it from a quantity still `|d_k|` off. On the transition-graded
//! ladder of the default scene four smooth quantities land at step 2 (`p = 4`, the stop of
//! `tol = 1e-3`): max `|v2|`, max `|v3|` and probes 1 and 2 are `2.7e-6, 1.3e-7, 7.4e-6,
//! 6.1e-6` from their limits after changes of `3.9e-4 ... 6.2e-4`, and the rules above
//! overestimate them 51x ... 6301x. A second solve at the stop with an error of its own sees
//! it: the *twin* (`Problem::transition_twin`), the stop's problem (its order, cells, corner
//! layers and transition grading) with 3 rows of ratio `0.3` toward the contact face, which
//! refine the stop's mesh where its error lives (the band of the `0.03`-long stick zone, rows
//! `0.125` high on `24 x 8` cells; the corner cells, shrunk to squares of side `H 0.3^3` with
//! their corner layers inside). With `e = Q_k - Q` and `e' = Q'_k - Q` the errors of the step
//! and of its twin,
//! ```text
//! |Q_k - Q'_k| = |e - e'|,        e_k = SAFETY |Q_k - Q'_k|                 (rule `twin`)
//! |e'| <= q |e|, q < 1:   2 (1 - q) |e| <= e_k <= 2 (1 + q) |e|    within 0.5x-10x for q <= 3/4
//! |e'| =  Q |e|, Q > 1:   2 (Q - 1) |e| <= e_k <= 2 (Q + 1) |e|    within 0.5x-10x for Q <= 4
//! ```
//! so the estimate is the error of the less accurate of the two: of the step where the twin
//! is closer to the limit (a landing of the twin alone is then harmless: `q ~ 0`), and an
//! overestimate by the twin's error where the step alone landed (bounded by `|e'|`, not by
//! the change `|d_k|`). It fails low only where the two share their error (`q` near 1, the same
//! sign): an error the rows do not touch, where the step and its twin land together. Measured
//! on the default scene at the twins of steps 2 ... 7 (`p = 4 ... 9`; docs/verification.md,
//! "The transition-graded ladder"): `|q| <= 0.57` for every quantity but max `|v3|` at step 2
//! (`Q = 3.7`: the step landed, the twin did not; the estimate is 5.5x) and at step 5
//! (`q = 0.93` at `|e| = 2.4e-9`, the reference's own level), and probe 0 at step 3
//! (`q = 1.08`: both land; the estimate is 0.15x; not a stop). At the stops of `tol = 1e-3,
//! 1e-4, 1e-5` (steps 2, 4, 6) the estimates are 0.85x ... 5.5x the true errors.
//!
//! The twin's estimate replaces the ladder's rather than joining it: their smaller would
//! inherit the low failures of both (the ladder's where a quantity stagnates, the twin's where
//! the two land together), their larger the ladder's landings, which are what the twin is for.
//! The ladder's rules still choose the stop (no twin before it); the refinement stops where the
//! twin's estimates meet the tolerance too, and climbs on where they do not
//! (`Problem::refine_along_twinned`). Its cost is one solve with 1.8x the stop's unknowns.
//!
//! # Limits
//! The estimate is of the error of `Q_k` against the ladder's limit from the changes alone: a
//! quantity that stagnates for several steps (its changes small while its error is not: a
//! stick zone not yet resolved) is underestimated by any such rule; docs/verification.md
//! records where that happens on the default scene (the slip measure at `tol = 1e-2` on the hp
//! ladder). A quantity that lands near its limit by accident is overestimated by any such
//! rule: at step 2 of the transition-graded ladder max `|v3|` is `1.3e-7` from its limit after
//! a change of `3.8e-4`, and nothing before step 3 shows it; the twin at the stop does (above).

/// The safety factor of the Richardson estimate (see the module docs).
pub const SAFETY: f64 = 2.0;

/// The largest ratio between two observed rates counted as agreeing: the last two rates of a
/// sequence (its asymptotic range), or a quantity's rate and the ladder's ([`ladder_rate`]).
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
    /// stick-zone ends) on a ladder that does not follow the transitions: the last change.
    Located,
    /// A quantity set by a stick/slip transition on a ladder graded toward the transitions
    /// (the slip measure and the stick-zone ends of the transition-graded ladder): it
    /// converges at a rate like [`Behaviour::Smooth`], and its last rate sets the ladder's
    /// ([`ladder_rate`]).
    Transition,
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
    /// `SAFETY sqrt(max(|d_k|, R_MIN |d_{k-1}|) rho |d_{k-1}|) rho / (1 - rho)`: a quantity
    /// whose rate is faster than the ladder's `rho` allows ([`ladder_rate`]).
    LadderRate,
    /// `SAFETY |Q_k - Q'_k|`: the difference from the stop's twin, the same order on a mesh
    /// refined toward the contact face ([`twin`]).
    Twin,
}

/// The estimate of the error of the last value of a sequence.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SequenceEstimate {
    /// The estimated error `e_k` (absolute, non-negative).
    pub error: f64,
    /// The rule that made it.
    pub rule: Rule,
    /// The rate `r` the rule used: the observed one (`richardson`), the ladder's `rho`
    /// (`ladder-rate`); `None` for the last change.
    pub rate: Option<f64>,
}

/// What the last changes of a sequence show, before any ladder-wide rate.
enum Observed {
    /// No estimate (fewer than two values, a non-finite change).
    Nothing,
    /// No rate can be read: the last change `|d_k|` is the estimate.
    LastChange(f64),
    /// A rate: the last two changes `d_k`, `d_{k-1}`, the last rate `r_k` and the rate the
    /// Richardson rule uses (the slower of two agreeing, else `r_k`).
    Rates {
        last: f64,
        before: f64,
        last_rate: f64,
        rate: f64,
    },
}

/// The changes and rates of `values` (see the module docs), `behaviour` deciding whether a
/// rate is read at all.
fn observe(values: &[f64], behaviour: Behaviour) -> Observed {
    let n = values.len();
    if n < 2 {
        return Observed::Nothing;
    }
    let d = |j: usize| values[j] - values[j - 1];
    let last = d(n - 1);
    if !last.is_finite() {
        return Observed::Nothing;
    }
    if behaviour == Behaviour::Located || n < 3 || last.abs() <= NOISE * values[n - 1].abs() {
        return Observed::LastChange(last.abs());
    }
    let before = d(n - 2);
    let r1 = last / before;
    if before == 0.0 || r1.abs() >= 1.0 {
        return Observed::LastChange(last.abs());
    }
    let mut rate = r1;
    if n >= 4 {
        let r0 = before / d(n - 3);
        let agree = r0 * r1 > 0.0
            && r0.abs() < 1.0
            && r0.abs().max(r1.abs()) <= CONSISTENT * r0.abs().min(r1.abs());
        if agree && r0.abs() > r1.abs() {
            rate = r0;
        }
    }
    Observed::Rates {
        last,
        before,
        last_rate: r1,
        rate,
    }
}

/// The ladder's rate `rho` from the sequences of its [`Behaviour::Transition`] quantities
/// (each coarsest first): the slowest of their last observed rates, `max |r_k|`, over those
/// that have one (see the module docs, "The ladder's rate"). `None` when none has a rate
/// (before step 2, or every change grew or is at the solvers' tolerances).
pub fn ladder_rate<'a>(sequences: impl IntoIterator<Item = &'a [f64]>) -> Option<f64> {
    sequences
        .into_iter()
        .filter_map(|values| match observe(values, Behaviour::Transition) {
            Observed::Rates { last_rate, .. } => Some(last_rate.abs()),
            _ => None,
        })
        .reduce(f64::max)
}

/// The estimate of the error of `value` (a quantity of the stop) from its value `twin` on the
/// stop's twin (the same order on a mesh refined where the stop's error lives; see the module
/// docs, "The twin at the stop"): `SAFETY |value - twin|`, rule [`Rule::Twin`]. `None` for a
/// non-finite difference.
pub fn twin(value: f64, twin: f64) -> Option<SequenceEstimate> {
    let difference = (value - twin).abs();
    difference.is_finite().then_some(SequenceEstimate {
        error: SAFETY * difference,
        rule: Rule::Twin,
        rate: None,
    })
}

/// The estimate of the error of the last of `values` (a quantity along the ladder, coarsest
/// first; see the module docs) on a ladder without a ladder-wide rate: [`estimate_on`] with
/// `None`. `None` with fewer than two values or a non-finite change.
pub fn estimate(values: &[f64], behaviour: Behaviour) -> Option<SequenceEstimate> {
    estimate_on(values, behaviour, None)
}

/// The estimate of the error of the last of `values` on a ladder whose rate is `ladder`
/// ([`ladder_rate`]; `None` on a ladder without one): rule `richardson` with the observed rate
/// where it agrees with `ladder` (or there is none), rule `ladder-rate` where it is faster than
/// `ladder / CONSISTENT`, rule `last-change` where no rate can be read (see the module docs).
/// `None` with fewer than two values or a non-finite change.
pub fn estimate_on(
    values: &[f64],
    behaviour: Behaviour,
    ladder: Option<f64>,
) -> Option<SequenceEstimate> {
    let (last, before, rate) = match observe(values, behaviour) {
        Observed::Nothing => return None,
        Observed::LastChange(change) => {
            return Some(SequenceEstimate {
                error: change,
                rule: Rule::LastChange,
                rate: None,
            });
        }
        Observed::Rates {
            last, before, rate, ..
        } => (last, before, rate),
    };
    // the change of the lower reading: a change of zero does not give a zero estimate
    let change = last.abs().max(R_MIN * before.abs());
    if let Some(rho) = ladder.filter(|rho| rate.abs() < rho / CONSISTENT) {
        let upper = rho * before.abs();
        return Some(SequenceEstimate {
            error: SAFETY * (change * upper).sqrt() * rho / (1.0 - rho),
            rule: Rule::LadderRate,
            rate: Some(rho),
        });
    }
    let r = rate.signum() * rate.abs().max(R_MIN);
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

    #[test]
    fn the_ladder_rate_is_the_slowest_last_rate_of_the_sequences_that_have_one() {
        let slow = geometric(0.1, 0.5, 5); // last rate 0.5
        let fast = geometric(0.1, -0.3, 5); // last rate -0.3: modulus 0.3
        let short = [1.0, 2.0]; // one change: no rate
        let growing = [0.0, 0.1, 0.3]; // rate 2: no rate
        let rho = ladder_rate([&fast[..], &slow[..], &short[..], &growing[..]]).unwrap();
        assert!((rho - 0.5).abs() < 1e-12, "{rho}");
        // the last rate, not the slower of two agreeing: changes 1, 0.6, 0.3 (rates 0.6, 0.5)
        let q = [0.0, 1.0, 1.6, 1.9];
        assert!((ladder_rate([&q[..]]).unwrap() - 0.5).abs() < 1e-12);
        assert_eq!(ladder_rate([&short[..], &growing[..]]), None);
        assert_eq!(ladder_rate(std::iter::empty::<&[f64]>()), None);
    }

    #[test]
    fn a_rate_within_the_ladders_band_keeps_richardson_and_no_ladder_changes_nothing() {
        for r in [0.5, 0.2, -0.3, 0.9] {
            let q = geometric(0.1, r, 6);
            // rho = 0.5: rates down to 0.5 / CONSISTENT agree with it
            let e = estimate_on(&q, Behaviour::Smooth, Some(0.5)).unwrap();
            assert_eq!(Some(e), estimate(&q, Behaviour::Smooth), "{r}");
            assert_eq!(e.rule, Rule::Richardson);
        }
        // without a ladder rate: the old rules, R_MIN cap included
        let q = geometric(0.1, 0.01, 6);
        let e = estimate_on(&q, Behaviour::Transition, None).unwrap();
        assert_eq!((e.rule, e.rate), (Rule::Richardson, Some(R_MIN)));
        // a located quantity keeps its last change whatever the ladder
        let q = geometric(0.1, 0.01, 6);
        let e = estimate_on(&q, Behaviour::Located, Some(0.5)).unwrap();
        assert_eq!(e.rule, Rule::LastChange);
    }

    #[test]
    fn the_twin_estimate_is_twice_the_difference_and_brackets_a_closer_twin() {
        // the step 1e-6 off; twins 0.7e-6 and -0.7e-6 off (q = 0.7 on either side): 0.6x, 3.4x
        for (twin_error, ratio) in [(0.7e-6, 0.6), (-0.7e-6, 3.4)] {
            let e = twin(1.0 + 1e-6, 1.0 + twin_error).unwrap();
            assert_eq!((e.rule, e.rate), (Rule::Twin, None));
            assert!((e.error / 1e-6 - ratio).abs() < 1e-9, "{}", e.error);
        }
        // a twin 4x as far: 2 (4 + 1) = 10x at most, the less accurate one's error
        let e = twin(1.0 + 1e-6, 1.0 - 4e-6).unwrap();
        assert!((e.error / 1e-6 - 10.0).abs() < 1e-9);
        assert_eq!(twin(1.0, f64::NAN), None);
    }

    /// `Q_j = 2^-j` with a fast part on step 3 alone that all but cancels the change of step 4
    /// (the landing: `d_4 = -1e-3` after `d_3 = -0.1865`), the error of `Q_4` still `2^-4`.
    #[test]
    fn a_rate_faster_than_the_ladder_allows_takes_the_geometric_mean_of_the_two_readings() {
        let mut q = geometric(1.0, 0.5, 5);
        q[3] -= 0.0615;
        let truth = q[4];
        let before = q[3] - q[2]; // -0.1865
        let rho = 0.5;
        let e = estimate_on(&q, Behaviour::Smooth, Some(rho)).unwrap();
        assert_eq!((e.rule, e.rate), (Rule::LadderRate, Some(rho)));
        let lower = R_MIN * before.abs() * rho / (1.0 - rho);
        let upper = rho * before.abs() * rho / (1.0 - rho);
        assert!(lower < truth && truth < upper, "{lower} {truth} {upper}");
        assert!((e.error - SAFETY * (lower * upper).sqrt()).abs() < 1e-15);
        // within SAFETY / sqrt(rho / R_MIN) ... SAFETY sqrt(rho / R_MIN) of any error between
        // the readings: here 0.53x, where Richardson with the R_MIN cap gives 0.0015x
        let worst = (rho / R_MIN).sqrt();
        let ratio = e.error / truth;
        assert!(
            ratio >= SAFETY / worst && ratio <= SAFETY * worst,
            "{ratio}"
        );
        assert!((0.5..=10.0).contains(&ratio), "{ratio}");
        let plain = estimate(&q, Behaviour::Smooth).unwrap();
        assert!(plain.error / truth < 0.01, "{}", plain.error / truth);
    }
}
