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
