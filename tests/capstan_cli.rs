//! `capstan tension` and `capstan infer-mu`: numbers through the library and the binary.

mod common;

use std::f64::consts::{FRAC_PI_4, PI};

use capstan::cli::{Cli, run};
use clap::Parser;
use common::json_array as array;
use common::run_json as json;

#[test]
fn tension_on_an_ellipse_quarter_is_exp_2_mu_atan_b_over_a() {
    let theta0 = format!("membrane.theta0={}", -FRAC_PI_4);
    let theta1 = format!("membrane.theta_max={}", FRAC_PI_4);
    let v = json(&[
        "tension",
        "--set",
        "obstacle.shape=ellipse",
        "--set",
        "obstacle.a=1",
        "--set",
        "obstacle.b=1.5",
        "--set",
        &theta0,
        "--set",
        &theta1,
        "--set",
        "membrane.samples=7",
    ]);
    assert_eq!(v["method"], "closed-form");
    let (theta, tension) = (array(&v, "theta"), array(&v, "tension"));
    assert_eq!(theta.len(), 7);
    assert_eq!(tension.len(), 7);
    assert_eq!(theta[0], -FRAC_PI_4);
    assert_eq!(theta[6], FRAC_PI_4);
    let expected = (2.0 * 0.5 * 1.5f64.atan()).exp(); // friction.mu defaults to 1/2
    assert!((v["tension_ratio"].as_f64().unwrap() - expected).abs() < 1e-14);
    assert!((v["t_max"].as_f64().unwrap() - expected).abs() < 1e-14);
}

/// `capstan tension` on the ellipse `a = 2, b = 1` written as a general prism.
const PRISM_ELLIPSE: [&str; 7] = [
    "tension",
    "--set",
    "obstacle.shape=prism",
    "--set",
    "obstacle.u=2*sin(t)",
    "--set",
    "obstacle.v=cos(t)",
];

#[test]
fn tension_methods_follow_the_scene() {
    let prism = json(&PRISM_ELLIPSE);
    assert_eq!(prism["method"], "quadrature");
    let ellipse = json(&["tension", "--set", "obstacle.a=2", "--set", "obstacle.b=1"]);
    assert!(
        (prism["t_max"].as_f64().unwrap() - ellipse["t_max"].as_f64().unwrap()).abs() < 1e-13,
        "expression ellipse vs closed form"
    );
    let heavy = json(
        &[
            &PRISM_ELLIPSE[..],
            &[
                "--set",
                "loads.gravity=9.81",
                "--set",
                "loads.density=0.1",
                "--set",
                "loads.thickness=0.1",
                "--set",
                "membrane.t0=5",
            ],
        ]
        .concat(),
    );
    assert_eq!(heavy["method"], "ode");
    let cone = json(&[
        "tension",
        "--set",
        "obstacle.shape=circular-cone",
        "--set",
        "obstacle.half_angle=0.5",
        "--set",
        "membrane.theta0=0",
        "--set",
        "membrane.theta_max=2",
    ]);
    assert_eq!(cone["method"], "closed-form");
    let expected = (0.5 / 0.5f64.tan() * (0.5f64.sin() * 2.0).sin()).exp();
    assert!((cone["tension_ratio"].as_f64().unwrap() - expected).abs() < 1e-14);
    let general = json(&[
        "tension",
        "--set",
        "obstacle.shape=cone",
        "--set",
        "membrane.theta0=0",
        "--set",
        "membrane.theta_max=2",
    ]);
    assert_eq!(general["method"], "quadrature");
}

#[test]
fn cylinder_with_gravity_is_cap_grav() {
    let v = json(&[
        "tension",
        "--set",
        "obstacle.shape=cylinder",
        "--set",
        "obstacle.radius=1",
        "--set",
        "membrane.theta0=0",
        "--set",
        "membrane.theta_max=1.5",
        "--set",
        "membrane.t0=3",
        "--set",
        "loads.gravity=9.81",
        "--set",
        "loads.density=0.2",
        "--set",
        "loads.width=0.5",
        "--set",
        "loads.thickness=0.5",
        "--set",
        "friction.mu=0.3",
    ]);
    assert_eq!(v["method"], "closed-form");
    let (w, mu, t) = (9.81 * 0.2 * 0.25, 0.3f64, 1.5f64);
    let k = (1.0 - mu * mu) / (1.0 + mu * mu);
    let cap_grav =
        (3.0 - w * k) * (mu * t).exp() + w * (k * t.cos() + 2.0 * mu / (1.0 + mu * mu) * t.sin());
    assert!((v["t_max"].as_f64().unwrap() - cap_grav).abs() < 1e-13 * cap_grav);
}

#[test]
fn infer_mu_on_a_circle_half_wrap_is_0_322() {
    let theta1 = format!("membrane.theta_max={PI}");
    let v = json(&[
        "infer-mu",
        "--set",
        "obstacle.shape=cylinder",
        "--set",
        "membrane.theta0=0",
        "--set",
        &theta1,
        "--set",
        "membrane.t_max=2.75",
    ]);
    let mu = v["mu"].as_f64().unwrap();
    assert!((mu - 2.75f64.ln() / PI).abs() < 1e-15);
    assert!(format!("{mu:.5}") == "0.32200");
    assert_eq!(v["method"], "closed-form");
}

#[test]
fn human_readable_output_is_a_table() {
    let out = run(Cli::parse_from([
        "capstan",
        "tension",
        "--set",
        "membrane.samples=5",
    ]))
    .unwrap();
    assert!(
        out.contains("T_max/T0") && out.contains("closed-form"),
        "{out}"
    );
    assert_eq!(
        out.lines()
            .filter(|l| l
                .trim_start()
                .starts_with(|c: char| c == '-' || c.is_ascii_digit()))
            .count(),
        5
    );
    let out = run(Cli::parse_from([
        "capstan",
        "infer-mu",
        "--set",
        "membrane.t_max=3",
    ]))
    .unwrap();
    assert!(out.contains("mu = "), "{out}");
}

fn exit_code(args: &[&str]) -> (i32, String) {
    let (code, _, stderr) = common::capstan_status(args);
    (code.unwrap_or(-1), stderr)
}

#[test]
fn errors_map_to_exit_codes() {
    // bad input: 2, naming the key
    let (code, err) = exit_code(&["tension", "--set", "friction.mu=-1"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("friction.mu"), "{err}");
    let (code, err) = exit_code(&["infer-mu"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("membrane.t_max"), "{err}");
    // no limiting equilibrium: 3, naming the angle
    let (code, err) = exit_code(&["infer-mu", "--set", "membrane.t_max=0.5"]);
    assert_eq!(code, 3, "{err}");
    let (code, err) = exit_code(&[
        "tension",
        "--set",
        "obstacle.shape=prism",
        "--set",
        "obstacle.u=sin(t) + 0.3*sin(3*t)",
        "--set",
        "obstacle.v=cos(t)",
    ]);
    assert_eq!(code, 3, "{err}");
    assert!(
        err.contains("not convex") && err.contains("theta ="),
        "{err}"
    );
    let (code, err) = exit_code(&[
        "tension",
        "--set",
        "obstacle.shape=circular-cone",
        "--set",
        "membrane.theta_max=4",
    ]);
    assert_eq!(code, 3, "{err}");
}

#[test]
fn contact_follows_the_scene_discretisation() {
    // `discretisation.method` selects the bulk operator of `capstan contact`; the three agree on
    // the default case within their discretisation errors (the largest v^2 to 1%, Slip exactly
    // on this grid), and the report names the method.
    let mut max_v2 = Vec::new();
    for method in ["fd", "fem-q1", "fem-q2"] {
        let set = format!("discretisation.method={method}");
        let v = json(&[
            "contact",
            "--set",
            &set,
            "--set",
            "grid.n2=61",
            "--set",
            "grid.n3=11",
        ]);
        assert_eq!(v["discretisation"], method);
        assert_eq!(v["converged"], true);
        max_v2.push(v["max_azimuthal_displacement"]["value"].as_f64().unwrap());
    }
    for v in &max_v2[1..] {
        assert!((v / max_v2[0] - 1.0).abs() < 1e-2, "{max_v2:?}");
    }
    let v = json(&[
        "contact",
        "--set",
        "discretisation.method=fem-q1",
        "--set",
        "discretisation.volumetric=reduced",
        "--set",
        "grid.n2=40",
        "--set",
        "grid.n3=9",
    ]);
    assert_eq!(v["discretisation"], "fem-q1");
}

#[test]
fn full_newton_reports_its_grid_sequence_and_agrees_with_the_condensed_solver() {
    // Below 20,000 nodes one level: the scene's grid, solved directly.
    let grid = ["--set", "grid.n2=61", "--set", "grid.n3=11"];
    let full = json(
        &[
            &["contact", "--set", "solver.nonlinear=full-newton"][..],
            &grid[..],
        ]
        .concat(),
    );
    let condensed = json(&[&["contact"][..], &grid[..]].concat());
    let iterations = full["newton_iterations"].as_u64().unwrap();
    assert_eq!(
        full["grid_sequence"],
        serde_json::json!([[61, 11, iterations]])
    );
    assert_eq!(condensed["grid_sequence"], serde_json::Value::Null);
    let v2 = |v: &serde_json::Value| v["max_azimuthal_displacement"]["value"].as_f64().unwrap();
    assert!((v2(&full) / v2(&condensed) - 1.0).abs() < 1e-7);
    assert_eq!(full["slip_fraction"], condensed["slip_fraction"]);
}

/// The words of a command line as a POSIX shell splits it (single quotes only, which is all
/// the examples use).
fn shell_words(line: &str) -> Vec<String> {
    let (mut words, mut word, mut quoted, mut open) = (Vec::new(), String::new(), false, false);
    for c in line.chars() {
        match c {
            '\'' => (quoted, open) = (!quoted, true),
            ' ' if !quoted => {
                if open {
                    words.push(std::mem::take(&mut word));
                }
                open = false;
            }
            _ => (word, open) = (word + &c.to_string(), true),
        }
    }
    if open {
        words.push(word);
    }
    words
}

#[test]
fn every_help_example_parses_and_every_reworded_argument_exists() {
    use capstan::cli::SUBCOMMAND_HELP;
    assert_eq!(
        shell_words("capstan geometry --set 'obstacle.u=2*sin(t) + 1' --json"),
        [
            "capstan",
            "geometry",
            "--set",
            "obstacle.u=2*sin(t) + 1",
            "--json"
        ]
    );
    let cli = Cli::command_with_help();
    let names: Vec<&str> = cli.get_subcommands().map(|c| c.get_name()).collect();
    for help in SUBCOMMAND_HELP {
        assert!(names.contains(&help.name), "no subcommand {}", help.name);
        assert!(!help.examples.is_empty(), "{}: no example", help.name);
        for example in help.examples {
            let words = shell_words(example);
            assert_eq!(words[0], "capstan", "{example}");
            if let Err(e) = Cli::command_with_help().try_get_matches_from(&words) {
                panic!("{example}: {e}");
            }
        }
        // `mut_arg` on an unknown id panics at build time: the reworded arguments exist
        let mut command = Cli::command_with_help();
        let sub = command.find_subcommand_mut(help.name).expect("listed");
        for (id, text) in help.arguments {
            let arg = sub.get_arguments().find(|a| a.get_id() == id);
            let shown = arg.and_then(|a| a.get_help()).map(ToString::to_string);
            assert_eq!(shown.as_deref(), Some(*text), "{}: {id}", help.name);
        }
    }
    // every subcommand but the defaults-only ones has examples
    for name in names {
        assert!(
            name == "help" || SUBCOMMAND_HELP.iter().any(|h| h.name == name),
            "{name} has no examples"
        );
    }
}
