//! `capstan contact-path`: the thick body along a load path through the binary: its first step
//! against `capstan contact`, its files, the condensed fast path, and its exit codes.

mod common;

use std::path::Path;

fn path_scene() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/scenes/contact_path.toml")
        .display()
        .to_string()
}

const SMALL: [&str; 4] = ["--set", "grid.n2=41", "--set", "grid.n3=5"];

/// The first step is `capstan contact` at `tau_max = loads.path[0]` (the static solve from
/// rest), to 1e-12; the hysteresis loop closes on reloading.
#[test]
fn first_step_is_the_static_contact_and_the_loop_closes() {
    let scene = path_scene();
    let mut args = vec!["contact-path", &scene, "--quiet"];
    args.extend(SMALL);
    args.extend(["--set", "loads.path=[1.0, 2.0, 1.5, 2.0]"]);
    let json = common::capstan_json(&args);
    let steps = json["steps"].as_array().unwrap();
    assert_eq!(steps.len(), 4);
    let mut args = vec!["contact", &scene, "--quiet", "--set", "loads.tau_max=1.0"];
    args.extend(SMALL);
    let statics = common::capstan_json(&args);
    let a = steps[0]["max_azimuthal_displacement"]["value"]
        .as_f64()
        .unwrap();
    let b = statics["max_azimuthal_displacement"]["value"]
        .as_f64()
        .unwrap();
    assert!((a - b).abs() <= 1e-12 * b.abs(), "{a} vs {b}");
    let w = |k: usize| steps[k]["end_displacement"].as_f64().unwrap();
    assert!(w(2) < w(1));
    assert!((w(3) - w(1)).abs() < 1e-9 * w(1), "{} vs {}", w(3), w(1));
    assert!(json["dissipation"].as_f64().unwrap() > 0.0);
    assert_eq!(json["solver_choice"]["nonlinear"], "full-newton");
    assert_eq!(json["law"], "exact-coulomb");
}

/// A regularised law runs the whole path on the condensed solver (one condensation).
#[test]
fn regularised_path_runs_on_the_condensed_solver() {
    let scene = path_scene();
    let mut args = vec![
        "contact-path",
        &scene,
        "--quiet",
        "--set",
        "friction.law=coulomb",
        "--set",
        "loads.path=[1.0, 2.0, 1.5]",
    ];
    args.extend(SMALL);
    let json = common::capstan_json(&args);
    assert_eq!(json["steps"].as_array().unwrap().len(), 3);
    assert_eq!(json["solver_choice"]["nonlinear"], "newton");
}

#[test]
fn out_writes_the_path_the_profiles_the_steps_and_the_loop() {
    let dir = common::scratch_dir("contact-path");
    let scene = path_scene();
    let mut args = vec![
        "contact-path",
        &scene,
        "--set",
        "loads.path=[1.0, 2.0, 1.5]",
        "--quiet",
        "--out",
        dir.to_str().unwrap(),
    ];
    args.extend(SMALL);
    common::capstan(&args);
    for f in [
        "contact-path.json",
        "scene.toml",
        "path.csv",
        "profiles.csv",
        "step_0001.vtu",
        "step_0003.vtu",
        "path.pvd",
        "hysteresis.svg",
    ] {
        assert!(dir.join(f).exists(), "{f}");
    }
    let path = std::fs::read_to_string(dir.join("path.csv")).unwrap();
    assert_eq!(path.lines().count(), 4); // header and three steps
    let profiles = std::fs::read_to_string(dir.join("profiles.csv")).unwrap();
    assert!(
        profiles
            .lines()
            .next()
            .unwrap()
            .contains("friction_traction")
    );
    let pvd = std::fs::read_to_string(dir.join("path.pvd")).unwrap();
    assert_eq!(pvd.matches("step_").count(), 3);
}

#[test]
fn bad_input_has_its_exit_code() {
    // no path: exit 2 naming loads.path
    let (code, _, err) = common::capstan_status(&["contact-path", "--set", "grid.n2=41"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("loads.path"), "{err}");
    for bad in ["loads.path=[]", "loads.path=[1.5, -1.0]"] {
        let (code, _, err) = common::capstan_status(&["contact-path", "--set", bad]);
        assert_eq!(code, Some(2), "{bad}: {err}");
        assert!(err.contains("loads.path"), "{err}");
    }
    // beyond the limiting ratio (about 3.3 on the paper's body) a step has no equilibrium
    let (code, _, err) = common::capstan_status(&[
        "contact-path",
        "--set",
        "grid.n2=41",
        "--set",
        "grid.n3=9",
        "--set",
        "loads.path=[2.0, 6.0]",
    ]);
    assert_eq!(code, Some(3), "{err}");
    assert!(err.contains("step 2"), "{err}");
}
