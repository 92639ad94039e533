//! The tension ratio at which the whole contact slides (Slip = 1), by bracketing and bisection.

use capstan_friction::FrictionLaw;

use crate::contact::boundary_solver::{BoundarySolver, SlidingMode};
use crate::contact::error::ContactError;
use crate::contact::loads::EndLoads;
use crate::contact::operator::ContactOperator;
use crate::contact::solution::ContactSolution;

/// Settings of [`threshold_ratio`].
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ThresholdSettings {
    /// Stop when the bracket is shorter than `tolerance * upper`.
    pub tolerance: f64,
    /// Give up bracketing past this ratio.
    pub max_ratio: f64,
    /// Bracket from the sliding mode's limiting ratio `L` when the body has one: probe
    /// `L (1 + d)` (no equilibrium) and `L (1 + d) (1 - tolerance)` (`d = min(1e-6,
    /// tolerance / 4)`) first, so that two solves end the search when the whole contact slides
    /// only at the limit (the circle: stick nodes persist up to `L`); the bisection from `1`
    /// runs only if the lower probe fully slips or fails. Default `false` (the bisection from
    /// `1`, whose midpoints the default reports keep).
    pub bracket_at_limit: bool,
}

impl Default for ThresholdSettings {
    fn default() -> Self {
        Self {
            tolerance: 1e-6,
            max_ratio: 1e4,
            bracket_at_limit: false,
        }
    }
}

/// The result of a threshold search.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ThresholdResult {
    /// The threshold ratio `tau_max / tau0` (upper end of the final bracket).
    pub ratio: f64,
    /// Largest ratio found with a stick node (Slip < 1).
    pub below: f64,
    /// Smallest ratio found fully slipping or without equilibrium.
    pub above: f64,
    /// Slip at `below`.
    pub slip_fraction_below: f64,
    /// Whether `above` had no static solution (rather than a fully slipping one).
    pub above_is_no_equilibrium: bool,
    /// Contact solves done.
    pub solves: usize,
    /// The limiting ratio from the sliding mode's solvability condition, when the bulk has one
    /// (on a 3-D body whose bound is unbounded, the run-off ratio
    /// [`SlidingMode::runaway_ratios`]: no equilibrium past it along the load path).
    pub limiting_ratio: Option<f64>,
    /// When the threshold is a fold of the equilibrium path (a 3-D body under unilateral
    /// contact: [`crate::contact::FullSystemSolver::run_off`]): the fold ratio `r*`, the
    /// largest ratio the path reached, in `[below, above]`; `None` otherwise.
    pub fold: Option<f64>,
}

/// The solve at `tau_max / tau0 = ratio` (`tau0 = 1`, from `warm` if given) when it lies below
/// the threshold of whole sliding; `None` at or above it: a fully slipping solution
/// ([`ContactSolution::fully_slipping`]), no static solution, or a solve that fails to converge
/// within `1e-3` (relative) below the sliding mode's limiting ratio, where the full-slip
/// solution is singular.
///
/// # Errors
/// Any other failure of the solve.
pub fn solve_below_threshold<D: ContactOperator, L: FrictionLaw<f64>>(
    solver: &BoundarySolver<'_, D, L>,
    ratio: f64,
    warm: Option<&[f64]>,
) -> Result<Option<ContactSolution>, ContactError> {
    match solver.solve_from(EndLoads::ratio(ratio), warm) {
        Ok(sol) if sol.fully_slipping() => Ok(None),
        Ok(sol) => Ok(Some(sol)),
        Err(ContactError::NoEquilibrium { .. }) => Ok(None),
        Err(ContactError::NotConverged { .. })
            if solver
                .sliding()
                .and_then(|m| limiting_upper_ratio(&m))
                .is_some_and(|upper| ratio >= upper * (1.0 - 1e-3)) =>
        {
            Ok(None)
        }
        Err(e) => Err(e),
    }
}

/// The sliding mode's finite upper limit: the bound `upper_ratio`, else on a 3-D body the
/// run-off ratio ([`SlidingMode::runaway_ratios`]).
fn limiting_upper_ratio(mode: &SlidingMode) -> Option<f64> {
    Some(mode.upper_ratio)
        .filter(|r| r.is_finite())
        .or_else(|| mode.runaway_ratios.map(|[_, upper]| upper))
        .filter(|r| r.is_finite())
}

/// Finds the smallest `tau_max / tau0 >= 1` (with `tau0 = 1`) at which every contact node slides
/// in the positive direction
/// ([`ContactSolution::fully_slipping`](crate::contact::ContactSolution::fully_slipping)), or
/// beyond which no static solution exists.
///
/// # Errors
/// [`ContactError::NotConverged`] if a solve fails for another reason or no bracket is found
/// below `settings.max_ratio`.
///
/// # Math
/// Bisection on `r = tau_max / tau0` keeping `[lo, hi]` with a stick node at `lo` and whole
/// sliding (or no static solution) at `hi`, until `hi - lo <= tolerance * hi`. With a rigid
/// sliding mode (the circle) no static solution exists past its limiting ratio `L`
/// ([`BoundarySolver::sliding`]), so `hi` starts at `L (1 + d)`; with
/// `settings.bracket_at_limit` the first probe below is `L (1 + d) (1 - 0.99 tolerance)`, and
/// when it keeps a stick node the bracket is done after 3 solves (`r = 1`, above, below)
/// instead of the `log2(L / tolerance)` of the bisection from `1`.
pub fn threshold_ratio<D: ContactOperator, L: FrictionLaw<f64>>(
    solver: &BoundarySolver<'_, D, L>,
    settings: ThresholdSettings,
) -> Result<ThresholdResult, ContactError> {
    let mut solves = 0;
    // Ok(Some(slip)) below threshold, Ok(None) at/above, with the warm start updated.
    let mut warm: Option<Vec<f64>> = None;
    let mut probe =
        |ratio: f64, warm: &mut Option<Vec<f64>>| -> Result<Option<(f64, bool)>, ContactError> {
            solves += 1;
            Ok(
                solve_below_threshold(solver, ratio, warm.as_deref())?.map(|sol| {
                    let slip = sol.slip_fraction;
                    *warm = Some(sol.unknowns);
                    (slip, false)
                }),
            )
        };
    let limiting_ratio = solver.sliding().and_then(|m| limiting_upper_ratio(&m));
    let mut lo = 1.0;
    let mut slip_lo = match probe(lo, &mut warm)? {
        Some((s, _)) => s,
        None => {
            return Ok(ThresholdResult {
                ratio: 1.0,
                below: 1.0,
                above: 1.0,
                slip_fraction_below: 1.0,
                above_is_no_equilibrium: false,
                solves,
                limiting_ratio,
                fold: None,
            });
        }
    };
    let offset = if settings.bracket_at_limit {
        (0.25 * settings.tolerance).min(1e-6)
    } else {
        1e-6
    };
    let mut hi = limiting_ratio.map_or(2.0, |r| r.max(1.0) * (1.0 + offset));
    // whether `hi` is known to be at or above the threshold
    let mut hi_above = false;
    if settings.bracket_at_limit && limiting_ratio.is_some() && probe(hi, &mut warm)?.is_none() {
        hi_above = true;
        // the bracket [hi (1 - tolerance), hi] at once when a stick node holds up to there
        let below = (hi * (1.0 - 0.99 * settings.tolerance)).max(lo);
        match probe(below, &mut warm)? {
            Some((s, _)) => {
                lo = below;
                slip_lo = s;
            }
            None => hi = below,
        }
    }
    while !hi_above {
        match probe(hi, &mut warm)? {
            None => hi_above = true,
            Some((s, _)) => {
                lo = hi;
                slip_lo = s;
                hi *= 2.0;
                if hi > settings.max_ratio {
                    return Err(ContactError::NotConverged {
                        iterations: solves,
                        residual: f64::NAN,
                        load_factor: 1.0,
                    });
                }
            }
        }
    }
    while hi - lo > settings.tolerance * hi {
        let mid = 0.5 * (lo + hi);
        match probe(mid, &mut warm)? {
            None => hi = mid,
            Some((s, _)) => {
                lo = mid;
                slip_lo = s;
            }
        }
    }
    let past_runaway = solver
        .sliding()
        .and_then(|m| m.runaway_ratios)
        .is_some_and(|[_, upper]| hi > upper * (1.0 + 1e-9));
    let above_is_no_equilibrium =
        past_runaway || solver.check_equilibrium(EndLoads::ratio(hi)).is_err();
    Ok(ThresholdResult {
        ratio: hi,
        below: lo,
        above: hi,
        slip_fraction_below: slip_lo,
        above_is_no_equilibrium,
        solves,
        limiting_ratio,
        fold: None,
    })
}
