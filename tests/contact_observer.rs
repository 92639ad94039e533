//! The contact solvers report every iterate to an observer, which can stop them.

use capstan_elasticity::contact::{
    BoundarySolver, ContactError, ContactErrorKind, ContactModel, ContactSettings, ContactSolution,
    EndLoads, FullSystemSettings, FullSystemSolver, ThickBody, ThickBodyOperator,
};
use capstan_elasticity::friction::{RegularisedCoulomb, RegularisedCoulombParams};
use capstan_elasticity::solvers::{Observer, Progress, SolveStage};

type Model = ContactModel<ThickBodyOperator, RegularisedCoulomb>;

fn model(eps: f64) -> Model {
    ThickBody::paper(41, 9)
        .unwrap()
        .model(
            RegularisedCoulomb,
            RegularisedCoulombParams::new(0.5, eps).unwrap(),
            eps,
        )
        .unwrap()
}

/// Records every event; stops the solve after `stop_after` events if set.
#[derive(Default)]
struct Recorder {
    events: Vec<Progress<f64>>,
    stop_after: Option<usize>,
}

impl Observer<f64> for Recorder {
    fn iteration(&mut self, p: &Progress<f64>) {
        self.events.push(*p);
    }
    fn interrupted(&mut self) -> bool {
        self.stop_after.is_some_and(|n| self.events.len() >= n)
    }
}

/// The condensed solve at the ratio 2 with `settings`, and the events it reported at `stage`.
fn observed_stage(
    model: &Model,
    settings: ContactSettings,
    stage: SolveStage,
) -> (ContactSolution, Vec<Progress<f64>>) {
    let solver = BoundarySolver::new(model, settings).unwrap();
    let mut rec = Recorder::default();
    let sol = solver
        .solve_observed(EndLoads::ratio(2.0), &mut rec)
        .unwrap();
    let events = rec
        .events
        .into_iter()
        .filter(|p| p.stage == stage)
        .collect();
    (sol, events)
}

#[test]
fn condensed_newton_reports_falling_residuals_and_the_active_set() {
    let model = model(1e-5);
    let (sol, newton) = observed_stage(
        &model,
        ContactSettings::default(),
        SolveStage::CondensedNewton,
    );
    // one event per iterate: the initial residual, then one per Newton step
    assert_eq!(newton.len(), sol.stats.newton_iterations + 1);
    assert_eq!(newton[0].iteration, 0);
    assert_eq!(newton[0].step_length, 0.0);
    let (first, last) = (
        newton[0].residual_norm,
        newton.last().unwrap().residual_norm,
    );
    assert!(
        last <= 1e-10 && last < 1e-6 * first,
        "{first:e} -> {last:e}"
    );
    let m = model.active().len();
    for p in &newton {
        let active = p.active.expect("the condensed solver knows its active set");
        assert_eq!(active.stick + active.slip, m);
    }
    // the final active set is the solution's: stick where |u| < eps
    let final_set = newton.last().unwrap().active.unwrap();
    let stuck = sol
        .contact
        .state
        .iter()
        .zip(model.contact_nodes())
        .filter(|(s, n)| **s == 0 && n.tangential_row.is_some())
        .count();
    assert_eq!(final_set.stick, stuck);
    assert!(final_set.slip > 0 && final_set.stick > 0);
}

#[test]
fn a_short_newton_budget_reports_continuation_steps() {
    // seven Newton iterations per attempt: plain Newton fails and a continuation takes over
    let model = model(1e-5);
    let settings = ContactSettings {
        max_iterations: 7,
        ..Default::default()
    };
    let (sol, steps) = observed_stage(&model, settings, SolveStage::Continuation);
    assert_eq!(steps.len(), sol.stats.continuation_steps);
    assert!(steps.len() > 1);
    assert!(steps.iter().skip(1).all(|p| p.step_length > 0.0));
}

#[test]
fn an_observer_stops_the_condensed_and_the_full_system_solver() {
    let model = model(1e-5);
    let loads = EndLoads::ratio(2.0);
    let condensed = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let mut rec = Recorder {
        stop_after: Some(3),
        ..Default::default()
    };
    let err = condensed.solve_observed(loads, &mut rec).unwrap_err();
    assert!(
        matches!(err, ContactError::Interrupted { iterations: 2 }),
        "{err:?}"
    );
    assert_eq!(
        (err.kind(), err.status()),
        (ContactErrorKind::Interrupted, "interrupted")
    );
    assert_eq!(rec.events.len(), 3);

    let full = FullSystemSolver::new(&model, FullSystemSettings::default()).unwrap();
    let mut rec = Recorder {
        stop_after: Some(2),
        ..Default::default()
    };
    let err = full.solve_observed(loads, &mut rec).unwrap_err();
    assert_eq!(err.kind(), ContactErrorKind::Interrupted, "{err:?}");
    assert!(rec.events.iter().all(|p| p.stage == SolveStage::Newton));
    // uninterrupted, the full system's residuals fall to its tolerance
    let mut rec = Recorder::default();
    full.solve_observed(loads, &mut rec).unwrap();
    let r: Vec<f64> = rec.events.iter().map(|p| p.residual_norm).collect();
    assert!(r.len() > 2 && r.last().unwrap() < &(1e-8 * r[0]), "{r:?}");
}

/// The set-up events of `events`: `(phase, done, total)`.
fn set_up_events(events: &[Progress<f64>]) -> Vec<(&'static str, usize, usize)> {
    events
        .iter()
        .filter(|p| p.stage == SolveStage::SetUp)
        .map(|p| {
            let w = p.work.expect("a set-up event carries its work");
            assert_eq!(
                (p.iteration, p.residual_norm, p.step_length),
                (w.done, 0.0, 0.0)
            );
            (w.phase.name(), w.done, w.total)
        })
        .collect()
}

/// A small scene of `dimension` with the default (condensed) solver.
fn small_problem(dimension: usize) -> capstan::Problem {
    let n2 = if dimension == 2 { "41" } else { "21" };
    let mut scene = capstan::Scene::default();
    for (key, value) in [
        ("body.dimension", dimension.to_string()),
        ("grid.n1", "3".into()),
        ("grid.n2", n2.into()),
        ("grid.n3", "5".into()),
        ("body.width", "0.5".into()),
        ("loads.tau_max", "1.5".into()),
    ] {
        scene = scene.with_raw(key, &value, "test").unwrap();
    }
    scene.build().unwrap()
}

#[test]
fn the_set_up_reports_assembly_factorisation_and_condensation_before_newton() {
    for dimension in [2, 3] {
        let mut rec = Recorder::default();
        small_problem(dimension).solve_observed(&mut rec).unwrap();
        let set_up = set_up_events(&rec.events);
        // assembly, then the factorisation, then the condensation to its last column
        assert_eq!(
            &set_up[..4],
            &[
                ("assembly", 0, 1),
                ("assembly", 1, 1),
                ("factorisation", 0, 1),
                ("factorisation", 1, 1),
            ]
        );
        let condensation: Vec<_> = set_up.iter().filter(|e| e.0 == "condensation").collect();
        let &&(_, last, m) = condensation.last().expect("condensation events");
        assert!(m > 0 && last == m, "{dimension}-D: {condensation:?}");
        assert!(
            condensation
                .windows(2)
                .all(|w| w[0].1 <= w[1].1 || w[1].1 == w[1].2)
        );
        // every set-up event comes before the first Newton iterate
        let first_newton = rec
            .events
            .iter()
            .position(|p| p.stage == SolveStage::CondensedNewton)
            .expect("Newton iterates");
        let last_set_up = rec
            .events
            .iter()
            .rposition(|p| p.stage == SolveStage::SetUp)
            .unwrap();
        assert!(last_set_up < first_newton, "{dimension}-D");
    }
}

#[test]
fn an_observer_stops_the_set_up_after_the_factorisation() {
    for dimension in [2, 3] {
        // the fourth event is the end of the factorisation: the first poll
        let mut rec = Recorder {
            stop_after: Some(4),
            ..Recorder::default()
        };
        let err = small_problem(dimension)
            .solve_observed(&mut rec)
            .unwrap_err()
            .to_string();
        assert!(err.contains("interrupted"), "{dimension}-D: {err}");
        assert!(
            rec.events.iter().all(|p| p.stage == SolveStage::SetUp),
            "{dimension}-D: stopped before any Newton iterate"
        );
    }
}
