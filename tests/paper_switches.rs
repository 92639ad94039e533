//! The paper's own choices, selectable beside ours (issue 32, `docs/errata.md` section 3
//! items 6 and 7): its grid condition, checked and warned about, and its undamped Jacobi
//! iteration (`solver.relaxation = 1`), with the errata's numbers.

mod common;

use std::f64::consts::PI;

use capstan::commands::contact::paper_grid_condition;
use capstan::scene::Scene;

fn scene(sets: &[&str]) -> Scene {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    Scene::load(None, &sets).unwrap()
}

#[test]
fn the_papers_own_grid_violates_its_grid_condition() {
    // 250 x 41 on the circle a = b = 2, h = 1: psi0 = sqrt(g_22) is 3 on the outer face, so
    // max psi0 dx2 = 3 pi/249 = 0.0379 > dx3 = 1/40 (docs/paper.md row 51)
    let (lhs, dx3) = paper_grid_condition(&Scene::default()).unwrap().unwrap();
    assert!((lhs - 3.0 * PI / 249.0).abs() < 1e-12 * lhs, "{lhs}");
    assert!((dx3 - 0.025).abs() < 1e-15);
    assert!(lhs > dx3);
    // 1001 nodes along x2 meet it: 3 pi/1000 = 0.0094 <= 0.025
    let (lhs, dx3) = paper_grid_condition(&scene(&["grid.n2=1001"]))
        .unwrap()
        .unwrap();
    assert!(lhs <= dx3, "{lhs} > {dx3}");
    // no condition for a 3-D body
    let solid = scene(&["body.dimension=3", "discretisation.method=\"fem-q1\""]);
    assert!(paper_grid_condition(&solid).unwrap().is_none());
}

const JACOBI_11X5: [&str; 6] = [
    "contact",
    "--set",
    "grid.n2=11",
    "--set",
    "grid.n3=5",
    "--set",
];

fn jacobi(extra: &[&str]) -> (Option<i32>, String, String) {
    let mut args = JACOBI_11X5.to_vec();
    args.push("solver.nonlinear=\"jacobi-newton\"");
    args.extend_from_slice(extra);
    common::capstan_status(&args)
}

/// The paper's undamped Jacobi: diverges at once (a fast run, whatever the build).
const UNDAMPED: [&str; 2] = ["--set", "solver.relaxation=1"];

#[test]
fn jacobi_newton_warns_of_the_grid_condition_unless_quiet() {
    // the warning comes before the solve
    let (code, _, err) = jacobi(&[&UNDAMPED[..], &["--json"]].concat());
    assert_eq!(code, Some(4), "{err}");
    assert!(
        err.contains("grid condition psi0 dx2 <= dx3 is violated")
            && err.contains("9.4248e-1")
            && err.contains("2.5000e-1"),
        "{err}"
    );
    let (code, _, err) = jacobi(&[&UNDAMPED[..], &["--json", "--quiet"]].concat());
    assert_eq!(code, Some(4));
    assert!(!err.contains("grid condition"), "{err}");
}

#[test]
fn undamped_jacobi_is_selectable_and_diverges() {
    // the paper's: relaxation 1 diverges in the first linear solve (exit 4, not converged)
    let (code, _, err) = jacobi(&[&UNDAMPED[..], &["--json", "--quiet"]].concat());
    assert_eq!(code, Some(4), "{err}");
    assert!(
        err.contains("did not converge") && err.contains("residual inf"),
        "{err}"
    );
    // outside (0, 2) is bad input naming the key
    let (code, _, err) = jacobi(&["--set", "solver.relaxation=2"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("solver.relaxation"), "{err}");
}

/// Slow in a debug build (27 s of damped Jacobi sweeps): `cargo test --release --test
/// paper_switches -- --include-ignored`.
#[test]
#[ignore = "27 s of Jacobi sweeps in a debug build; run with --release --include-ignored"]
fn damped_jacobi_converges_with_the_errata_numbers() {
    // ours: relaxation 1/2, 9 Newton iterations, Slip 0.5455, max v^3 = -1.1235e-3
    let (code, out, err) = jacobi(&["--json", "--quiet"]);
    assert_eq!(code, Some(0), "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["newton_iterations"], 9);
    assert_eq!(
        format!("{:.4}", v["slip_fraction"].as_f64().unwrap()),
        "0.5455"
    );
    let v3 = v["max_radial_displacement"]["value"].as_f64().unwrap();
    assert_eq!(format!("{v3:.4e}"), "-1.1235e-3");
}
