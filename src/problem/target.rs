//! Accuracy targets: capstan chooses the discretisation and grid of a [`Problem`] and refines
//! until every reported quantity's estimated error is below a tolerance.
//!
//! See [`AccuracyTarget`] for the estimate and the ladder.

use std::collections::BTreeMap;
use std::time::Instant;

use capstan_elasticity::contact::Dimension;
use capstan_elasticity::finite_element::{CornerSettings, DiscretisationMethod, Grading};
use capstan_geometry::Surface;

use super::builder::Problem;
use super::estimate::{Behaviour, SequenceEstimate, estimate_on, ladder_rate, twin};

/// The highest order of the plane ladder: order 7 with 7 layers of ratio 0.15 (elements
/// `H 0.15^6 ~ 1e-5 H`) gives a singular factorisation at `nu = 0.45`, order 8 already at the
/// default `nu = 1/4`.
const MAX_ORDER: usize = 6;

/// The grading ratio of the plane ladder toward the ends (Schwab's `sigma ~ 0.15`).
const GRADING: f64 = 0.15;

/// The least index of the step that may end the refinement (three solves: two differences).
const MIN_STEPS: usize = 2;
use super::solve::ProblemError;

/// What an accuracy target asks for, with its work budget.
///
/// # Math
/// A ladder of discretisations `D_0, D_1, ...` gives every quantity `Q` a sequence
/// `Q_0, Q_1, ...` with changes `d_k = Q_k - Q_{k-1}` and observed rates
/// `r_k = d_k / d_{k-1}`. The estimate `e_k(Q)` of the error of `Q_k` is
/// (`capstan::problem::estimate`, derived in its module docs):
/// ```text
/// c_k = max(|d_k|, |d_{k-1}| / 64)
/// e_k = 2 c_k |r| / |1 - r|          richardson: the observed rate r (the slower of the last
///                                    two when they agree within 3x, else the last; |r| >= 1/64)
/// e_k = 2 sqrt(c_k rho |d_{k-1}|) rho / (1 - rho)
///                                    ladder-rate: |r| < rho / 3 on a ladder with a rate rho
///                                    (the transition-graded one: the slowest last rate of the
///                                    slip measure and the stick-zone ends)
/// e_k = |d_k|                        last-change: at k = 1, a growing change, a change at the
///                                    solvers' tolerances, a quantity located between nodes
///                                    on the hp ladder (slip measure, stick-zone ends)
/// e_k = 2 |Q_k - Q'_k|               twin: at the stop of the transition-graded ladder, Q'_k
///                                    the stop's twin (the same order with rows toward the
///                                    contact face, Problem::transition_twin)
/// ```
/// Refinement stops at the first `k >= 2` (two differences) with `e_k(Q) <= tol * scale(Q)`
/// for every `Q`; `scale(Q)` is the quantity's own magnitude, or for lengths along the contact
/// face (slip measure, stick-zone ends) the face's measure. On the transition-graded ladder the
/// stop's twin is solved there and its estimates must meet the tolerance too (else the ladder
/// climbs on); they are the ones reported. On the default scene the estimates of the chosen
/// step are within 0.5x-10x of the true errors: on the hp ladder at `tol = 1e-3` and `1e-4`
/// against at least one of the two finest solves (docs/verification.md, "The contact tolerance
/// table"); on the transition-graded ladder at `1e-3`, `1e-4` and `1e-5` (0.85x ... 5.5x, the
/// twin's; docs/verification.md, "The transition-graded ladder").
///
/// # The ladder
/// Plane strain: `fem-qp` of order `p = 2, 3, ..., 6` (GLL nodes) with `p` geometric layers of
/// ratio `0.15` toward both ends of `x2` and `x3` (the hp meshes of the corner singularities
/// where the contact face meets the loaded ends: Schwab, *p- and hp-FEM*, section 4.4),
/// `16 + 2p` elements along `x2` and `2p + 2` through the thickness; past `p = 6` twice the
/// elements of `p = 6` along `x2` per step (the same layers, the uniform part and the layers
/// finer), the thickness kept at `p = 6`'s 14 elements. Measured on the default scene
/// (docs/verification.md, "Accuracy targets"), the threshold ratio converges geometrically
/// along it (differences `3.6e-3, 4.4e-4, 8.6e-5, 1.8e-5`, a factor 5 per step), where the
/// uniform FD and Q2 grids and a graded mesh refined in `h` alone move it by `1e-4 ... 1e-3`
/// from level to level. The `h` steps refine `x2` alone because what is left after `p = 6` is
/// the stick zone (about 0.03 long, under half of one interior element at `p = 6`) and the
/// pollution it spreads along the face (`sigma_n` at the quarter point moves by `2.9e-3`
/// relative from `p = 6` to its `h` step), an `x2` feature: doubling the thickness too changes
/// every quantity by under `1e-6` relative at twice the unknowns, and puts the step that settles
/// them over the default budget. A 3-D body keeps its
/// method and doubles every direction per step (`n -> 2 n - 1`). The solver is the problem's
/// own. The contact quantities of a plane body climb the transition-graded ladder instead
/// ([`Problem::transition_step`] through [`Problem::refine_along`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AccuracyTarget {
    /// The relative tolerance every quantity's estimated error must meet.
    pub tolerance: f64,
    /// The largest number of unknowns a step may have (the work budget).
    pub max_unknowns: usize,
}

impl AccuracyTarget {
    /// The allowed tolerances.
    pub const ALLOWED: &'static str = "1e-9 <= accuracy.tol <= 0.1";

    /// The default work budget: `300,000` unknowns (the plane ladder's steps 5, 6, 7, the
    /// `p = 6` mesh with 2, 4, 8 times the elements along `x2`, are `2 * 85 * (337, 673,
    /// 1345) = 57,290, 114,410, 228,650`; the next `457,130`).
    pub const DEFAULT_MAX_UNKNOWNS: usize = 300_000;

    /// A target of relative tolerance `tolerance` with the default budget.
    ///
    /// # Errors
    /// [`ProblemError::Elasticity`] (`InvalidParameter` naming `accuracy.tol`) outside
    /// [`Self::ALLOWED`].
    pub fn new(tolerance: f64) -> Result<Self, ProblemError> {
        if !(1e-9..=0.1).contains(&tolerance) {
            return Err(capstan_elasticity::ElasticityError::InvalidParameter {
                field: "accuracy.tol",
                value: tolerance,
                allowed: Self::ALLOWED,
            }
            .into());
        }
        Ok(Self {
            tolerance,
            max_unknowns: Self::DEFAULT_MAX_UNKNOWNS,
        })
    }

    /// Whether step `k` with `assessment` ends the refinement: `k >= 2` (two changes) and every
    /// quantity's relative estimate at most the tolerance.
    pub fn met(&self, k: usize, assessment: &Assessment) -> bool {
        k >= MIN_STEPS
            && assessment
                .worst
                .as_ref()
                .is_some_and(|(_, w)| *w <= self.tolerance)
    }

    /// With the work budget `max_unknowns`.
    #[must_use]
    pub fn with_max_unknowns(mut self, max_unknowns: usize) -> Self {
        self.max_unknowns = max_unknowns;
        self
    }
}

/// A quantity's value with the scale its tolerance is relative to and how it converges.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scaled {
    /// The value.
    pub value: f64,
    /// `scale(Q)` (positive).
    pub scale: f64,
    /// How the quantity converges, which picks its estimate's rule.
    pub behaviour: Behaviour,
}

impl Scaled {
    /// A quantity that converges at a rate ([`Behaviour::Smooth`]).
    pub fn smooth(value: f64, scale: f64) -> Self {
        Self {
            value,
            scale,
            behaviour: Behaviour::Smooth,
        }
    }
}

/// One step of the refinement: the discretisation, its size, time and worst estimate.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Step {
    /// The discretisation (`fem-qp`, ...).
    pub method: &'static str,
    /// Its order (`fem-qp`), else `null`.
    pub order: Option<usize>,
    /// The grading ratio toward the ends (`1`: uniform).
    pub grading: f64,
    /// `[n2, n3]`, or `[n1, n2, n3]` in 3-D.
    pub grid: Vec<usize>,
    /// Unknowns (2 per node in plane strain, 3 in 3-D).
    pub unknowns: usize,
    /// Wall time of the step, seconds.
    pub seconds: f64,
    /// The largest relative estimate `e_k(Q) / scale(Q)` and its quantity (`null` at step 0).
    pub worst: Option<(String, f64)>,
    /// Every quantity's value on this step.
    pub values: BTreeMap<String, f64>,
    /// `fem-qp-corner`: the `x2` points its mesh is graded toward (on the transition-graded
    /// ladder, [`Problem::transition_step`], the stick/slip transitions the first pass or the
    /// step before located); absent on other methods.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub transitions: Option<Vec<f64>>,
}

/// The result of [`Problem::refine_to`]: the last step's result and problem, the estimate of
/// every quantity, and the steps taken.
#[derive(Debug, Clone)]
pub struct Refined<T, S> {
    /// What the last step's evaluation returned.
    pub value: T,
    /// The problem of the last step (the chosen discretisation and grid).
    pub problem: Problem<S>,
    /// `e_k(Q)` of every quantity of the last step (see [`AccuracyTarget`]).
    pub estimates: BTreeMap<String, f64>,
    /// The rule of each estimate.
    pub rules: BTreeMap<String, super::estimate::Rule>,
    /// The steps, coarsest first.
    pub steps: Vec<Step>,
    /// The twins solved at the stops the ladder's estimates met
    /// ([`Problem::refine_along_twinned`]: the same order on a mesh refined where the stop's
    /// error lives), coarsest first: the last is the stop's, whose differences from the stop
    /// are the estimates (`worst`: the worst of them); an earlier one's estimates missed the
    /// tolerance. Empty on a ladder without twins.
    pub twins: Vec<Step>,
}

impl<S: Surface<f64> + Clone + Send + Sync + 'static> Problem<S> {
    /// The problem at step `k` of the accuracy ladder (see [`AccuracyTarget`]).
    ///
    /// # Errors
    /// The discretisation's errors ([`ProblemError::Elasticity`]).
    pub fn accuracy_step(&self, k: usize) -> Result<Self, ProblemError> {
        let mut p = self.clone();
        match &mut p.body.dimension {
            Dimension::Plane => {
                // hp: p = 2 ... 6 with p geometric layers, then the p = 6 mesh refined in h
                // along x2 (the stick zone's direction)
                let order = (2 + k).min(MAX_ORDER);
                let halvings = k.saturating_sub(MAX_ORDER - 2);
                p.body.method = DiscretisationMethod::FemQp;
                p.body.settings.order = order;
                p.body.settings.grading = Grading::geometric(GRADING, order)?;
                p.body.n2 = order * ((16 + 2 * order) << halvings) + 1;
                p.body.n3 = order * (2 * order + 2) + 1;
            }
            Dimension::Solid { n1, .. } => {
                let twice = |n: usize| (n - 1) * (1 << k) + 1;
                *n1 = twice(*n1);
                p.body.n2 = twice(p.body.n2);
                p.body.n3 = twice(p.body.n3);
            }
        }
        p.body.scheme()?.check_nodes("grid.n2", p.body.n2)?;
        Ok(p)
    }

    /// The number of unknowns of the body (2 per node in plane strain, 3 in 3-D). For
    /// `fem-qp-corner` an upper bound: the corner mesh's nodes with `2 layers` more element
    /// columns per transition point (each point adds at most `layers` lines on each side; the
    /// dropped coarse lines are not subtracted) and `2 face_layers` more columns and rows.
    pub fn unknowns(&self) -> usize {
        let nodes_2d = if self.body.method == DiscretisationMethod::FemQpCorner {
            let s = &self.body.settings;
            let p = s.order.max(1);
            let extra = 2 * s.transitions.layers * s.transitions.points.len();
            let face = 2 * s.transitions.face_layers;
            CornerSettings {
                order: p,
                cells: [
                    (self.body.n2 - 1) / p + extra + face,
                    (self.body.n3 - 1) / p + face,
                ],
                layers: s.corner_layers,
                ratio: s.corner_ratio,
            }
            .node_count()
        } else {
            self.body.n2 * self.body.n3
        };
        match self.body.dimension {
            Dimension::Plane => 2 * nodes_2d,
            Dimension::Solid { n1, .. } => 3 * n1 * nodes_2d,
        }
    }

    /// Refines along the accuracy ladder until every quantity `eval` reports has
    /// `e_k(Q) <= target.tolerance * scale(Q)` (see [`AccuracyTarget`]).
    ///
    /// `eval` solves one step's problem and returns its result and quantities by name. A
    /// quantity present on one step and missing on the other (a stick zone that appears) has
    /// no estimate yet, and refinement goes on.
    ///
    /// # Errors
    /// `eval`'s errors; [`ProblemError::AccuracyNotReached`] when the next step would exceed
    /// `target.max_unknowns`.
    pub fn refine_to<T>(
        &self,
        target: &AccuracyTarget,
        eval: impl FnMut(&Self) -> Result<(T, BTreeMap<String, Scaled>), ProblemError>,
    ) -> Result<Refined<T, S>, ProblemError> {
        self.refine_along(target, |k| self.accuracy_step(k), eval)
    }

    /// [`Self::refine_to`] along the ladder `ladder(k)`, `k = 0, 1, ...` (the hp ladder
    /// [`Self::accuracy_step`], or the transition-graded [`Self::transition_step`]), with the
    /// same estimate and stopping rule.
    ///
    /// # Errors
    /// `ladder`'s and `eval`'s errors; [`ProblemError::AccuracyNotReached`] when the next
    /// step would exceed `target.max_unknowns` ([`Self::unknowns`]).
    pub fn refine_along<T>(
        &self,
        target: &AccuracyTarget,
        ladder: impl Fn(usize) -> Result<Self, ProblemError>,
        eval: impl FnMut(&Self) -> Result<(T, BTreeMap<String, Scaled>), ProblemError>,
    ) -> Result<Refined<T, S>, ProblemError> {
        self.refine_along_twinned(target, ladder, |_| Ok(None), eval)
    }

    /// [`Self::refine_along`] with a twin at the stop: where the estimates along the ladder meet
    /// the tolerance at step `k`, `twin_of(step k)` (the same order on a mesh refined where the
    /// step's error lives: [`Self::transition_twin`]; `None`: no twin, the ladder's estimates
    /// stand) is solved by `eval` too, and every quantity's estimate is
    /// `SAFETY |Q_k - Q'_k|` (rule `twin`, `capstan::problem::estimate`, "The twin at the
    /// stop"). The refinement stops when every twin estimate meets the tolerance as well, and
    /// climbs on otherwise (a twin at each later stop). The twins' times are in
    /// [`Refined::twins`].
    ///
    /// # Errors
    /// As [`Self::refine_along`]; `twin_of`'s errors; [`ProblemError::AccuracyNotReached`] when a
    /// twin would exceed `target.max_unknowns`.
    pub fn refine_along_twinned<T>(
        &self,
        target: &AccuracyTarget,
        ladder: impl Fn(usize) -> Result<Self, ProblemError>,
        twin_of: impl Fn(&Self) -> Result<Option<Self>, ProblemError>,
        mut eval: impl FnMut(&Self) -> Result<(T, BTreeMap<String, Scaled>), ProblemError>,
    ) -> Result<Refined<T, S>, ProblemError> {
        let mut steps: Vec<Step> = Vec::new();
        // every step's quantities, coarsest first
        let mut seen: Vec<BTreeMap<String, Scaled>> = Vec::new();
        let mut twins: Vec<Step> = Vec::new();
        for k in 0.. {
            let problem = ladder(k)?;
            let unknowns = problem.unknowns();
            if unknowns > target.max_unknowns {
                let worst = steps
                    .last()
                    .and_then(|s| s.worst.clone())
                    .unwrap_or_else(|| ("every quantity".to_owned(), f64::INFINITY));
                return Err(not_reached(target, &seen, worst, unknowns));
            }
            let t = Instant::now();
            let (value, quantities) = eval(&problem)?;
            let seconds = t.elapsed().as_secs_f64();
            seen.push(quantities);
            let assessment = assess(&seen);
            let mut step = step_of(&problem, unknowns, seconds, &seen[k]);
            step.worst = assessment.worst.clone();
            steps.push(step);
            if !target.met(k, &assessment) {
                continue;
            }
            let Some(twin_problem) = twin_of(&problem)? else {
                return Ok(refined(value, problem, &assessment, steps, twins));
            };
            let unknowns = twin_problem.unknowns();
            if unknowns > target.max_unknowns {
                let worst = assessment.worst.clone().unwrap_or_default();
                return Err(not_reached(target, &seen, worst, unknowns));
            }
            let t = Instant::now();
            let (_, twin_quantities) = eval(&twin_problem)?;
            let seconds = t.elapsed().as_secs_f64();
            let twinned = assess_twin(&seen[k], &twin_quantities);
            let mut twin_step = step_of(&twin_problem, unknowns, seconds, &twin_quantities);
            twin_step.worst = twinned.worst.clone();
            twins.push(twin_step);
            if twinned
                .worst
                .as_ref()
                .is_some_and(|(_, w)| *w <= target.tolerance)
            {
                return Ok(refined(value, problem, &twinned, steps, twins));
            }
        }
        unreachable!("the budget ends the ladder")
    }
}

/// The record of one solved problem of a ladder (its `worst` unset).
fn step_of<S: Surface<f64> + Clone + Send + Sync + 'static>(
    problem: &Problem<S>,
    unknowns: usize,
    seconds: f64,
    quantities: &BTreeMap<String, Scaled>,
) -> Step {
    let method = problem.body.method;
    let corner = method == DiscretisationMethod::FemQpCorner;
    Step {
        method: method.name(),
        order: (method == DiscretisationMethod::FemQp || corner)
            .then_some(problem.body.settings.order),
        grading: if corner {
            problem.body.settings.corner_ratio
        } else {
            problem.body.settings.grading.ratio()
        },
        grid: problem.grid(),
        unknowns,
        seconds,
        worst: None,
        values: quantities
            .iter()
            .map(|(k, q)| (k.clone(), q.value))
            .collect(),
        transitions: corner.then(|| problem.body.settings.transitions.points.clone()),
    }
}

/// The result of a refinement that stopped with `assessment`'s estimates.
fn refined<T, S>(
    value: T,
    problem: Problem<S>,
    assessment: &Assessment,
    steps: Vec<Step>,
    twins: Vec<Step>,
) -> Refined<T, S> {
    Refined {
        value,
        problem,
        estimates: assessment
            .estimates
            .iter()
            .map(|(n, e)| (n.clone(), e.error))
            .collect(),
        rules: assessment
            .estimates
            .iter()
            .map(|(n, e)| (n.clone(), e.rule))
            .collect(),
        steps,
        twins,
    }
}

/// Assesses a stop by its twin: every quantity of `stop` gets [`twin`]'s estimate
/// `SAFETY |Q_k - Q'_k|` from its value in `twin_quantities` (the stop's twin, see
/// [`Problem::refine_along_twinned`]); a quantity missing on the twin has none (infinite
/// relative estimate), and the worst relative estimate is over them all.
pub fn assess_twin(
    stop: &BTreeMap<String, Scaled>,
    twin_quantities: &BTreeMap<String, Scaled>,
) -> Assessment {
    let mut out = Assessment::default();
    for (name, q) in stop {
        let estimate = twin_quantities
            .get(name)
            .and_then(|t| twin(q.value, t.value));
        out.record(name, estimate, q.scale);
    }
    out
}

/// The estimates of the last step of a ladder: every quantity's [`SequenceEstimate`] from its
/// values on the steps so far, and the worst relative estimate.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Assessment {
    /// The estimate of every quantity of the last step that has one (two or more steps).
    pub estimates: BTreeMap<String, SequenceEstimate>,
    /// The largest `e_k(Q) / scale(Q)` and its quantity: infinite for a quantity with no
    /// estimate yet or missing on the last step; `None` on the first step.
    pub worst: Option<(String, f64)>,
}

impl Assessment {
    /// Records quantity `name`'s `estimate` (none: not yet estimable) and keeps the worst
    /// relative one, `e(Q) / scale(Q)` (infinite without an estimate).
    fn record(&mut self, name: &str, estimate: Option<SequenceEstimate>, scale: f64) {
        let relative = match estimate {
            Some(e) => {
                self.estimates.insert(name.to_owned(), e);
                e.error / scale
            }
            None => f64::INFINITY,
        };
        if self.worst.as_ref().is_none_or(|w| relative > w.1) {
            self.worst = Some((name.to_owned(), relative));
        }
    }
}

/// The contiguous run of values of `name` ending at the last of `steps` (a quantity missing on
/// a step starts again after it).
fn run(steps: &[BTreeMap<String, Scaled>], name: &str) -> Vec<Scaled> {
    let mut run: Vec<Scaled> = steps
        .iter()
        .rev()
        .map_while(|s| s.get(name).copied())
        .collect();
    run.reverse();
    run
}

/// The relative changes `|d_j| / scale_j` of `name` along its run, for the budget's error.
fn relative_changes(steps: &[BTreeMap<String, Scaled>], name: &str) -> Vec<f64> {
    run(steps, name)
        .windows(2)
        .map(|w| (w[1].value - w[0].value).abs() / w[1].scale)
        .collect()
}

/// Assesses the last of `steps` (every step's quantities along the ladder, coarsest first):
/// each quantity's estimate from its run of values ([`estimate_on`], the rule of
/// [`AccuracyTarget`]) on the ladder's rate, [`ladder_rate`] of the runs of its
/// [`Behaviour::Transition`] quantities (none on a ladder without them), and the worst
/// relative estimate. The same function serves [`Problem::refine_to`],
/// [`Problem::refine_along`] and the cached ladders of examples/contact_accuracy.rs.
pub fn assess(steps: &[BTreeMap<String, Scaled>]) -> Assessment {
    let mut out = Assessment::default();
    let Some(last) = steps.last() else {
        return out;
    };
    if steps.len() < 2 {
        return out;
    }
    let values = |name: &str| -> Vec<f64> { run(steps, name).iter().map(|s| s.value).collect() };
    let transitions: Vec<Vec<f64>> = last
        .iter()
        .filter(|(_, q)| q.behaviour == Behaviour::Transition)
        .map(|(name, _)| values(name))
        .collect();
    let ladder = ladder_rate(transitions.iter().map(Vec::as_slice));
    for (name, q) in last {
        out.record(
            name,
            estimate_on(&values(name), q.behaviour, ladder),
            q.scale,
        );
    }
    for name in steps[steps.len() - 2]
        .keys()
        .filter(|n| !last.contains_key(*n))
    {
        out.worst = Some((name.clone(), f64::INFINITY));
    }
    out
}

/// The error of a refinement stopped by `target.max_unknowns` before a step (or its twin) of
/// `unknowns` unknowns: the worst quantity and its estimate, with its trend along `seen`.
fn not_reached(
    target: &AccuracyTarget,
    seen: &[BTreeMap<String, Scaled>],
    (quantity, estimate): (String, f64),
    unknowns: usize,
) -> ProblemError {
    ProblemError::AccuracyNotReached {
        tolerance: target.tolerance,
        trend: trend(&relative_changes(seen, &quantity)),
        quantity,
        estimate,
        unknowns,
        max_unknowns: target.max_unknowns,
    }
}

/// How a quantity's relative differences `r_1, ..., r_k` along the ladder went, for the
/// budget's error: the last three, and `falling` (each below the one before: converging, too
/// slowly for the budget) or `not falling` (the last above the one before: the quantity does
/// not converge on this ladder yet, e.g. a point value polluted by a feature the ladder does
/// not resolve).
fn trend(relative: &[f64]) -> String {
    let last = &relative[relative.len().saturating_sub(3)..];
    if last.is_empty() {
        return "no difference yet".to_owned();
    }
    let listed = last
        .iter()
        .map(|r| format!("{r:.1e}"))
        .collect::<Vec<_>>()
        .join(", ");
    let falling = last.windows(2).all(|w| w[1] < w[0]);
    format!(
        "its last relative differences along the ladder {listed}: {}",
        if falling {
            "falling, converging too slowly for the budget"
        } else {
            "not falling, not converging on this ladder"
        }
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::problem::estimate::{R_MIN, Rule, SAFETY};

    /// The refinement value `q` and the one quantity `"q"` at scale 1.
    fn one_quantity(q: f64) -> (f64, BTreeMap<String, Scaled>) {
        (
            q,
            BTreeMap::from([("q".to_owned(), Scaled::smooth(q, 1.0))]),
        )
    }

    /// A manufactured quantity along the ladder: `Q_k = 1 + (-1)^k C 3^-k` (geometric with
    /// alternating sign), no solve.
    fn alternating(k: usize) -> f64 {
        1.0 + (-1.0f64).powi(k as i32) * 0.1 * 3f64.powi(-(k as i32))
    }

    fn step_of(p: &Problem) -> usize {
        let halvings = ((p.body.n2 - 1)
            / (p.body.settings.order * (16 + 2 * p.body.settings.order)))
            .trailing_zeros() as usize;
        (p.body.settings.order - 2) + halvings
    }

    #[test]
    fn refine_to_stops_where_the_estimate_meets_the_tolerance_and_brackets_the_error() {
        let problem = Problem::paper();
        for tol in [1e-2, 1e-3, 1e-4] {
            let target = AccuracyTarget::new(tol)
                .unwrap()
                .with_max_unknowns(usize::MAX);
            let refined = problem
                .refine_to(&target, |p| {
                    let q = alternating(step_of(p));
                    Ok(one_quantity(q))
                })
                .unwrap();
            let e = refined.estimates["q"];
            let truth = (refined.value - 1.0).abs();
            assert!(e <= tol, "{tol}: estimate {e:.2e}");
            assert!(truth <= tol, "{tol}: true error {truth:.2e}");
            // geometric: Richardson with the observed rate -1/3 is exact, times the safety
            // factor (the old max(d_k, d_{k-1} / 4) gave 4x)
            assert_eq!(refined.rules["q"], Rule::Richardson);
            assert!(
                (e / truth - SAFETY).abs() < 1e-9,
                "{tol}: ratio {}",
                e / truth
            );
            assert!(refined.steps.len() > MIN_STEPS);
            assert_eq!(refined.steps.len(), step_of(&refined.problem) + 1);
        }
    }

    #[test]
    fn a_feature_resolved_between_steps_takes_the_last_rate_no_faster_than_r_min() {
        // changes 0.1, 1e-2, 1e-5, 1e-7: the rates 0.1 and 1e-3 disagree at step 3 (a feature
        // resolved): the last rate, held at R_MIN = 1/64, on max(d_3, R_MIN d_2)
        let values = [0.0, 0.1, 0.11, 0.11 + 1e-5, 0.11 + 1e-5 + 1e-7];
        let target = AccuracyTarget::new(1e-3).unwrap();
        let refined = Problem::paper()
            .refine_to(&target, |p| {
                let q = values[step_of(p)];
                Ok(one_quantity(q))
            })
            .unwrap();
        assert_eq!(refined.steps.len(), 4);
        assert_eq!(refined.rules["q"], Rule::Richardson);
        let expected = SAFETY * (1e-2 * R_MIN) * R_MIN / (1.0 - R_MIN);
        assert!((refined.estimates["q"] / expected - 1.0).abs() < 1e-9);
        // step 2: the one rate 0.1, 2 * 1e-2 * 0.1 / 0.9 misses the tolerance
        let worst = refined.steps[2].worst.as_ref().unwrap().1;
        assert!(
            (worst / (SAFETY * 1e-2 * 0.1 / 0.9) - 1.0).abs() < 1e-9,
            "{worst}"
        );
    }

    /// The twin of a step in the tests below: the step's problem with `n3 = TWIN_N3`.
    const TWIN_N3: usize = 7;

    /// Climbs the hp ladder of [`Problem::paper`] with a manufactured quantity: `ladder[k]` at
    /// step `k`, `twin[k]` on the twin of step `k`.
    fn climb_twinned(
        tol: f64,
        ladder: &[f64],
        twin: &[f64],
    ) -> Refined<f64, capstan_geometry::Obstacle> {
        let problem = Problem::paper();
        let target = AccuracyTarget::new(tol).unwrap();
        problem
            .refine_along_twinned(
                &target,
                |k| problem.accuracy_step(k),
                |stop| {
                    let mut t = stop.clone();
                    t.body.n3 = TWIN_N3;
                    Ok(Some(t))
                },
                |p| {
                    let k = p.body.settings.order - 2;
                    Ok(one_quantity(if p.body.n3 == TWIN_N3 {
                        twin[k]
                    } else {
                        ladder[k]
                    }))
                },
            )
            .unwrap()
    }

    #[test]
    fn the_twin_at_the_stop_sees_a_landing_the_ladder_cannot() {
        // the limit 1; step 2 lands 1e-7 from it after changes 0.09, 0.0099999: the ladder's
        // Richardson (rate 0.11) says 2.5e-3, 25,000x the error; the twin, 5e-8 from the limit
        // on the same side, says 2 |Q_2 - Q'_2| = 1e-7 (1x)
        let ladder = [1.1, 1.01, 1.0 + 1e-7, 1.0];
        let twin = [1.0, 1.0, 1.0 + 5e-8, 1.0];
        let refined = climb_twinned(1e-2, &ladder, &twin);
        assert_eq!(refined.steps.len(), 3);
        assert_eq!(refined.twins.len(), 1);
        assert_eq!(refined.rules["q"], Rule::Twin);
        let e = refined.estimates["q"];
        assert!((e / 1e-7 - 1.0).abs() < 1e-6, "{e:.3e}");
        // the ladder's own estimate at the stop, kept in the step's record
        let ladder_estimate = refined.steps[2].worst.as_ref().unwrap().1;
        assert!(ladder_estimate > 1e4 * 1e-7, "{ladder_estimate:.2e}");
        assert_eq!(refined.twins[0].worst.as_ref().unwrap().1, e);
    }

    #[test]
    fn a_twin_that_misses_the_tolerance_sends_the_ladder_on() {
        // at step 2 the twin is 0.05 off the step (estimate 0.1 > 1e-2): step 3 and its twin
        let ladder = [1.1, 1.01, 1.001, 1.0001, 1.0];
        let twin = [1.0, 1.0, 1.051, 1.0, 1.0];
        let refined = climb_twinned(1e-2, &ladder, &twin);
        assert_eq!(refined.steps.len(), 4);
        assert_eq!(refined.twins.len(), 2);
        assert!(refined.twins[0].worst.as_ref().unwrap().1 > 1e-2);
        assert!((refined.estimates["q"] / (2.0 * 1e-4) - 1.0).abs() < 1e-9);
        assert!((refined.value - 1.0001).abs() < 1e-15);
    }

    #[test]
    fn a_spent_budget_is_a_typed_error_naming_the_quantity() {
        let target = AccuracyTarget::new(1e-6).unwrap().with_max_unknowns(10_000);
        let e = Problem::paper()
            .refine_to(&target, |p| {
                let q = 1.0 / p.body.settings.order as f64; // converges too slowly
                Ok((
                    (),
                    BTreeMap::from([("slow".to_owned(), Scaled::smooth(q, 1.0))]),
                ))
            })
            .unwrap_err();
        match e {
            ProblemError::AccuracyNotReached {
                quantity,
                unknowns,
                max_unknowns,
                trend,
                ..
            } => {
                assert_eq!(quantity, "slow");
                // 1/2, 1/3, 1/4 (p = 5 is over the budget): differences 1/6, 1/12
                assert_eq!(
                    trend,
                    "its last relative differences along the ladder 1.7e-1, 8.3e-2: \
                     falling, converging too slowly for the budget"
                );
                assert!(unknowns > max_unknowns);
            }
            e => panic!("{e}"),
        }
        assert!(AccuracyTarget::new(0.0).is_err());
        assert!(AccuracyTarget::new(f64::NAN).is_err());
        assert!(AccuracyTarget::new(0.5).is_err());
    }

    #[test]
    fn a_quantity_whose_differences_rise_is_reported_as_not_converging() {
        // the default scene's sigma_n at the quarter point along the old ladder (x2 and x3
        // doubled past p = 6): relative differences 6.0e-4, 1.7e-3, 2.9e-3
        let t = trend(&[3.0e-2, 6.4e-3, 6.0e-4, 1.7e-3, 2.9e-3]);
        assert_eq!(
            t,
            "its last relative differences along the ladder 6.0e-4, 1.7e-3, 2.9e-3: not \
             falling, not converging on this ladder"
        );
        assert!(trend(&[1e-2, 3e-3, 4e-3]).contains("not falling"));
        assert_eq!(trend(&[]), "no difference yet");
    }

    #[test]
    fn the_plane_ladder_is_hp_then_h() {
        let p = Problem::paper();
        let grids: Vec<_> = (0..7)
            .map(|k| {
                let s = p.accuracy_step(k).unwrap();
                (s.body.settings.order, s.body.n2, s.body.n3)
            })
            .collect();
        assert_eq!(
            grids,
            [
                (2, 41, 13),
                (3, 67, 25),
                (4, 97, 41),
                (5, 131, 61),
                (6, 169, 85),
                (6, 337, 85),
                (6, 673, 85)
            ]
        );
    }
}
