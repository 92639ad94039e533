//! Theorem 1 with general loads given as expressions (`loads.f_t`, `loads.f_n`): the
//! production ODE against Theorem 1's integral formula, the observed order of a reference
//! integrator, constant loads against today's gravity and belt-speed closed forms, and the
//! paper's printed steady-speed transform (erratum 4).

use std::f64::consts::FRAC_PI_2;

use capstan_friction::FrictionError;
use capstan_friction::membrane::{
    ExpressionLoad, MembraneBudget, MembraneEquilibrium, MembraneLoads, MembraneProblem,
    PaperSpeedTransform, closed_form, tension_profile, tension_profile_with_load,
};
use capstan_geometry::{
    CircularCylinder, EllipticalPrism, GeometryError, Obstacle, RightCircularCone,
};

/// The ellipse `(x1, a sin t, b cos t)` of the non-constant-load study.
const A: f64 = 2.0;
const B: f64 = 1.0;
const MU: f64 = 0.4;
const T0: f64 = 3.0;
const THETA0: f64 = -1.0;
const THETA_MAX: f64 = 1.2;
const F_T: &str = "0.3*sin(2*t) + 0.1";
const F_N: &str = "-0.5*cos(t)^2 + 0.2*t";

fn f_t(t: f64) -> f64 {
    0.3 * (2.0 * t).sin() + 0.1
}
fn f_n(t: f64) -> f64 {
    -0.5 * t.cos().powi(2) + 0.2 * t
}
/// `sqrt(a_22)` of the ellipse.
fn speed(t: f64) -> f64 {
    (A * A * t.cos().powi(2) + B * B * t.sin().powi(2)).sqrt()
}
/// The continuous turning angle `Psi(t) = atan((b/a) tan t) + pi round(t/pi)`.
fn psi(t: f64) -> f64 {
    closed_form::ellipse_turning_angle(A, B, t)
}

/// Composite 5-point Gauss–Legendre with `panels` panels (order 10): the reference quadrature,
/// independent of the crate's adaptive Gauss–Kronrod.
fn gauss_legendre(f: impl Fn(f64) -> f64, a: f64, b: f64, panels: usize) -> f64 {
    let x = [
        0.0,
        0.538_469_310_105_683_1,
        -0.538_469_310_105_683_1,
        0.906_179_845_938_664,
        -0.906_179_845_938_664,
    ];
    let w = [
        0.568_888_888_888_888_9,
        0.478_628_670_499_366_5,
        0.478_628_670_499_366_5,
        0.236_926_885_056_189_1,
        0.236_926_885_056_189_1,
    ];
    let h = (b - a) / panels as f64;
    (0..panels)
        .map(|k| {
            let m = a + (k as f64 + 0.5) * h;
            x.iter()
                .zip(&w)
                .map(|(xi, wi)| wi * f(m + 0.5 * h * xi))
                .sum::<f64>()
                * 0.5
                * h
        })
        .sum()
}

/// Theorem 1 (continuous turning angle):
/// `T = exp(mu Psi) [T0 exp(-mu Psi(theta0)) - int sqrt(a_22) (f_t + mu f_n) exp(-mu Psi)]`.
fn theorem1(theta: f64) -> f64 {
    let integrand = |x: f64| speed(x) * (f_t(x) + MU * f_n(x)) * (-MU * psi(x)).exp();
    let integral = gauss_legendre(integrand, THETA0, theta, 400);
    (MU * psi(theta)).exp() * (T0 * (-MU * psi(THETA0)).exp() - integral)
}

/// `dT/dx2` of the equilibrium, written out for the ellipse (no geometry layer).
fn rate(t: f64, tension: f64) -> f64 {
    let psi_rate = A * B / (speed(t) * speed(t));
    MU * psi_rate * tension - speed(t) * (f_t(t) + MU * f_n(t))
}

/// Classical fourth-order Runge–Kutta with `n` equal steps from `THETA0` to `theta`.
fn rk4(theta: f64, n: usize) -> f64 {
    let h = (theta - THETA0) / n as f64;
    let mut y = T0;
    for k in 0..n {
        let t = THETA0 + k as f64 * h;
        let k1 = rate(t, y);
        let k2 = rate(t + 0.5 * h, y + 0.5 * h * k1);
        let k3 = rate(t + 0.5 * h, y + 0.5 * h * k2);
        let k4 = rate(t + h, y + h * k3);
        y += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    y
}

fn problem(mu: f64, t0: f64, theta0: f64, theta_max: f64) -> MembraneProblem {
    MembraneProblem {
        mu,
        t0,
        theta0,
        theta_max,
        samples: 23,
        ..Default::default()
    }
}

fn ellipse() -> Obstacle {
    Obstacle::Ellipse(EllipticalPrism::new(A, B).unwrap())
}

fn max_relative(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| ((x - y) / y.abs()).abs())
        .fold(0.0, f64::max)
}

#[test]
fn theorem1_with_expression_loads_matches_its_integral_formula() {
    let load = ExpressionLoad::parse(Some(F_T), Some(F_N)).unwrap();
    let p = problem(MU, T0, THETA0, THETA_MAX);
    let profile =
        tension_profile_with_load(&ellipse(), &p, &MembraneBudget::default(), &load).unwrap();
    let exact: Vec<f64> = profile.theta.iter().map(|&t| theorem1(t)).collect();
    let err = max_relative(&profile.tension, &exact);
    // Dormand–Prince at 1e-13 against a 2000-node Gauss–Legendre rule (order 10): both near
    // round-off; the loads change T by tens of per cent, so the comparison is not vacuous.
    assert!(err < 1e-10, "max relative difference {err:.3e}");
    let unloaded = tension_profile(&ellipse(), &p).unwrap();
    let change = max_relative(&unloaded.tension, &profile.tension);
    assert!(change > 0.1, "the loads change the tension by {change}");
    println!(
        "T_max = {:.12} (Theorem 1 {:.12}), max relative difference {err:.2e}",
        profile.t_max(),
        exact[exact.len() - 1]
    );
}

#[test]
fn reference_rk4_converges_at_fourth_order_to_theorem1() {
    let exact = theorem1(THETA_MAX);
    let study: Vec<(f64, f64)> = [20, 40, 80, 160]
        .iter()
        .map(|&n| {
            let h = (THETA_MAX - THETA0) / n as f64;
            (h, (rk4(THETA_MAX, n) - exact).abs())
        })
        .collect();
    let orders: Vec<f64> = study
        .windows(2)
        .map(|w| (w[0].1 / w[1].1).ln() / (w[0].0 / w[1].0).ln())
        .collect();
    println!("RK4 (h, error): {study:?}; observed orders {orders:?}");
    for p in &orders {
        assert!((p - 4.0).abs() < 0.15, "observed orders {orders:?}");
    }
    assert!(study[3].1 < 1e-7, "{study:?}");
    // The production integrator agrees with the converged reference.
    let load = ExpressionLoad::parse(Some(F_T), Some(F_N)).unwrap();
    let p = problem(MU, T0, THETA0, THETA_MAX);
    let t_max = tension_profile_with_load(&ellipse(), &p, &MembraneBudget::default(), &load)
        .unwrap()
        .t_max();
    assert!(((t_max - exact) / exact).abs() < 1e-10);
}

#[test]
fn gravity_as_expressions_reproduces_cap_grav() {
    // Cylinder a = 1, w = rho h l g = 0.981, mu = 0.3, T0 = 5 on [0, 2] (docs/errata.md):
    // gravity (0, 0, -w) is f_t = w sin t, f_n = -w cos t.
    let cylinder = Obstacle::Cylinder(CircularCylinder::new(1.0).unwrap());
    let mut p = problem(0.3, 5.0, 0.0, 2.0);
    let as_loads = tension_profile_with_load(
        &cylinder,
        &p,
        &MembraneBudget::default(),
        &ExpressionLoad::parse(Some("0.981*sin(t)"), Some("-0.981*cos(t)")).unwrap(),
    )
    .unwrap();
    p.loads = MembraneLoads {
        gravity: 9.81,
        density: 0.1,
        ..Default::default()
    };
    let cap_grav = tension_profile(&cylinder, &p).unwrap();
    let err = max_relative(&as_loads.tension, &cap_grav.tension);
    assert!(err < 1e-12, "max relative difference {err:.3e}");
    assert!((cap_grav.t_max() - 7.768475055786).abs() < 1e-11);
}

#[test]
fn constant_normal_load_reproduces_the_belt_speed_closed_form() {
    // Belt speed c = rho_l V^2 = 0.3 on a cylinder of radius 2: R = kappa (T - c) = kappa T - f_n
    // with f_n = c kappa = 0.15, so T = c + (T0 - c) exp(mu theta).
    let cylinder = Obstacle::Cylinder(CircularCylinder::new(2.0).unwrap());
    let mut p = problem(0.5, 1.0, 0.0, FRAC_PI_2);
    let as_loads = tension_profile_with_load(
        &cylinder,
        &p,
        &MembraneBudget::default(),
        &ExpressionLoad::parse(None, Some("0.15")).unwrap(),
    )
    .unwrap();
    p.loads = MembraneLoads {
        density: 0.3,
        speed: 1.0,
        ..Default::default()
    };
    let speed = tension_profile(&cylinder, &p).unwrap();
    let err = max_relative(&as_loads.tension, &speed.tension);
    assert!(err < 1e-12, "max relative difference {err:.3e}");
    assert!((speed.t_max() - 1.835296035517).abs() < 1e-11);
}

#[test]
fn paper_speed_transform_gives_the_errata_number() {
    // Erratum 4: ellipse a = 2, b = 1 on [0, pi/2], mu = 1/2, T0 = 1, rho_l V^2 = 0.3.
    let e = EllipticalPrism::new(2.0, 1.0).unwrap();
    let mut p = problem(0.5, 1.0, 0.0, FRAC_PI_2);
    p.loads = MembraneLoads {
        density: 0.3,
        speed: 1.0,
        ..Default::default()
    };
    let ours = MembraneEquilibrium::new(&e, p).solve().unwrap().t_max();
    let printed = MembraneEquilibrium::new(&e, p)
        .solve_with(&PaperSpeedTransform { speed_tension: 0.3 })
        .unwrap()
        .0
        .t_max();
    assert!((ours - 1.835296035517).abs() < 1e-11, "{ours}");
    assert!((printed - 1.501379887204).abs() < 1e-11, "{printed}");
}

#[test]
fn bad_load_expressions_name_their_key() {
    let err = ExpressionLoad::parse(Some("sin(x)"), None).unwrap_err();
    assert!(matches!(
        err,
        FrictionError::Geometry(GeometryError::Expression {
            field: "loads.f_t",
            ..
        })
    ));
    assert!(err.to_string().contains("loads.f_t"), "{err}");
    let load = ExpressionLoad::parse(None, Some("ln(t)")).unwrap();
    let err = load.check_finite_on(-1.0, 1.0, 65).unwrap_err();
    assert!(err.to_string().contains("loads.f_n"), "{err}");
}

#[test]
fn loads_on_a_cone_are_refused() {
    let cone = Obstacle::CircularCone(RightCircularCone::new(0.5).unwrap());
    let load = ExpressionLoad::parse(Some("1"), None).unwrap();
    let err = tension_profile_with_load(
        &cone,
        &problem(0.5, 1.0, 0.0, 1.0),
        &MembraneBudget::default(),
        &load,
    )
    .unwrap_err();
    assert!(matches!(err, FrictionError::Unsupported { .. }), "{err}");
}

#[test]
fn a_load_that_pulls_the_membrane_off_is_a_lift_off() {
    // f_n = 5 outward on a unit cylinder with T0 = 1: R = T - 5 < 0 at once.
    let cylinder = Obstacle::Cylinder(CircularCylinder::new(1.0).unwrap());
    let load = ExpressionLoad::parse(None, Some("5")).unwrap();
    let err = tension_profile_with_load(
        &cylinder,
        &problem(0.5, 1.0, 0.0, 1.0),
        &MembraneBudget::default(),
        &load,
    )
    .unwrap_err();
    assert!(matches!(err, FrictionError::LiftOff { .. }), "{err}");
}
