//! Exact (nonsmooth) Coulomb friction on the thick body, named by a scene:
//! `friction.law = "exact-coulomb"` solves by the full-system semismooth Newton (what `auto`
//! picks), agrees with regularised Coulomb as `eps -> 0`, and the condensed solver refuses it
//! naming `solver.nonlinear`.

mod common;

use capstan::Scene;

/// The paper's body on FD 81 x 17 at ratio 2 with `law`, `friction.eps = eps` and the extra
/// `sets`.
fn scene(law: &str, eps: f64, sets: &[(&str, &str)]) -> Scene {
    let mut scene = Scene::default();
    let base = [
        ("grid.n2", "81".to_owned()),
        ("grid.n3", "17".to_owned()),
        ("friction.law", format!("\"{law}\"")),
        ("friction.eps", eps.to_string()),
    ];
    for (key, value) in base
        .iter()
        .map(|(k, v)| (*k, v.as_str()))
        .chain(sets.iter().copied())
    {
        scene = scene.with_raw(key, value, "test").unwrap();
    }
    scene
}

/// max `|v2|` of the contact face of the scene's solve, and the solver that ran.
fn max_v2(scene: &Scene) -> (f64, String, String) {
    let solved = scene.build().unwrap().solve().unwrap();
    let choice = solved.choice;
    (
        solved.solution.max_azimuthal_displacement.value.abs(),
        choice.nonlinear.to_owned(),
        choice.reason,
    )
}

#[test]
fn exact_coulomb_from_a_scene_is_the_eps_to_zero_limit_of_regularised_coulomb() {
    let (exact, nonlinear, reason) = max_v2(&scene("exact-coulomb", 1e-5, &[]));
    assert_eq!(nonlinear, "full-newton");
    assert!(reason.contains("exact friction"), "{reason}");
    // regularised Coulomb approaches it at first order in eps (h27: 1.98e-6 at 1e-5)
    let errors: Vec<f64> = [1e-5, 1e-6]
        .iter()
        .map(|&eps| (max_v2(&scene("coulomb", eps, &[])).0 - exact).abs())
        .collect();
    let order = (errors[0] / errors[1]).log10();
    assert!(errors[1] < 1e-6 * exact.max(1.0), "{errors:?}");
    assert!(
        (order - 1.0).abs() < 0.1,
        "order {order}, errors {errors:?}"
    );
}

#[test]
fn the_condensed_solver_refuses_exact_friction_naming_the_key() {
    let (code, _, err) = common::capstan_status(&[
        "contact",
        "--set",
        "friction.law=\"exact-coulomb\"",
        "--set",
        "solver.nonlinear=\"newton\"",
    ]);
    assert_eq!(code, Some(2), "{err}");
    assert!(
        err.contains("solver.nonlinear") && err.contains("full-newton"),
        "{err}"
    );
}

#[test]
fn exact_coulomb_starts_from_its_regularisation_without_load_continuation() {
    // the semismooth Newton starts from the condensed solver's regularised solution
    // (src/problem/exact_start.rs): before, its own regularised start stagnated at full load
    // from the stuck state and the load continuation ran (29 iterations on the default scene)
    let exact = scene("exact-coulomb", 1e-5, &[])
        .build()
        .unwrap()
        .solve()
        .unwrap();
    let regularised = scene("coulomb", 1e-5, &[])
        .build()
        .unwrap()
        .solve()
        .unwrap();
    let (e, r) = (&exact.solution.stats, &regularised.solution.stats);
    assert_eq!(e.continuation_steps, 1, "{e:?}");
    // the regularised solve's iterations (counted in) and a few semismooth ones
    assert!(
        e.newton_iterations > r.newton_iterations && e.newton_iterations <= r.newton_iterations + 6,
        "exact {e:?}, regularised {r:?}"
    );
}
