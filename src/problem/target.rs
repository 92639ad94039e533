//! Accuracy targets: capstan chooses the discretisation and grid of a [`Problem`] and refines
//! until every reported quantity's estimated error is below a tolerance.
//!
//! # Math
//! A ladder of discretisations `D_0, D_1, ...` gives every quantity `Q` a sequence
//! `Q_0, Q_1, ...`. The estimate of the error of `Q_k` is the difference to the step before,
//! kept from falling faster than a factor 4 per step:
//! ```text
//! d_k(Q) = |Q_k - Q_{k-1}|,      e_k(Q) = max(d_k, d_{k-1} / 4)
//! ```
//! For an error falling geometrically by `q` per step (`E_k = C q^-k`), `d_k` lies between
//! `(q - 1) E_k` (monotone) and `(q + 1) E_k` (alternating), so `e_k` is `2 ... 4` times the
//! true error at the `q ~ 3` measured on the default scene; the floor `d_{k-1} / 4` keeps a
//! step that happens to land near its predecessor from ending the refinement. Refinement
//! stops at the first `k >= 2` (two differences) with `e_k(Q) <= tol * scale(Q)` for every
//! `Q`; `scale(Q)` is the quantity's own magnitude, or for lengths along the contact face
//! (slip measure, stick-zone ends) the face's measure.
//!
//! # The ladder
//! Plane strain: `fem-qp` of order `p = 2, 3, ..., 7` (GLL nodes) with `p` geometric layers of
//! ratio `0.15` toward both ends of `x2` and `x3` (the hp meshes of the corner singularities
//! where the contact face meets the loaded ends: Schwab, *p- and hp-FEM*, section 4.4),
//! `16 + 2p` elements along `x2` and `2p + 2` through the thickness; past `p = 7` the `p = 7`
//! mesh halved in `h`. Measured on the default scene (docs/verification.md, "Accuracy
//! targets"), the threshold ratio converges geometrically along it (differences `2.7e-3,
//! 1.1e-3, 3.7e-4, 1.2e-4, 4.8e-5`), where the uniform FD and Q2 grids and a graded mesh
//! refined in `h` alone move it by `1e-4 ... 1e-3` from level to level. A 3-D body keeps its
//! method and doubles every direction per step (`n -> 2 n - 1`). The solver is the problem's
//! own.

use std::collections::BTreeMap;
use std::time::Instant;

use capstan_elasticity::contact::Dimension;
use capstan_elasticity::finite_element::{DiscretisationMethod, Grading};
use capstan_geometry::Surface;

use super::builder::Problem;

/// The most an estimate may fall from one step to the next: `e_k >= |Q_{k-1} - Q_{k-2}| / DROP`.
const DROP: f64 = 4.0;

/// The highest order of the plane ladder (order 8 with 8 layers of ratio 0.15 gives
/// elements `H 0.15^7 ~ 2e-6 H` and a singular factorisation).
const MAX_ORDER: usize = 7;

/// The grading ratio of the plane ladder toward the ends (Schwab's `sigma ~ 0.15`).
const GRADING: f64 = 0.15;

/// The least index of the step that may end the refinement (three solves: two differences).
const MIN_STEPS: usize = 2;
use super::solve::ProblemError;

/// What an accuracy target asks for, with its work budget.
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

    /// The default work budget: `300,000` unknowns (the plane ladder's step 6, the `p = 7`
    /// mesh halved, is `2 * 421 * 225 = 189,450`; the next `755,378`).
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

    /// With the work budget `max_unknowns`.
    #[must_use]
    pub fn with_max_unknowns(mut self, max_unknowns: usize) -> Self {
        self.max_unknowns = max_unknowns;
        self
    }
}

/// A quantity's value with the scale its tolerance is relative to.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scaled {
    /// The value.
    pub value: f64,
    /// `scale(Q)` (positive).
    pub scale: f64,
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
}

/// The result of [`Problem::refine_to`]: the last step's result and problem, the estimate of
/// every quantity, and the steps taken.
#[derive(Debug, Clone)]
pub struct Refined<T, S> {
    /// What the last step's evaluation returned.
    pub value: T,
    /// The problem of the last step (the chosen discretisation and grid).
    pub problem: Problem<S>,
    /// `e_k(Q) = |Q_k - Q_{k-1}|` of every quantity of the last step.
    pub estimates: BTreeMap<String, f64>,
    /// The steps, coarsest first.
    pub steps: Vec<Step>,
}

impl<S: Surface<f64> + Clone + Send + Sync + 'static> Problem<S> {
    /// The problem at step `k` of the accuracy ladder (see the [module docs](self)).
    ///
    /// # Errors
    /// The discretisation's errors ([`ProblemError::Elasticity`]).
    pub fn accuracy_step(&self, k: usize) -> Result<Self, ProblemError> {
        let mut p = self.clone();
        match &mut p.body.dimension {
            Dimension::Plane => {
                // hp: p = 2 ... 7 with p geometric layers, then the p = 7 mesh halved in h
                let order = (2 + k).min(MAX_ORDER);
                let halvings = k.saturating_sub(MAX_ORDER - 2);
                p.body.method = DiscretisationMethod::FemQp;
                p.body.settings.order = order;
                p.body.settings.grading = Grading::geometric(GRADING, order)?;
                p.body.n2 = order * ((16 + 2 * order) << halvings) + 1;
                p.body.n3 = order * ((2 * order + 2) << halvings) + 1;
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

    /// The number of unknowns of the body (2 per node in plane strain, 3 in 3-D).
    pub fn unknowns(&self) -> usize {
        match self.body.dimension {
            Dimension::Plane => 2 * self.body.n2 * self.body.n3,
            Dimension::Solid { n1, .. } => 3 * n1 * self.body.n2 * self.body.n3,
        }
    }

    /// Refines along the accuracy ladder until every quantity `eval` reports has
    /// `e_k(Q) <= target.tolerance * scale(Q)` (see the [module docs](self)).
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
        mut eval: impl FnMut(&Self) -> Result<(T, BTreeMap<String, Scaled>), ProblemError>,
    ) -> Result<Refined<T, S>, ProblemError> {
        let mut steps: Vec<Step> = Vec::new();
        let mut previous: Option<BTreeMap<String, Scaled>> = None;
        let mut differences: BTreeMap<String, f64> = BTreeMap::new();
        for k in 0.. {
            let problem = self.accuracy_step(k)?;
            let unknowns = problem.unknowns();
            if unknowns > target.max_unknowns {
                let (quantity, estimate) = steps
                    .last()
                    .and_then(|s| s.worst.clone())
                    .unwrap_or_else(|| ("every quantity".to_owned(), f64::INFINITY));
                return Err(ProblemError::AccuracyNotReached {
                    tolerance: target.tolerance,
                    quantity,
                    estimate,
                    unknowns,
                    max_unknowns: target.max_unknowns,
                });
            }
            let t = Instant::now();
            let (value, quantities) = eval(&problem)?;
            let mut estimates = BTreeMap::new();
            let mut worst: Option<(String, f64)> = None;
            if let Some(before) = &previous {
                for (name, q) in &quantities {
                    let relative = match before.get(name) {
                        Some(b) => {
                            let d = (q.value - b.value).abs();
                            // a step that happens to land near the previous value does not
                            // end the refinement: at most a factor DROP below the last change
                            let e = d.max(differences.get(name).map_or(0.0, |d0| d0 / DROP));
                            differences.insert(name.clone(), d);
                            estimates.insert(name.clone(), e);
                            e / q.scale
                        }
                        None => f64::INFINITY,
                    };
                    if worst.as_ref().is_none_or(|w| relative > w.1) {
                        worst = Some((name.clone(), relative));
                    }
                }
                for name in before.keys().filter(|n| !quantities.contains_key(*n)) {
                    worst = Some((name.clone(), f64::INFINITY));
                }
            }
            steps.push(Step {
                method: problem.body.method.name(),
                order: (problem.body.method == DiscretisationMethod::FemQp)
                    .then_some(problem.body.settings.order),
                grading: problem.body.settings.grading.ratio(),
                grid: problem.grid(),
                unknowns,
                seconds: t.elapsed().as_secs_f64(),
                worst: worst.clone(),
                values: quantities
                    .iter()
                    .map(|(k, q)| (k.clone(), q.value))
                    .collect(),
            });
            if let Some((_, w)) = worst
                && w <= target.tolerance
                && k >= MIN_STEPS
            {
                return Ok(Refined {
                    value,
                    problem,
                    estimates,
                    steps,
                });
            }
            previous = Some(quantities);
        }
        unreachable!("the budget ends the ladder")
    }
}
