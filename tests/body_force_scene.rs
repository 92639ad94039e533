//! `loads.body_force` from a scene (issue 32): a zero force reproduces today's contact
//! numbers, a force moves them the same way under the condensed and the full-system Newton,
//! 2-D and 3-D; bad input names the key.

mod common;

use capstan::cli::{Cli, run};
use clap::Parser;
use serde_json::Value;

fn contact(sets: &[&str]) -> Value {
    let mut argv = vec!["capstan", "contact"];
    for s in sets {
        argv.extend(["--set", s]);
    }
    argv.push("--json");
    serde_json::from_str(&run(Cli::parse_from(argv)).unwrap()).unwrap()
}

/// The report without wall times and the echoed scene.
fn numbers(mut v: Value) -> Value {
    let map = v.as_object_mut().unwrap();
    for key in ["setup_seconds", "solve_seconds", "scene"] {
        map.remove(key);
    }
    v
}

fn max_abs_diff(a: &Value, b: &Value, key: &str) -> (f64, f64) {
    let (a, b) = (
        common::json_array(&a["contact"], key),
        common::json_array(&b["contact"], key),
    );
    assert_eq!(a.len(), b.len());
    let size = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let diff = a
        .iter()
        .zip(&b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    (diff, size)
}

const COARSE: [&str; 2] = ["grid.n2=41", "grid.n3=9"];

#[test]
fn a_zero_body_force_reproduces_the_default_contact_run() {
    // the paper's default run (250 x 41, condensed Newton), bit for bit
    let zero = contact(&["loads.body_force=[\"0\", \"0*x3\"]"]);
    assert_eq!(numbers(zero.clone()), numbers(contact(&[])));
    assert_eq!(zero["scene"]["loads"]["body_force"][1], "0*x3");
    // and the full-system Newton's (grid sequencing) on a coarse grid
    let mut sets = COARSE.to_vec();
    sets.push("solver.nonlinear=\"full-newton\"");
    let bare = contact(&sets);
    sets.push("loads.body_force=[\"0\", \"0\"]");
    assert_eq!(numbers(contact(&sets)), numbers(bare));
}

#[test]
fn a_body_force_moves_the_solution_alike_under_both_newtons() {
    let force = "loads.body_force=[\"0.05*(1 + x3)\", \"-0.4*cos(x2)\"]";
    let mut sets = COARSE.to_vec();
    sets.push(force);
    let condensed = contact(&sets);
    sets.push("solver.nonlinear=\"full-newton\"");
    let full = contact(&sets);
    let (diff, size) = max_abs_diff(&condensed, &full, "v2");
    assert!(
        diff <= 1e-7 * size,
        "condensed vs full-newton: {diff:e} of {size:e}"
    );
    assert_eq!(condensed["slip_fraction"], full["slip_fraction"]);
    // limiting ratios assume loads linear in the end tractions: not reported with a force
    assert!(condensed["limiting_ratios"].is_null());
    let bare = contact(&COARSE);
    let (change, _) = max_abs_diff(&condensed, &bare, "v2");
    assert!(change > 1e-2 * size, "the force changes v2 by {change:e}");
}

#[test]
fn a_solid_body_takes_three_components_in_x1_x2_x3() {
    let body = [
        "body.dimension=3",
        "discretisation.method=\"fem-q1\"",
        "grid.n1=3",
        "grid.n2=21",
        "grid.n3=5",
        "body.sides=\"plane-strain\"",
    ];
    let bare = contact(&body);
    let mut sets = body.to_vec();
    sets.push("loads.body_force=[\"0\", \"0\", \"0*x1\"]");
    assert_eq!(numbers(contact(&sets)), numbers(bare.clone()));
    // an x1-invariant force on the extruded body is the plane body's (Q1, 21 x 5)
    sets.pop();
    sets.push("loads.body_force=[\"0\", \"0.05*(1 + x3)\", \"-0.4*cos(x2)\"]");
    let solid = contact(&sets);
    let plane = contact(&[
        "discretisation.method=\"fem-q1\"",
        "grid.n2=21",
        "grid.n3=5",
        "loads.body_force=[\"0.05*(1 + x3)\", \"-0.4*cos(x2)\"]",
    ]);
    assert_eq!(solid["slip_fraction"], plane["slip_fraction"]);
    let (s, p) = (
        common::json_array(&solid["contact"], "v2"),
        common::json_array(&plane["contact"], "v2"),
    );
    let size = p.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for row in s.chunks(21) {
        for (a, b) in row.iter().zip(&p) {
            assert!((a - b).abs() <= 1e-9 * size, "{a} vs {b}");
        }
    }
}

#[test]
fn bad_body_forces_name_the_key() {
    for (set, says) in [
        ("loads.body_force=[\"1\"]", "takes 2"),
        ("loads.body_force=[\"1\", \"2\", \"3\"]", "takes 2"),
        ("loads.body_force=[\"x1\", \"0\"]", "`x2`, `x3`"),
        ("loads.body_force=[\"ln(x3)\", \"0\"]", "not finite"),
        ("loads.body_force=[\"1 +\", \"0\"]", "loads.body_force"),
    ] {
        let (code, _, err) = common::capstan_status(&["contact", "--set", set]);
        assert_eq!(code, Some(2), "{set}: {err}");
        assert!(
            err.contains("loads.body_force") && err.contains(says),
            "{set}: {err}"
        );
    }
    let (code, _, err) = common::capstan_status(&[
        "contact",
        "--set",
        "body.dimension=3",
        "--set",
        "discretisation.method=\"fem-q1\"",
        "--set",
        "loads.body_force=[\"0\", \"0\"]",
    ]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("takes 3"), "{err}");
    // the threshold and the thick-body implied mu need loads linear in the end tractions
    let force = "loads.body_force=[\"0\", \"-0.1\"]";
    for args in [
        &["threshold", "--set", force][..],
        &[
            "infer-mu",
            "--model",
            "kikuchi-oden",
            "--set",
            "membrane.t_max=2",
            "--set",
            force,
        ],
    ] {
        let (code, _, err) = common::capstan_status(args);
        assert_eq!(code, Some(2), "{args:?}: {err}");
        assert!(err.contains("loads.body_force"), "{args:?}: {err}");
    }
}
