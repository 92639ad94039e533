//! Exact (nonsmooth) Coulomb friction on the thick body, named by a scene:
//! `friction.law = "exact-coulomb"` solves by semismooth Newton on the condensed contact face
//! (what `auto` picks on bilateral contact), gives the full-system semismooth Newton's answer,
//! agrees with regularised Coulomb as `eps -> 0`, and the condensed solver refuses unilateral
//! exact friction naming `solver.nonlinear`.

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
    assert_eq!(nonlinear, "newton");
    assert!(
        reason.contains("exact friction") && reason.contains("condensed contact face"),
        "{reason}"
    );
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
fn the_condensed_route_gives_the_full_system_answer() {
    // auto and `newton` run the condensed semismooth Newton, `full-newton` the full system
    let solve = |sets: &[(&str, &str)]| {
        scene("exact-coulomb", 1e-5, sets)
            .build()
            .unwrap()
            .solve()
            .unwrap()
    };
    let auto = solve(&[]);
    let named = solve(&[("solver.nonlinear", "\"newton\"")]);
    let full = solve(&[("solver.nonlinear", "\"full-newton\"")]);
    assert_eq!(auto.solution.stats.method, "condensed-semismooth");
    assert_eq!(named.solution.stats.method, "condensed-semismooth");
    assert_eq!(full.solution.stats.method, "full-newton");
    assert_eq!(auto.solution.displacement, named.solution.displacement);
    let scale = full
        .solution
        .displacement
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let diff = auto
        .solution
        .displacement
        .iter()
        .zip(&full.solution.displacement)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(diff < 1e-10 * scale, "{:e}", diff / scale);
    assert_eq!(auto.solution.contact.state, full.solution.contact.state);
    assert!(auto.limiting.is_some());
}

#[test]
fn the_condensed_solver_refuses_unilateral_exact_friction_naming_the_key() {
    let (code, _, err) = common::capstan_status(&[
        "contact",
        "--set",
        "friction.law=\"exact-coulomb\"",
        "--set",
        "contact.kind=\"unilateral\"",
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
    // from the stuck state and the load continuation ran (29 iterations on the default scene);
    // on the condensed face it takes 2 semismooth steps here
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
    // the regularised solve's iterations (counted in, stopped early) and a few semismooth ones
    assert!(
        e.newton_iterations >= r.newton_iterations
            && e.newton_iterations <= r.newton_iterations + 6,
        "exact {e:?}, regularised {r:?}"
    );
}

/// On the default scene (the paper's body, FD 250 x 41, ratio 2) exact Coulomb takes as many
/// condensed iterations as regularised Coulomb at `eps = 1e-5` (8 regularised to the loose
/// hand-over, 2 semismooth), none of them backtracked: the semismooth Newton starts at the
/// balanced rigid amplitude, where before its first step slid the body and was cut to
/// `alpha = 2^-9` (3 semismooth steps after 9 regularised ones). The answer is the full-system
/// semismooth Newton's to 1e-10, with the same stick/slip.
#[test]
fn exact_coulomb_on_the_default_scene_takes_full_semismooth_steps() {
    use capstan::solvers::{Progress, SolveStage};
    let exact = |sets: &[(&str, &str)]| {
        let mut scene = Scene::default()
            .with_raw("friction.law", "\"exact-coulomb\"", "test")
            .unwrap();
        for (key, value) in sets {
            scene = scene.with_raw(key, value, "test").unwrap();
        }
        scene.build().unwrap()
    };
    // (iteration, step length) of every condensed iterate
    let mut iterates: Vec<(usize, f64)> = Vec::new();
    let mut record = |p: &Progress<f64>| {
        if p.stage == SolveStage::CondensedNewton {
            iterates.push((p.iteration, p.step_length));
        }
    };
    let solved = exact(&[]).solve_observed(&mut record).unwrap();
    let regularised = Scene::default().build().unwrap().solve().unwrap();
    let full = exact(&[("solver.nonlinear", "\"full-newton\"")])
        .solve()
        .unwrap();
    // the semismooth iterates: from the second iteration 0 on
    let k = iterates.iter().rposition(|s| s.0 == 0).unwrap();
    let semismooth = &iterates[k..];
    assert!(k > 0, "{iterates:?}");
    assert_eq!(semismooth.len(), 3, "{iterates:?}");
    assert!(semismooth[1..].iter().all(|s| s.1 == 1.0), "{iterates:?}");
    let (e, r) = (&solved.solution.stats, &regularised.solution.stats);
    assert_eq!(e.method, "condensed-semismooth");
    assert_eq!(e.newton_iterations, r.newton_iterations, "{e:?} {r:?}");
    let scale = full
        .solution
        .displacement
        .iter()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let diff = solved
        .solution
        .displacement
        .iter()
        .zip(&full.solution.displacement)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(diff < 1e-10 * scale, "{:e}", diff / scale);
    assert_eq!(solved.solution.contact.state, full.solution.contact.state);
}
