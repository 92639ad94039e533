//! Paper items reached from a scene alone (issue 32): load expressions, Corollary 1
//! (`membrane.model = "infinite"`), the paper's belt-speed rule, the cone's development map.

mod common;

use std::f64::consts::FRAC_PI_2;

use capstan::cli::{Cli, run};
use clap::Parser;
use common::json_array as array;
use common::run_json as json;
use serde_json::Value;

fn tension(sets: &[&str]) -> Value {
    let mut args = vec!["tension"];
    for s in sets {
        args.push("--set");
        args.push(s);
    }
    json(&args)
}

/// Eq. capGrav with `theta0 = 0`: `(T0 - w a k) e^{mu t} + w a (k cos t + s sin t)`,
/// `k = (1 - mu^2)/(1 + mu^2)`, `s = 2 mu/(1 + mu^2)`, `w` the weight per unit length.
fn cap_grav(t0: f64, w: f64, a: f64, mu: f64, t: f64) -> f64 {
    let d = 1.0 + mu * mu;
    let (k, s) = ((1.0 - mu * mu) / d, 2.0 * mu / d);
    (t0 - w * a * k) * (mu * t).exp() + w * a * (k * t.cos() + s * t.sin())
}

const CYLINDER: [&str; 6] = [
    "obstacle.shape=cylinder",
    "obstacle.radius=1.5",
    "membrane.theta0=0",
    "membrane.theta_max=2",
    "friction.mu=0.3",
    "membrane.samples=9",
];

#[test]
fn infinite_membrane_is_corollary_1_in_closed_form() {
    // Corollary 1: stresses and volume densities; width and thickness play no part.
    let mut sets = CYLINDER.to_vec();
    sets.extend([
        "membrane.model=\"infinite\"",
        "membrane.t0=4",
        "loads.gravity=9.81",
        "loads.density=0.1",
        "loads.width=7",
        "loads.thickness=0.3",
    ]);
    let v = tension(&sets);
    assert_eq!(v["model"], "infinite");
    let (theta, tau) = (array(&v, "theta"), array(&v, "tension"));
    for (t, tau) in theta.iter().zip(&tau) {
        let exact = cap_grav(4.0, 0.981, 1.5, 0.3, *t);
        assert!(
            ((tau - exact) / exact).abs() < 1e-12,
            "{t}: {tau} vs {exact}"
        );
    }
    // Theorem 1 with the same scene is the force: h l times the stress under h l times the load.
    let mut finite = CYLINDER.to_vec();
    finite.extend([
        "membrane.t0=8.4",
        "loads.gravity=9.81",
        "loads.density=0.1",
        "loads.width=7",
        "loads.thickness=0.3",
    ]);
    let f = tension(&finite);
    assert_eq!(f["model"], "finite");
    let scaled = f["t_max"].as_f64().unwrap() / 2.1;
    assert!((scaled / v["t_max"].as_f64().unwrap() - 1.0).abs() < 1e-12);
}

#[test]
fn infinite_membrane_without_loads_is_the_capstan_equation() {
    let v = tension(&[
        "membrane.model=\"infinite\"",
        "obstacle.shape=ellipse",
        "obstacle.a=2",
        "obstacle.b=1",
        "membrane.theta0=-0.7853981633974483",
        "membrane.theta_max=0.7853981633974483",
        "membrane.t0=2.5",
    ]);
    let expected = 2.5 * (2.0 * 0.5 * 0.5f64.atan()).exp(); // exp(2 mu atan(b/a))
    assert!((v["t_max"].as_f64().unwrap() / expected - 1.0).abs() < 1e-14);
}

#[test]
fn gravity_as_load_expressions_equals_the_gravity_keys() {
    let mut keys = CYLINDER.to_vec();
    keys.extend(["membrane.t0=5", "loads.gravity=9.81", "loads.density=0.1"]);
    let builtin = tension(&keys);
    assert_eq!(builtin["method"], "closed-form");
    // gravity (0, 0, -w), w = 0.981, on (x1, a sin t, a cos t): f_t = w sin t, f_n = -w cos t
    let mut expr = CYLINDER.to_vec();
    expr.extend([
        "membrane.t0=5",
        "loads.f_t=0.981*sin(t)",
        "loads.f_n=-0.981*cos(t)",
    ]);
    let loaded = tension(&expr);
    assert_eq!(loaded["method"], "ode");
    for (a, b) in array(&builtin, "tension")
        .iter()
        .zip(array(&loaded, "tension"))
    {
        assert!(((a - b) / a).abs() < 1e-12, "{a} vs {b}");
    }
}

#[test]
fn paper_belt_speed_rule_is_selectable_and_differs_off_the_circle() {
    // Erratum 4: ellipse a = 2, b = 1 on [0, pi/2], mu = 1/2, T0 = 1, rho_l V^2 = 0.3.
    let theta_max = format!("membrane.theta_max={FRAC_PI_2}");
    let base = [
        "obstacle.shape=ellipse",
        "obstacle.a=2",
        "obstacle.b=1",
        "membrane.theta0=0",
        theta_max.as_str(),
        "loads.density=0.3",
        "loads.speed=1",
    ];
    let ours = tension(&base);
    let mut paper = base.to_vec();
    paper.push("membrane.belt_speed_rule=\"paper\"");
    let printed = tension(&paper);
    assert!((ours["t_max"].as_f64().unwrap() - 1.835296035517).abs() < 1e-11);
    assert!((printed["t_max"].as_f64().unwrap() - 1.501379887204).abs() < 1e-11);
    // On the circle (Gamma^2_22 = 0) the two rules agree.
    let circle = [
        "obstacle.shape=cylinder",
        "obstacle.radius=1",
        "membrane.theta0=0",
        theta_max.as_str(),
        "loads.density=0.3",
        "loads.speed=1",
        "membrane.belt_speed_rule=\"paper\"",
    ];
    assert!((tension(&circle)["t_max"].as_f64().unwrap() - 1.835296035517).abs() < 1e-11);
}

#[test]
fn bad_load_expressions_and_rules_name_their_key() {
    for (set, key) in [
        ("loads.f_t=2*sin(x)", "loads.f_t"),
        ("loads.f_n=1/(t-0.5)^0.5", "loads.f_n"),
        ("membrane.model=\"long\"", "model"),
        ("membrane.belt_speed_rule=\"printed\"", "belt_speed_rule"),
    ] {
        let argv = ["capstan", "tension", "--set", set, "--json"];
        let err = run(Cli::parse_from(argv)).unwrap_err();
        assert!(err.to_string().contains(key), "{set}: {err}");
        assert_eq!(err.exit_code(), 2, "{set}: {err}");
    }
    // A cone takes no load (Theorem 2).
    let argv = [
        "capstan",
        "tension",
        "--set",
        "obstacle.shape=circular-cone",
        "--set",
        "membrane.theta0=0",
        "--set",
        "membrane.theta_max=1",
        "--set",
        "loads.f_t=1",
        "--json",
    ];
    let err = run(Cli::parse_from(argv)).unwrap_err();
    assert!(err.to_string().contains("loads.f_t"), "{err}");
    assert_eq!(err.exit_code(), 2, "{err}");
}

#[test]
fn geometry_of_the_circular_cone_gives_forms_and_development_in_closed_form() {
    // sigma = (x, x tan(alpha) sin t, x tan(alpha) cos t) at x1 = 1:
    // a = diag(sec^2 alpha, tan^2 alpha), b_22 = -sin(alpha) (paper: -x1 (v'u'' - u'v'')/|w' x w|),
    // phi = sin(alpha) t, rbar = sec(alpha), J = [[sec c, -tan s], [sec s, tan c]].
    let alpha: f64 = 0.4;
    let v = json(&[
        "geometry",
        "--set",
        "obstacle.shape=circular-cone",
        "--set",
        "obstacle.half_angle=0.4",
        "--set",
        "membrane.theta0=-1.5",
        "--set",
        "membrane.theta_max=2",
        "--set",
        "membrane.samples=8",
    ]);
    assert_eq!(v["x1"].as_f64(), Some(1.0));
    let x2 = array(&v, "x2");
    let (sec, tan, sin) = (1.0 / alpha.cos(), alpha.tan(), alpha.sin());
    let close = |a: &Value, b: f64, what: &str| {
        let a = a.as_f64().unwrap();
        assert!(
            (a - b).abs() <= 1e-12 * b.abs().max(1.0),
            "{what}: {a} vs {b}"
        );
    };
    let d = &v["development"];
    for (i, t) in x2.iter().enumerate() {
        let a = &v["first_form"][i];
        close(&a[0][0], sec * sec, "a11");
        close(&a[0][1], 0.0, "a12");
        close(&a[1][0], 0.0, "a21");
        close(&a[1][1], tan * tan, "a22");
        let b = &v["second_form"][i];
        close(&b[0][0], 0.0, "b11");
        close(&b[0][1], 0.0, "b12");
        close(&b[1][1], -sin, "b22");
        let phi = sin * t;
        let (s, c) = phi.sin_cos();
        close(&d["phi"][i], phi, "phi");
        close(&d["radius"][i], sec, "rbar");
        close(&d["chi"][i][0], sec * c, "chi1");
        close(&d["chi"][i][1], sec * s, "chi2");
        let j = &d["jacobian"][i];
        close(&j[0][0], sec * c, "J11");
        close(&j[0][1], -tan * s, "J12");
        close(&j[1][0], sec * s, "J21");
        close(&j[1][1], tan * c, "J22");
    }
    // Prisms have no development.
    assert!(json(&["geometry"]).get("development").is_none());
}

#[test]
fn shell_chart_of_the_ellipse_is_the_papers_psi2bar() {
    // On the semi-prism body the paper's psi2bar = phi + x3 a b / phi^2 is sqrt(g_22), and
    // sqrt(g) = sqrt(g_22) there (g_11 = g_33 = 1, orthogonal): `sqrt_g_outer` at x3 = h.
    let v = json(&[
        "geometry",
        "--set",
        "obstacle.b=1.3",
        "--set",
        "body.thickness=0.7",
        "--set",
        "membrane.samples=9",
    ]);
    let (a, b, h) = (2.0_f64, 1.3_f64, 0.7);
    for (t, g) in array(&v, "x2").iter().zip(array(&v, "sqrt_g_outer")) {
        let phi = (b * b * t.sin().powi(2) + a * a * t.cos().powi(2)).sqrt();
        let psi = phi + h * a * b / (phi * phi);
        assert!((g - psi).abs() < 1e-12 * psi, "{t}: {g} vs {psi}");
    }
}

#[test]
fn circular_cone_limits_are_the_capstan_equation_and_no_friction() {
    // alpha -> 0: T0 exp(mu theta); alpha -> pi/2: T0 (cot(alpha) -> 0).
    let ratio = |alpha: &str, theta_max: &str| {
        tension(&[
            "obstacle.shape=circular-cone",
            alpha,
            "membrane.theta0=0",
            theta_max,
        ])["tension_ratio"]
            .as_f64()
            .unwrap()
    };
    let small = ratio("obstacle.half_angle=1e-6", "membrane.theta_max=2");
    // the exponent is theta - alpha^2 (theta^3/6 + theta/3) + ...: 1.1e-12 below at alpha = 1e-6
    assert!((small / 1f64.exp() - 1.0).abs() < 3e-12, "{small}");
    // near pi/2 the development limit pi/(2 sin(alpha)) is about pi/2: stay inside it
    let flat = ratio("obstacle.half_angle=1.5707", "membrane.theta_max=1.5");
    let alpha: f64 = "1.5707".parse().unwrap(); // as in the scene
    let exact = (0.5 / alpha.tan() * (alpha.sin() * 1.5).sin()).exp();
    assert!((flat - exact).abs() < 1e-14 && flat - 1.0 < 5e-5, "{flat}");
}

/// The non-constant load of `docs/paper.md` row 10 on the ellipse `a = 2`, `b = 1`.
const LOADED_ELLIPSE: [&str; 8] = [
    "obstacle.shape=ellipse",
    "obstacle.a=2",
    "obstacle.b=1",
    "membrane.theta0=-1",
    "membrane.theta_max=1.2",
    "membrane.t0=3",
    "loads.f_t=\"0.3*sin(2*t) + 0.1\"",
    "loads.f_n=\"-0.5*cos(t)^2 + 0.2*t\"",
];

#[test]
fn infer_mu_under_load_expressions_round_trips_through_tension() {
    let mut sets = LOADED_ELLIPSE.to_vec();
    sets.push("friction.mu=0.4");
    let t_max = tension(&sets)["t_max"].as_f64().unwrap();
    let pair = format!("membrane.t_max={t_max:.17e}");
    let mut args = vec!["infer-mu"];
    for s in LOADED_ELLIPSE
        .iter()
        .chain([&"friction.mu=0.9", &pair.as_str()])
    {
        args.extend(["--set", s]);
    }
    let v = json(&args);
    let mu = v["mu"].as_f64().unwrap();
    assert!((mu - 0.4).abs() < 1e-10, "inferred {mu}");
    assert_eq!(v["method"], "ode");
    // the membrane and thick-body models carry no such loads: refused, naming the key
    for model in ["membrane", "kikuchi-oden"] {
        let mut args = args.clone();
        args.extend(["--model", model]);
        let (code, _, err) = common::capstan_status(&args);
        assert_eq!(code, Some(2), "{err}");
        assert!(err.contains("loads.f_t"), "{err}");
    }
}
