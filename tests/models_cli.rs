//! `capstan infer-mu --model ...` and `capstan compare`: the three models' implied
//! coefficients through the binary, on a coarse thick-body grid.

mod common;

use common::capstan_json;
use serde_json::Value;

/// The coarse thick-body grid of every run here.
const GRID: [&str; 4] = ["--set", "grid.n2=41", "--set", "grid.n3=9"];

/// `capstan infer-mu --model MODEL --set membrane.t_max=T_MAX` on [`GRID`].
fn infer_mu_at(model: &str, t_max: f64) -> Value {
    let set = format!("membrane.t_max={t_max}");
    capstan_json(&[&["infer-mu", "--model", model, "--set", &set], &GRID[..]].concat())
}

fn infer_mu(model: &str) -> Value {
    infer_mu_at(model, 2.75)
}

#[test]
fn kikuchi_oden_implies_a_larger_mu_and_membrane_matches_capstan() {
    let [capstan, membrane, thick] = ["capstan", "membrane", "kikuchi-oden"].map(infer_mu);
    for (v, name) in [
        (&capstan, "capstan"),
        (&membrane, "membrane"),
        (&thick, "kikuchi-oden"),
    ] {
        assert_eq!(v["model"], name);
        assert_eq!(v["tension_ratio"].as_f64().unwrap(), 2.75);
    }
    let mu = |v: &Value| v["mu"].as_f64().unwrap();
    // Capstan on [-pi/2, pi/2] of the circle: ln(2.75) / pi, closed form.
    assert!((mu(&capstan) - 2.75f64.ln() / std::f64::consts::PI).abs() < 1e-15);
    assert_eq!(capstan["method"], "closed-form");
    // Membrane at full slip is the capstan equation up to its grid error (801 nodes).
    assert!(
        (mu(&membrane) / mu(&capstan) - 1.0).abs() < 1e-5,
        "{membrane} vs {capstan}"
    );
    // The paper's finding mu_capstan <= nu_F; 41 x 9 gives 0.417 against 0.322.
    assert!(mu(&thick) > mu(&capstan) * 1.1, "{thick} vs {capstan}");
    assert_eq!(thick["grid"], serde_json::json!([41, 9]));
}

#[test]
fn kikuchi_oden_mu_reproduces_the_threshold_ratio() {
    // threshold at mu = 1/2 gives r_K; inverting r_K must give mu = 1/2 back (bisection
    // tolerances: 1e-6 on the ratio and on mu, amplified by d mu / d r ~ 0.3).
    let t = capstan_json(&[&["threshold"], &GRID[..]].concat());
    let r = t["threshold_ratio"].as_f64().unwrap();
    let v = infer_mu_at("kikuchi-oden", r);
    let mu = v["mu"].as_f64().unwrap();
    assert!((mu - 0.5).abs() < 1e-4, "mu {mu} for r_K {r}");
}

#[test]
fn membrane_model_refuses_a_cone() {
    let refused = exit_code(&[
        "infer-mu",
        "--model",
        "membrane",
        "--set",
        "obstacle.shape=circular-cone",
        "--set",
        "membrane.t_max=2",
    ]);
    assert_eq!(refused, Some(2));
}

#[test]
fn compare_quick_writes_the_table_and_plots() {
    let dir = common::scratch_dir("compare");
    let d = dir.to_str().unwrap();
    let v = capstan_json(&["compare", "--quick", "--out", d]);
    let rows = v["b_over_a"].as_array().unwrap();
    assert_eq!(rows.len(), 3);
    for r in rows.iter().chain(v["poisson"].as_array().unwrap()) {
        let (capstan, membrane) = (
            r["mu_capstan"].as_f64().unwrap(),
            r["mu_membrane"].as_f64().unwrap(),
        );
        assert!(capstan < r["nu_kikuchi_oden"].as_f64().unwrap(), "{r}");
        assert!((membrane / capstan - 1.0).abs() < 1e-5, "{r}");
    }
    // h -> 0: r_K rises towards exp(nu_F pi) (41 x 9: 3.32245, 3.89516, 4.29178).
    let r: Vec<f64> = v["thickness"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["threshold_ratio"].as_f64().unwrap())
        .collect();
    assert!(r.windows(2).all(|w| w[0] < w[1]) && r[2] < v["capstan_ratio"].as_f64().unwrap());
    assert!((r[0] - 3.32245).abs() < 1e-4, "{r:?}"); // bisection tolerance 1e-5 relative
    for f in [
        "compare.json",
        "implied_mu.csv",
        "thickness.csv",
        "implied_mu_vs_b_over_a.svg",
        "implied_mu_vs_poisson.png",
        "implied_mu_vs_thickness.svg",
    ] {
        assert!(dir.join(f).is_file(), "{f}");
    }
    let csv = std::fs::read_to_string(dir.join("implied_mu.csv")).unwrap();
    assert!(csv.starts_with(
        "b_over_a,thickness,poisson,n2,n3,threshold_ratio,nu_kikuchi_oden,mu_capstan,mu_membrane\n"
    ));
    std::fs::remove_dir_all(&dir).unwrap();
}

fn exit_code(args: &[&str]) -> Option<i32> {
    common::capstan_status(args).0
}

#[test]
fn friction_law_selects_the_contact_law() {
    let traction = |law: &str| {
        let set = format!("friction.law={law}");
        let sets = ["--set", &set, "--set", "loads.tau_max=1.5"];
        capstan_json(&[&["contact"], &GRID[..], &sets].concat())["contact"]["friction_traction"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect::<Vec<f64>>()
    };
    // Howell with n = 1 and orthotropic Coulomb with mu2 = mu are Coulomb: same tractions
    // up to Newton's tolerance.
    let coulomb = traction("coulomb");
    for law in ["howell", "orthotropic-coulomb"] {
        let other = traction(law);
        let scale = coulomb.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        assert!(
            coulomb
                .iter()
                .zip(&other)
                .all(|(a, b)| (a - b).abs() <= 1e-8 * scale),
            "{law}"
        );
    }
}

#[test]
fn new_friction_keys_are_validated() {
    assert_eq!(
        exit_code(&["contact", "--set", "friction.exponent=3"]),
        Some(2)
    );
    assert_eq!(
        exit_code(&["contact", "--set", "friction.bound=-1"]),
        Some(2)
    );
    assert_eq!(
        exit_code(&[
            "contact",
            "--set",
            "friction.law=orthotropic-coulomb",
            "--set",
            "friction.mu=0",
            "--set",
            "friction.mu2=0",
        ]),
        Some(2)
    );
}
