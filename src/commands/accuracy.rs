//! Error estimates of the converging quantities (`estimated_error` in `capstan contact --json`
//! and `capstan threshold --json`): every quantity is computed again one grid level coarser,
//! with the same discretisation and solver, and the difference is the estimate.
//!
//! # Math
//! With `Q_h` the quantity on the scene's grid and `Q_2h` on the next coarser level of grid
//! sequencing (`n -> (n + 1) / 2` nodes per direction, kept whole elements for `fem-q2` and
//! `fem-qp`: [`capstan_elasticity::registration::DiscretisationScheme::coarser_nodes`]),
//! ```text
//! estimated_error(Q) = |Q_h - Q_2h| / (2^p - 1),  p = 1
//! ```
//! that is Richardson's estimate of `|Q - Q_h|` for a first-order quantity, and an upper bound
//! `(2^p - 1)` times too large for one of order `p > 1` (3x for `p = 2`). The rate is fixed at
//! 1 rather than observed because the quantities of the paper's problem are not in their
//! asymptotic range on practical grids: the stick zone of the regularised law is a boundary
//! layer a few nodes wide at the default grid (docs/verification.md, "Converging
//! quantities"), and the end corners of the contact face carry singular stresses, so the
//! observed rates vary between 0.3 and 2 from level to level. A quantity that the coarser
//! level does not have (the stick zone vanished there) has no estimate (`null`).
//!
//! After the full-system Newton's grid sequencing the coarser level is the one the sequence
//! solved on the way ([`crate::problem::Solved::coarser`]), with no solve of its own.
//!
//! The estimate is of the discretisation error only; the solver's own tolerances (Newton
//! `1e-10` relative residual, the threshold bisection `1e-6` relative) are far below it.

use std::collections::BTreeMap;

use serde::Serialize;

use std::cell::RefCell;
use std::time::Instant;

use capstan_elasticity::contact::{ContactQuantities, ContactSolution, Dimension};

use crate::error::CliError;
use crate::problem::estimate::{Behaviour, Rule};
use crate::problem::{AccuracyTarget, Problem, Refined, Scaled, Step};
use crate::scene::Scene;

/// `estimated_error` of a report: the estimate of every converging quantity, by name, and the
/// grid it was estimated from.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ErrorEstimate {
    /// `|Q_h - Q_2h|` for every converging quantity `Q` of the report (see the module docs);
    /// `null` for a quantity missing on the coarser grid.
    pub quantities: BTreeMap<String, Option<f64>>,
    /// `[n2, n3]` of the coarser grid (`[n1, n2, n3]` on a 3-D body).
    pub coarser_grid: Vec<usize>,
    /// How the estimate was made: `one-level-coarser`, or under an accuracy target
    /// `previous-refinement` (along the ladder) or `stop-twin` (the difference from the stop's
    /// twin, `accuracy.twins`, on the transition-graded ladder).
    pub method: &'static str,
    /// Under an accuracy target, the rule of each quantity's estimate (`richardson`,
    /// `ladder-rate`, `last-change` along the ladder, `twin` from the stop's twin:
    /// [`crate::problem::estimate`]); absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rules: Option<BTreeMap<String, Rule>>,
}

impl ErrorEstimate {
    /// The estimate from the quantities on the scene's grid (`fine`) and one level coarser.
    pub fn from_levels(
        fine: &BTreeMap<String, f64>,
        coarse: &BTreeMap<String, f64>,
        coarser_grid: Vec<usize>,
    ) -> Self {
        let quantities = fine
            .iter()
            .map(|(name, q)| {
                let e = coarse.get(name).map(|c| (q - c).abs());
                (name.clone(), e.filter(|e| e.is_finite()))
            })
            .collect();
        Self {
            quantities,
            coarser_grid,
            method: "one-level-coarser",
            rules: None,
        }
    }
}

/// The probe points of a scene: `output.probe_x2`, or the quarter points of the contact
/// interval when it is not set.
pub fn probes(scene: &Scene) -> Vec<f64> {
    scene.output.probe_x2.clone().unwrap_or_else(|| {
        capstan_elasticity::contact::default_probes([
            scene.membrane.theta0,
            scene.membrane.theta_max,
        ])
    })
}

/// The observer of the coarser solve of an estimate: forwards only the stop request of the
/// run's observer (Ctrl-C, `--timeout`, a Python callback's stop), so progress lines and
/// callbacks describe the scene's own solve.
pub struct StopOnly<'a>(pub &'a mut dyn capstan_elasticity::solvers::Observer<f64>);

impl capstan_elasticity::solvers::Observer<f64> for StopOnly<'_> {
    fn iteration(&mut self, _progress: &capstan_elasticity::solvers::Progress<f64>) {}

    fn interrupted(&mut self) -> bool {
        self.0.interrupted()
    }
}

/// `accuracy` in a report run to an accuracy target (`accuracy.tol`): the target, what capstan
/// chose, and every refinement step.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AccuracyReport {
    /// `accuracy.tol`.
    pub tol: f64,
    /// `accuracy.max_unknowns`.
    pub max_unknowns: usize,
    /// The chosen discretisation and grid: the last step.
    pub chosen: Step,
    /// The contact solver (`solver.nonlinear`).
    pub solver: String,
    /// Every step, coarsest first (`worst`: the largest relative estimate and its quantity).
    pub steps: Vec<Step>,
    /// The contact quantities of a plane-strain body: the first pass that located the
    /// stick/slip transitions the ladder's meshes are graded toward
    /// ([`crate::problem::Problem::transition_step`]); absent on the hp ladder (`threshold`,
    /// 3-D bodies).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub transition_grading: Option<TransitionChoice>,
    /// The twins solved at the stops of the transition-graded ladder
    /// ([`crate::problem::Problem::transition_twin`]: the stop's order with rows toward the
    /// contact face), coarsest first; the last is the chosen step's, whose differences from it
    /// are `estimated_error` (rule `twin`; `worst`: the largest relative one). Absent on the
    /// hp ladder.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub twins: Vec<Step>,
}

/// `accuracy.transition_grading`: how the transition-graded ladder was placed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TransitionChoice {
    /// The first pass: `fem-qp-corner` of this order ...
    pub first_pass_order: usize,
    /// ... on these `[x2, x3]` element cells ...
    pub first_pass_cells: [usize; 2],
    /// ... with these unknowns ...
    pub first_pass_unknowns: usize,
    /// ... in this wall time (seconds).
    pub first_pass_seconds: f64,
    /// The stick/slip transitions it located (`x2`, increasing; empty: no stick zone, the
    /// ladder is the corner mesh ungraded).
    pub transitions: Vec<f64>,
    /// Geometric layers on each side of every transition ...
    pub layers: usize,
    /// ... of this ratio.
    pub ratio: f64,
}

impl AccuracyReport {
    /// The report of a refinement to `target` with the scene's solver.
    pub fn new<T, S>(
        scene: &Scene,
        target: &AccuracyTarget,
        refined: &Refined<T, S>,
    ) -> Option<Self> {
        Some(Self {
            tol: target.tolerance,
            max_unknowns: target.max_unknowns,
            chosen: refined.steps.last()?.clone(),
            solver: scene.solver.nonlinear.clone(),
            steps: refined.steps.clone(),
            transition_grading: None,
            twins: refined.twins.clone(),
        })
    }

    /// The estimate of a refinement: `e_k(Q)` of every quantity along the ladder (Richardson
    /// with the observed rate, with the ladder's rate, or the last change:
    /// [`crate::problem::AccuracyTarget`]), with
    /// the grid of the step before (method `previous-refinement`); on a ladder with a twin at
    /// the stop, the twin's `SAFETY |Q_k - Q'_k|` (method `stop-twin`).
    pub fn estimate<T, S>(refined: &Refined<T, S>) -> ErrorEstimate {
        let n = refined.steps.len();
        ErrorEstimate {
            quantities: refined
                .estimates
                .iter()
                .map(|(k, v)| (k.clone(), Some(*v)))
                .collect(),
            coarser_grid: refined.steps[n.saturating_sub(2)].grid.clone(),
            method: if refined.twins.is_empty() {
                "previous-refinement"
            } else {
                "stop-twin"
            },
            rules: Some(refined.rules.clone()),
        }
    }

    /// One line per step and the choice, for the text reports.
    pub fn table(&self) -> String {
        let mut s = format!(
            "  accuracy target {:e}: chose {}{} graded {} on {:?} ({} unknowns), solver {}\n",
            self.tol,
            self.chosen.method,
            self.chosen
                .order
                .map_or_else(String::new, |p| format!(" p = {p}")),
            self.chosen.grading,
            self.chosen.grid,
            self.chosen.unknowns,
            self.solver
        );
        if let Some(t) = &self.transition_grading {
            s += &format!(
                "    graded toward the stick/slip transitions {:?} ({} layers of {} each side), located by a first pass p = {} on {:?} cells ({} unknowns, {:.3} s)\n",
                t.transitions,
                t.layers,
                t.ratio,
                t.first_pass_order,
                t.first_pass_cells,
                t.first_pass_unknowns,
                t.first_pass_seconds
            );
        }
        for step in &self.steps {
            s += &format!(
                "    step {:?}: {:.3} s{}\n",
                step.grid,
                step.seconds,
                step.worst
                    .as_ref()
                    .map_or_else(String::new, |(q, e)| format!(
                        ", worst relative estimate {e:.2e} ({q})"
                    ))
            );
        }
        for twin in &self.twins {
            s += &format!(
                "    twin: p = {} on {:?} with rows toward the contact face ({} unknowns): {:.3} s{}\n",
                twin.order.unwrap_or_default(),
                twin.grid,
                twin.unknowns,
                twin.seconds,
                twin.worst
                    .as_ref()
                    .map_or_else(String::new, |(q, e)| format!(
                        ", worst relative estimate {e:.2e} ({q})"
                    ))
            );
        }
        s
    }
}

/// The quantities of a contact solution with the scales their tolerances are relative to:
/// lengths along the contact face (`slip_measure`, `stick_from`, `stick_to`) the face's
/// measure, every other quantity its own magnitude; the behaviour of each from [`behaviour`].
pub fn scaled(
    quantities: &ContactQuantities,
    solution: &ContactSolution,
) -> BTreeMap<String, Scaled> {
    quantities
        .scalars(solution)
        .into_iter()
        .map(|(name, value)| {
            let scale = match name.as_str() {
                "slip_measure" | "stick_from" | "stick_to" => quantities.contact_measure,
                _ => value.abs(),
            };
            let scale = scale.max(f64::MIN_POSITIVE);
            let behaviour = behaviour(&name);
            (
                name,
                Scaled {
                    value,
                    scale,
                    behaviour,
                },
            )
        })
        .collect()
}

/// How a contact quantity converges along a ladder, by its name: the slip measures and the
/// stick-zone ends are located between nodes ([`Behaviour::Located`]), every other quantity
/// converges at a rate ([`Behaviour::Smooth`]).
pub fn behaviour(name: &str) -> Behaviour {
    match name {
        "slip_measure" | "slip_physical_measure" | "stick_from" | "stick_to" => Behaviour::Located,
        _ => Behaviour::Smooth,
    }
}

/// How a contact quantity converges along the transition-graded ladder
/// ([`crate::problem::Problem::transition_step`]), by its name: the slip measures and the
/// stick-zone ends converge at a rate that is the ladder's ([`Behaviour::Transition`]), every
/// other quantity at a rate of its own ([`Behaviour::Smooth`]), which the ladder's bounds
/// (`capstan::problem::estimate`, "The ladder's rate").
pub fn graded_behaviour(name: &str) -> Behaviour {
    match behaviour(name) {
        Behaviour::Located => Behaviour::Transition,
        other => other,
    }
}

/// [`scaled`] on the transition-graded ladder ([`crate::problem::Problem::transition_step`]):
/// every quantity converges at a rate, the located ones too ([`graded_behaviour`]). With an
/// element line at each transition, relocated on every step, the slip measure and the
/// stick-zone ends lose the grid-dependent jitter that makes the hp ladder read their rates
/// as noise, and fall geometrically: on the default scene at the observed rate `0.47 ... 0.52`
/// per order (differences `3.2e-5, 1.6e-5, 7.5e-6, 3.4e-6, 1.6e-6, 8.4e-7` of `pi` over
/// `p = 4 ... 10`), where the last change alone is `|r| / |1 - r| ~ 1` times the error, and
/// less (an underestimate) when the rate is slower (`0.6` on `12 x 2` cells). Their last rates
/// are the ladder's rate, which the other quantities' estimates use where their own rates are
/// faster than it allows.
pub fn scaled_graded(
    quantities: &ContactQuantities,
    solution: &ContactSolution,
) -> BTreeMap<String, Scaled> {
    let mut q = scaled(quantities, solution);
    for (name, s) in &mut q {
        s.behaviour = graded_behaviour(name);
    }
    q
}

/// Solves a scene's contact problem to its accuracy target: the solution of the chosen step,
/// its estimate and the report of the choice.
///
/// # Errors
/// The solves' errors; [`CliError::AccuracyNotReached`] when the budget runs out.
pub fn contact_to(
    scene: &Scene,
    target: &AccuracyTarget,
    observer: &mut dyn capstan_elasticity::solvers::Observer<f64>,
) -> Result<
    (
        crate::problem::Solved,
        Problem,
        ErrorEstimate,
        AccuracyReport,
    ),
    CliError,
> {
    let problem = scene.build()?;
    let probes = probes(scene);
    // the contact quantities of a plane body need the mesh graded toward the stick/slip
    // transitions: a cheap first pass locates them once, every step is graded toward them
    let choice = match problem.body.dimension {
        Dimension::Plane => {
            let t = Instant::now();
            let first = problem.transition_first_pass().solve_observed(observer)?;
            let (first_pass_order, first_pass_cells) = crate::problem::TRANSITION_FIRST_PASS;
            let (layers, ratio) = crate::problem::DEFAULT_TRANSITION_GRADING;
            Some(TransitionChoice {
                first_pass_order,
                first_pass_cells,
                first_pass_unknowns: first.model.operator().dof_count(),
                first_pass_seconds: t.elapsed().as_secs_f64(),
                transitions: first.transitions(),
                layers,
                ratio,
            })
        }
        Dimension::Solid { .. } => None,
    };
    // the actual unknowns of every step and of every twin (`Problem::unknowns` bounds a
    // graded corner mesh's); the ladder's steps have no rows toward the face, its twins have
    let (mut unknowns, mut twin_unknowns) = (Vec::new(), Vec::new());
    // the transitions the next step is graded toward: the first pass's, then each step's own
    // (located ever more sharply: the first pass is 0.016 off on the default scene, step 2
    // within 1e-4)
    let points = RefCell::new(
        choice
            .as_ref()
            .map_or_else(Vec::new, |c| c.transitions.clone()),
    );
    let graded = choice.is_some();
    let eval = |p: &Problem| {
        let solved = p.solve_observed(observer)?;
        let n = solved.model.operator().dof_count();
        if p.body.settings.transitions.face_layers > 0 {
            // a twin: the next step (after a twin that missed) stays graded toward the
            // transitions its step located, as on the cached ladder
            twin_unknowns.push(n);
        } else {
            unknowns.push(n);
            let located = solved.transitions();
            if !located.is_empty() {
                *points.borrow_mut() = located;
            }
        }
        let q = solved.quantities(&probes)?;
        let scaled = match graded {
            true => scaled_graded(&q, &solved.solution),
            false => scaled(&q, &solved.solution),
        };
        Ok((solved, scaled))
    };
    let mut refined = match &choice {
        Some(_) => problem.refine_along_twinned(
            target,
            |k| problem.transition_step(k, &points.borrow()),
            |stop| stop.transition_twin().map(Some),
            eval,
        )?,
        None => problem.refine_to(target, eval)?,
    };
    for (step, n) in refined.steps.iter_mut().zip(unknowns) {
        step.unknowns = n;
    }
    for (twin, n) in refined.twins.iter_mut().zip(twin_unknowns) {
        twin.unknowns = n;
    }
    let estimate = AccuracyReport::estimate(&refined);
    let mut report = AccuracyReport::new(scene, target, &refined).ok_or(CliError::Scene {
        origin: "accuracy.tol".into(),
        message: "no refinement step ran".into(),
    })?;
    report.transition_grading = choice;
    Ok((refined.value, refined.problem, estimate, report))
}
