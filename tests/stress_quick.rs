//! The fast part of the stress suite (`capstan stress`): a few points at the extremes, small
//! grids, dev profile.

use capstan::commands::stress::{
    REFUSED_GRID, capstan_point, contact_case, grid_refusal, run_contact_case,
};
use capstan::output::check_finite_json;
use serde_json::json;

#[test]
fn answer_is_invariant_in_young_after_scaling() {
    // eps scales as 1/E with the displacement, so E v and the stick/slip pattern are invariant.
    let run = |young: f64| {
        let case = contact_case(
            "young",
            [30, 7],
            &[
                ("body.young", json!(young)),
                ("friction.eps", json!(1e-5 * 1e3 / young)),
            ],
            false,
        )
        .unwrap();
        let p = run_contact_case(case);
        assert!(p.converged, "{p:?}");
        p
    };
    let (low, high) = (run(1e-3), run(1e12));
    let scaled = |p: &capstan::commands::stress::StressPoint, e: f64| p.quantities["max_v2"] * e;
    approx::assert_relative_eq!(scaled(&low, 1e-3), scaled(&high, 1e12), max_relative = 1e-8); // rounding only
    assert_eq!(
        low.quantities["slip_fraction"],
        high.quantities["slip_fraction"]
    );
    assert!(low.condition_estimate.unwrap() > 1.0);
}

#[test]
fn refinement_change_compares_magnitudes_under_symmetric_loads() {
    // Equal end tractions: the largest |v^2| is attained at both ends with opposite signs, and
    // which one wins flips with rounding (60 x 11: -1.3476e-3 at theta0; 119 x 21: +1.3435e-3 at
    // theta1); the change must not read 2.
    let p = run_contact_case(
        contact_case("ratio", [60, 11], &[("loads.tau_max", json!(1.0))], true).unwrap(),
    );
    assert!(p.converged, "{p:?}");
    assert!(p.refinement_change.unwrap() < 0.1, "{p:?}");
}

#[test]
fn beyond_limiting_equilibrium_and_without_friction_are_typed_failures() {
    for sets in [
        vec![("loads.tau_max", json!(5.0))],
        vec![("friction.mu", json!(0.0))],
    ] {
        let p = run_contact_case(contact_case("ratio", [30, 7], &sets, false).unwrap());
        assert!(!p.converged);
        let f = p.failure.as_deref().unwrap();
        assert!(f.starts_with("no-equilibrium:"), "{f}");
        check_finite_json(&p).unwrap();
    }
}

#[test]
fn poisson_points_report_refinement_change_or_a_typed_failure() {
    let p = run_contact_case(
        contact_case("poisson", [21, 5], &[("body.poisson", json!(0.45))], true).unwrap(),
    );
    assert!(p.converged, "{p:?}");
    assert!(p.refinement_change.unwrap().is_finite());
    assert!(p.final_residual.unwrap() < 1e-8);
    check_finite_json(&p).unwrap();
    // FD near incompressibility: measured to fail Newton (locking); typed, never NaN.
    let p = run_contact_case(
        contact_case("poisson", [21, 5], &[("body.poisson", json!(0.4999))], true).unwrap(),
    );
    assert!(
        p.converged || p.failure.as_deref().unwrap().starts_with("not-converged:"),
        "{p:?}"
    );
    check_finite_json(&p).unwrap();
}

#[test]
fn huge_grid_is_refused_with_its_estimate() {
    if capstan::scene::available_memory().is_none_or(|m| m > 300e9) {
        return; // the machine might hold it: nothing quick to check
    }
    let p = grid_refusal(REFUSED_GRID);
    assert!(!p.converged);
    assert!(
        p.failure.as_deref().unwrap().starts_with("refused:"),
        "{p:?}"
    );
    assert!(p.quantities["memory_estimate_bytes"] > p.quantities["memory_available_bytes"]);
}

#[test]
fn capstan_extremes_are_exact_or_typed() {
    // mu = 5 over 20 wraps: T = exp(200 pi) ~ 1e273, still finite; the quadrature path agrees.
    let angle = 40.0 * std::f64::consts::PI;
    for shape in [
        vec![("obstacle.shape", json!("cylinder"))],
        vec![
            ("obstacle.shape", json!("prism")),
            ("obstacle.u", json!("2*sin(t)")),
            ("obstacle.v", json!("2*cos(t)")),
        ],
    ] {
        let mut sets = shape;
        sets.extend([
            ("friction.mu", json!(5.0)),
            ("membrane.theta0", json!(0.0)),
            ("membrane.theta_max", json!(angle)),
        ]);
        let p = capstan_point("capstan-wraps", &sets, Some((5.0 * angle).exp()));
        assert!(p.converged, "{p:?}");
        assert!(p.refinement_change.unwrap() < 1e-9, "{p:?}");
    }
    // 50 wraps overflow: a typed failure, no NaN or inf in the point.
    let p = capstan_point(
        "capstan-wraps",
        &[
            ("obstacle.shape", json!("cylinder")),
            ("friction.mu", json!(5.0)),
            ("membrane.theta0", json!(0.0)),
            ("membrane.theta_max", json!(100.0 * std::f64::consts::PI)),
        ],
        None,
    );
    assert!(!p.converged);
    assert!(
        p.failure.as_deref().unwrap().starts_with("not-converged:"),
        "{p:?}"
    );
    check_finite_json(&p).unwrap();
}
