//! Accuracy targets: capstan chooses the discretisation and grid of a [`Problem`] and refines
//! until every reported quantity's estimated error is below a tolerance.
//!
//! # Math
//! A ladder of discretisations `D_0, D_1, ...` (each the previous refined by 2 in `h`) gives
//! every quantity `Q` a sequence `Q_0, Q_1, ...`. The estimate of the error of `Q_k` is the
//! difference to the step before,
//! ```text
//! e_k(Q) = |Q_k - Q_{k-1}|        (Richardson with rate 1: |Q - Q_k| <= e_k for rate >= 1)
//! ```
//! and the refinement stops at the first `k >= 1` with `e_k(Q) <= tol * scale(Q)` for every
//! `Q`, `scale(Q)` being the quantity's own magnitude, or for lengths along the contact face
//! (slip measure, stick-zone ends) the face's measure. The rate is not taken from observation:
//! the quantities of the contact problem are pre-asymptotic on practical grids (the stick
//! zone is a boundary layer a few nodes wide, the end corners carry singular stresses), and
//! the rate-1 bound errs on the safe side (3x for a second-order quantity).
//!
//! # The ladder
//! Plane strain: `fem-qp` of order 4 (GLL nodes), geometrically graded toward both ends of
//! `x2` and `x3` (`sigma = 0.15`, 4 layers: the corner singularities where the contact face
//! meets the loaded ends), `16 * 2^k x 8 * 2^k` elements. Measured on the default scene, it
//! is the discretisation whose threshold ratio and contact quantities change least and most
//! steadily from step to step (docs/verification.md, "Accuracy targets"); the uniform FD and
//! Q2 grids move the threshold by `1e-3` between levels at the corners. A 3-D body keeps its
//! method and grid and doubles every direction per step (`n -> 2 n - 1`). The solver is the
//! problem's own.

use std::collections::BTreeMap;
use std::time::Instant;

use capstan_elasticity::contact::Dimension;
use capstan_elasticity::finite_element::{DiscretisationMethod, Grading};
use capstan_geometry::Surface;

use super::builder::Problem;
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

    /// The default work budget: `300,000` unknowns (the plane ladder's step 3, `129 x 65`
    /// elements of order 4, is `2 * 513 * 257 = 263,682`).
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
                let order = 4;
                p.body.method = DiscretisationMethod::FemQp;
                p.body.settings.order = order;
                p.body.settings.grading = Grading::geometric(0.15, 4)?;
                p.body.n2 = order * (16 << k) + 1;
                p.body.n3 = order * (8 << k) + 1;
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
                            let e = (q.value - b.value).abs();
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
