//! Accuracy targets on the default scene (`accuracy.tol`): the threshold ratio the target
//! returns is within the tolerance of a much finer run, and its estimate brackets the true
//! error (docs/verification.md, "Accuracy targets").

use capstan::commands::threshold;
use capstan::scene::Scene;

fn threshold_at(tol: Option<f64>, step: Option<usize>) -> threshold::ThresholdReport {
    let mut scene = Scene::default();
    scene.accuracy.tol = tol;
    scene.output.error_estimate = false;
    if let Some(k) = step {
        // the ladder's step k as a plain scene
        let p = scene.build().unwrap().accuracy_step(k).unwrap();
        scene.discretisation.method = p.body.method;
        scene.discretisation.order = p.body.settings.order;
        scene.discretisation.grading = Some(p.body.settings.grading.ratio());
        scene.discretisation.layers = Some(p.body.settings.order);
        scene.grid.n2 = p.body.n2;
        scene.grid.n3 = p.body.n3;
    }
    threshold::report(&scene).unwrap()
}

#[test]
fn threshold_to_1e_3_is_within_tolerance_of_the_hp_ladder_at_order_6() {
    let target = threshold_at(Some(1e-3), None);
    // the reference: order 6 with 6 layers (169 x 85), whose own estimate is 6.4e-6 relative
    let reference = threshold_at(None, Some(4)).threshold_ratio;
    let truth = (target.threshold_ratio - reference).abs();
    let estimate = target.estimated_error.as_ref().unwrap().quantities["threshold_ratio"].unwrap();
    assert!(truth <= 1e-3 * reference, "true error {truth:.2e}");
    assert!(
        estimate <= 1e-3 * target.threshold_ratio,
        "estimate {estimate:.2e}"
    );
    let ratio = estimate / truth;
    // measured: estimate 1.20e-4 (Richardson with the observed rate 0.121), true error
    // 1.04e-4 (ratio 1.15; the old rule max(d_k, d_{k-1} / 4) gave 9.0e-4, ratio 8.7)
    assert!(
        (0.5..=10.0).contains(&ratio),
        "estimate / true error = {ratio:.2}"
    );
    // bracketed from the rigid-sliding limit: r = 1, above it, just below it
    assert_eq!(target.solves, 3);
    let accuracy = target.accuracy.unwrap();
    assert_eq!(accuracy.chosen.method, "fem-qp");
    assert_eq!(accuracy.chosen.order, Some(4));
    assert_eq!(accuracy.steps.len(), 3);
}

#[test]
fn a_sweep_with_a_target_solves_every_point_to_it() {
    let sets = ["accuracy.tol=1e-2".to_owned()];
    let r = capstan::commands::sweep::report(None, &sets, "body.poisson", &[0.1, 0.3]).unwrap();
    for p in &r.points {
        assert!(p.converged, "{:?}", p.error);
        let a = p.accuracy.as_ref().unwrap();
        let slip = a.estimated_error["slip_measure"].unwrap();
        assert!(
            slip <= 1e-2 * a.contact_measure,
            "slip measure estimate {slip:.2e}"
        );
        assert_eq!(a.grid.len(), 2);
        assert!(a.slip_measure > 0.0 && a.slip_measure < a.contact_measure);
    }
    // the text table says what the target chose for every point
    let table = capstan::commands::sweep::table(&r);
    assert_eq!(table.matches("chosen grid").count(), 2, "{table}");
}

#[test]
fn contact_to_1e_2_is_within_tolerance_of_the_hp_ladder_at_order_6() {
    use capstan::commands::accuracy::{contact_to, probes, scaled};
    use capstan::problem::estimate::Rule;
    use capstan_elasticity::solvers::SilentObserver;
    let mut scene = Scene::default();
    scene.accuracy.tol = Some(1e-2);
    let target = scene.accuracy.target().unwrap().unwrap();
    let (solved, _, estimate, report) = contact_to(&scene, &target, &mut SilentObserver).unwrap();
    let probes = probes(&scene);
    let q = scaled(&solved.quantities(&probes).unwrap(), &solved.solution);
    // the reference: the ladder's order-6 step (169 x 85)
    let fine = scene
        .build()
        .unwrap()
        .accuracy_step(4)
        .unwrap()
        .solve()
        .unwrap();
    let reference = scaled(&fine.quantities(&probes).unwrap(), &fine.solution);
    assert_eq!(report.chosen.order, Some(4));
    assert_eq!(report.steps.len(), 3);
    assert_eq!(q.len(), 9, "{q:?}");
    // the estimates are the stop's twin's: the same order with 3 rows toward the face
    assert_eq!(estimate.method, "stop-twin");
    assert_eq!(report.twins.len(), 1);
    assert_eq!(report.twins[0].order, Some(4));
    assert!(report.twins[0].unknowns > report.chosen.unknowns);
    let rules = estimate.rules.as_ref().unwrap();
    assert!(rules.values().all(|r| *r == Rule::Twin), "{rules:?}");
    for (name, v) in &q {
        let truth = (v.value - reference[name].value).abs() / v.scale;
        let e = estimate.quantities[name].unwrap() / v.scale;
        // measured (docs/verification.md, "The contact tolerance table"): true errors
        // 6.6e-7 ... 2.5e-3 against step 7, estimates 7.4e-6 ... 3.6e-3
        assert!(truth < 1e-2, "{name}: true error {truth:.2e}");
        assert!(e <= 1e-2 && e > 0.0, "{name}: estimate {e:.2e}");
    }
}
