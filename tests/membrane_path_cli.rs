//! `capstan membrane-path`: the belt-creep scene through the binary against the closed form,
//! its files, and its exit codes (bad input 2, no equilibrium 3).

mod common;

use std::path::Path;

fn belt_creep() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/scenes/belt_creep.toml")
        .display()
        .to_string()
}

/// `R (T1 - T0 - T0 ln(T1/T0)) / (k mu)` with the scene's `R = 2`, `mu = 0.3`,
/// `k = E h / (1 - nu^2) = 1e3 / (1 - 1/16)`.
fn loading_displacement(t1: f64) -> f64 {
    let k = 1e3 / (1.0 - 0.0625);
    2.0 * (t1 - 1.0 - (t1).ln()) / (k * 0.3)
}

#[test]
fn belt_creep_scene_matches_the_closed_form_and_closes_its_loop() {
    let scene = belt_creep();
    let json = common::capstan_json(&["membrane-path", &scene, "--quiet"]);
    let steps = json["steps"].as_array().unwrap();
    assert_eq!(steps.len(), 34);
    let w = |k: usize| steps[k]["end_displacement"].as_f64().unwrap();
    // loaded to 2 after ten steps: the closed form to the grid error (801 nodes)
    let exact = loading_displacement(2.0);
    assert!((w(9) / exact - 1.0).abs() < 1e-5, "{} vs {exact}", w(9));
    // unloading 2 -> 1.2: -R (sqrt 2 - sqrt 1.2)^2 / (k mu)
    let k = 1e3 / (1.0 - 0.0625);
    let unload = -2.0 * (2f64.sqrt() - 1.2f64.sqrt()).powi(2) / (k * 0.3);
    assert!(((w(17) - w(9)) / unload - 1.0).abs() < 1e-4);
    // the loop closes: the state at 2 after reloading is the state at 2 after loading
    assert!((w(25) - w(9)).abs() < 1e-12 * w(9));
    assert!((w(33) - w(17)).abs() < 1e-12 * w(9));
    let d = json["dissipation"].as_f64().unwrap();
    assert!(d > 0.0);
    assert_eq!(json["law"], "exact-coulomb");
    assert_eq!(json["scene"]["loads"]["path"].as_array().unwrap().len(), 34);
}

#[test]
fn out_writes_the_path_the_profiles_and_the_loop() {
    let dir = common::scratch_dir("membrane-path");
    let scene = belt_creep();
    common::capstan(&[
        "membrane-path",
        &scene,
        "--set",
        "loads.path=[1.5, 1.2]",
        "--set",
        "membrane.nodes=101",
        "--quiet",
        "--out",
        dir.to_str().unwrap(),
    ]);
    for f in [
        "membrane-path.json",
        "scene.toml",
        "path.csv",
        "profiles.csv",
        "hysteresis.svg",
    ] {
        assert!(dir.join(f).exists(), "{f}");
    }
    let path = std::fs::read_to_string(dir.join("path.csv")).unwrap();
    assert_eq!(path.lines().count(), 3); // header and two steps
    let profiles = std::fs::read_to_string(dir.join("profiles.csv")).unwrap();
    assert_eq!(profiles.lines().count(), 1 + 2 * 101);
    assert!(profiles.lines().next().unwrap().contains("slip_increment"));
}

#[test]
fn bad_input_and_no_equilibrium_have_their_exit_codes() {
    let scene = belt_creep();
    // the default (regularised) law is smooth: exit 2 naming friction.law
    let (code, _, err) =
        common::capstan_status(&["membrane-path", &scene, "--set", "friction.law=coulomb"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("friction.law"), "{err}");
    // no path: exit 2 naming loads.path
    let (code, _, err) = common::capstan_status(&[
        "membrane-path",
        "--set",
        "friction.law=exact-coulomb",
        "--set",
        "obstacle.shape=cylinder",
    ]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("loads.path"), "{err}");
    for bad in ["loads.path=[]", "loads.path=[1.5, -1.0]"] {
        let (code, _, err) = common::capstan_status(&["membrane-path", &scene, "--set", bad]);
        assert_eq!(code, Some(2), "{bad}: {err}");
        assert!(err.contains("loads.path"), "{err}");
    }
    // beyond the capstan ratio exp(0.3 pi) = 2.566 the belt slides as a whole: exit 3
    let (code, _, err) =
        common::capstan_status(&["membrane-path", &scene, "--set", "loads.path=[2.7]"]);
    assert_eq!(code, Some(3), "{err}");
    assert!(err.contains("slides as a whole"), "{err}");
    // the thick body takes the nonsmooth law too (tests/exact_friction_scene.rs): on the
    // condensed face when bilateral, by the full-system semismooth Newton when unilateral,
    // where the condensed solver (which holds v^3 = 0) refuses it: exit 2, not a panic
    let (code, _, err) = common::capstan_status(&[
        "contact",
        "--set",
        "friction.law=exact-coulomb",
        "--set",
        "contact.kind=unilateral",
        "--set",
        "solver.nonlinear=newton",
        "--set",
        "grid.n2=20",
        "--set",
        "grid.n3=5",
    ]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("solver.nonlinear"), "{err}");
}
