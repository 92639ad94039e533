//! The transition-graded accuracy ladder (issue 28, `Problem::transition_step`): a cheap version
//! on `12 x 2` cells reaches a tolerance on the slip measure and the stick-zone ends with its
//! estimate bracketing the true error, where the same step without the grading toward the
//! stick/slip transitions is off by more than twice the tolerance.
//!
//! The ladder is climbed as `capstan::commands::accuracy::contact_to` climbs it: a first pass
//! locates the transitions, every step is graded toward the transitions the step before
//! located, and the estimate and stopping rule are `Problem::refine_along`'s.

use std::cell::RefCell;
use std::collections::BTreeMap;

use capstan::commands::accuracy::{probes, scaled_graded};
use capstan::problem::{AccuracyTarget, Problem, ProblemError, Refined, Scaled};
use capstan::scene::Scene;

/// The located quantities (the ones the grading is for).
const LOCATED: [&str; 3] = ["slip_measure", "stick_from", "stick_to"];

/// The cheap ladder's cells (the first pass's).
const CELLS: [usize; 2] = [12, 2];

/// Climbs the cheap ladder to `tol` on the located quantities, each step graded toward the
/// transitions the step before located.
fn climb(tol: f64) -> Result<Refined<f64, capstan::geometry::Obstacle>, ProblemError> {
    let scene = Scene::default();
    let base: Problem = scene.build().unwrap();
    let probes = probes(&scene);
    let first = base.transition_first_pass().solve().unwrap();
    let points = RefCell::new(first.transitions());
    let target = AccuracyTarget::new(tol).unwrap();
    base.refine_along(
        &target,
        |k| base.transition_step_on(k, &points.borrow(), CELLS),
        |p| {
            let solved = p.solve()?;
            *points.borrow_mut() = solved.transitions();
            let q = solved.quantities(&probes)?;
            let all = scaled_graded(&q, &solved.solution);
            let located: BTreeMap<String, Scaled> =
                LOCATED.iter().map(|n| ((*n).to_owned(), all[*n])).collect();
            Ok((q.slip_measure, located))
        },
    )
}

/// The default scene's slip measure: the transition-graded reference (p 10 on `48 x 16` cells,
/// docs/verification.md "The contact tolerance table (transition-graded)"), good to well under
/// `1e-6` of `pi`.
const SLIP_LIMIT: f64 = 3.112_301;

#[test]
fn the_graded_ladder_reaches_a_tolerance_the_ungraded_one_does_not() {
    let tol = 1e-3;
    let pi = core::f64::consts::PI;
    let graded = climb(tol).unwrap();
    let k = graded.steps.len() - 1;
    // measured: p 2 ... 6, slip measure 3.117886, 3.115742, 3.114312, 3.113495, 3.113017
    // (rate 0.6 per order); at p 6 estimate 4.3e-4 of pi, true error 2.3e-4 (1.9x)
    assert_eq!(k, 4, "{:?}", graded.steps);
    let last = graded.steps.last().unwrap();
    assert_eq!(last.method, "fem-qp-corner");
    // graded toward two transitions, located by the step before
    assert_eq!(last.transitions.as_ref().map(Vec::len), Some(2), "{last:?}");
    let truth = (graded.value - SLIP_LIMIT).abs() / pi;
    let estimate = graded.estimates["slip_measure"] / pi;
    assert!(truth < tol, "true error {truth:.1e}");
    assert!(estimate <= tol, "estimate {estimate:.1e}");
    assert!(
        (0.5..=10.0).contains(&(estimate / truth)),
        "estimate {estimate:.1e}, true error {truth:.1e}"
    );
    // the same step without the layers at the transitions: the stick zone (~0.03 long) in
    // one 0.26-wide cell, the slip measure 2e-3 off
    let scene = Scene::default();
    let plain = scene
        .build()
        .unwrap()
        .transition_step_on(k, &[], CELLS)
        .unwrap()
        .solve()
        .unwrap();
    let slip = plain.quantities(&probes(&scene)).unwrap().slip_measure;
    let plain_truth = (slip - SLIP_LIMIT).abs() / pi;
    assert!(
        plain_truth > 2.0 * tol,
        "ungraded true error {plain_truth:.1e}"
    );
}
