//! Membrane capstan models: every closed form and quadrature against Dormand–Prince
//! integration of the membrane equilibrium built from the geometry layer.

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI, TAU};

use approx::assert_relative_eq;
use capstan_friction::FrictionError;
use capstan_friction::membrane::{
    ConeMembrane, GeodesicStrip, Gravity, InfiniteMembrane, LoadField, MembraneEquilibrium,
    MembraneLoads, MembraneProblem, Method, closed_form, infer_mu, tension_profile,
};
use capstan_friction::quadrature::GaussKronrod;
use capstan_friction::samples::{ReferenceEllipse, heavy_fast_belt, weighted_belt, wobbly_prism};
use capstan_geometry::{
    CircularCylinder, EllipticalPrism, ExpressionProfile, GeneralCone, Obstacle, RightCircularCone,
    Surface, SurfaceGeometry,
};

/// Largest relative difference between two profiles.
fn max_relative(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| ((x - y) / y.abs().max(1e-300)).abs())
        .fold(0.0, f64::max)
}

fn problem(mu: f64, theta0: f64, theta_max: f64) -> MembraneProblem {
    MembraneProblem {
        mu,
        theta0,
        theta_max,
        samples: 41,
        ..Default::default()
    }
}

/// The problem `mu`, `t0` on `[theta0, theta_max]` with `samples` output samples under
/// `loads`.
fn loaded(
    mu: f64,
    t0: f64,
    [theta0, theta_max]: [f64; 2],
    samples: usize,
    loads: MembraneLoads,
) -> MembraneProblem {
    MembraneProblem {
        mu,
        t0,
        theta0,
        theta_max,
        samples,
        loads,
    }
}

/// The unit circle and the default problem on the half turn `[0, pi]`.
fn half_turn_of_the_unit_circle() -> (Obstacle, MembraneProblem) {
    let circle = Obstacle::Cylinder(CircularCylinder::new(1.0).unwrap());
    let half = MembraneProblem {
        theta0: 0.0,
        theta_max: PI,
        ..Default::default()
    };
    (circle, half)
}

/// The ODE built from `Surface::geometry` on `surface`, compared with `tension_profile`.
fn ode_vs_model<S: Surface<f64>>(
    surface: &S,
    obstacle: &Obstacle,
    p: &MembraneProblem,
) -> (f64, Method) {
    let model = tension_profile(obstacle, p).unwrap();
    let ode = MembraneEquilibrium::new(surface, *p).solve().unwrap();
    assert_eq!(ode.method, Method::Ode);
    assert_eq!(model.theta, ode.theta);
    (max_relative(&model.tension, &ode.tension), model.method)
}

#[test]
fn ellipse_closed_form_matches_ode_past_pi_over_2_and_over_multiple_wraps() {
    let e = EllipticalPrism::new(2.0, 1.0).unwrap();
    let obstacle = Obstacle::Ellipse(e);
    for (theta0, theta_max, mu) in [
        (-FRAC_PI_4, FRAC_PI_4, 0.5),
        (0.0, FRAC_PI_2 + 1.0, 0.5),  // past pi/2, where u' = 0
        (-0.3, 2.0 * TAU + 1.1, 0.3), // more than two wraps
        (0.0, TAU, 5.0),              // mu = 5 over a full turn
    ] {
        let p = problem(mu, theta0, theta_max);
        let (err, method) = ode_vs_model(&e, &obstacle, &p);
        assert_eq!(method, Method::ClosedForm);
        assert!(err <= 1e-10, "[{theta0}, {theta_max}] mu {mu}: {err:e}");
    }
}

#[test]
fn expression_ellipse_quadrature_equals_the_closed_form_to_rounding() {
    let r = ReferenceEllipse::default();
    for (theta0, theta_max) in [
        (-FRAC_PI_4, FRAC_PI_4),
        (0.2, FRAC_PI_2 + 0.7),
        (-1.0, 3.0 * TAU),
    ] {
        let p = problem(0.7, theta0, theta_max);
        let exact = tension_profile(&r.closed_form(), &p).unwrap();
        let quad = tension_profile(&r.expressions(), &p).unwrap();
        assert_eq!(quad.method, Method::Quadrature);
        let err = max_relative(&quad.tension, &exact.tension);
        // atan2 snapping: the quadrature only fixes the branch, so round-off is all that is left
        assert!(err <= 1e-13, "[{theta0}, {theta_max}]: {err:e}");
    }
}

#[test]
fn full_turn_of_closed_convex_prisms_gives_exp_2_pi_mu() {
    let mu = 0.4;
    for obstacle in [
        wobbly_prism(),
        ReferenceEllipse { a: 1.0, b: 3.0 }.expressions(),
    ] {
        for theta0 in [-2.0, 0.0, 0.9] {
            let p = problem(mu, theta0, theta0 + TAU);
            let model = tension_profile(&obstacle, &p).unwrap();
            assert_relative_eq!(
                model.tension_ratio(),
                (TAU * mu).exp(),
                max_relative = 1e-14
            );
        }
    }
    // and the ODE on the same non-elliptical prism
    let Obstacle::Prism(prism) = wobbly_prism() else {
        unreachable!()
    };
    let (err, _) = ode_vs_model(&prism, &wobbly_prism(), &problem(mu, 0.3, 0.3 + TAU));
    assert!(err <= 1e-10, "{err:e}");
}

#[test]
fn cylinder_with_gravity_is_cap_grav_and_matches_ode() {
    let radius = 1.5;
    let cyl = CircularCylinder::new(radius).unwrap();
    let obstacle = Obstacle::Cylinder(cyl);
    let loads = MembraneLoads {
        width: 0.5,
        thickness: 0.2,
        ..weighted_belt(0.3)
    };
    let w = loads.weight_per_length();
    let p = loaded(0.35, 2.0, [0.0, PI], 61, loads);
    let model = tension_profile(&obstacle, &p).unwrap();
    assert_eq!(model.method, Method::ClosedForm);
    // eq. capGrav as printed (theta0 = 0)
    let (mu, k) = (p.mu, (1.0 - p.mu * p.mu) / (1.0 + p.mu * p.mu));
    for (&t, &tension) in model.theta.iter().zip(&model.tension) {
        let printed = (p.t0 - radius * w * k) * (mu * t).exp()
            + radius * w * (k * t.cos() + 2.0 * mu / (1.0 + mu * mu) * t.sin());
        assert_relative_eq!(tension, printed, max_relative = 1e-14);
    }
    let (err, _) = ode_vs_model(&cyl, &obstacle, &p);
    assert!(err <= 1e-10, "{err:e}");
    // with theta0 != 0 and steady speed too
    let p = MembraneProblem {
        theta0: -1.0,
        theta_max: 2.5,
        t0: 3.0,
        loads: MembraneLoads {
            speed: 3.0,
            ..loads
        },
        ..p
    };
    let (err, method) = ode_vs_model(&cyl, &obstacle, &p);
    assert_eq!(method, Method::ClosedForm);
    assert!(err <= 1e-10, "{err:e}");
}

#[test]
fn steady_speed_transform_is_closed_form_on_every_prism() {
    // T - rho_l V^2 obeys the load-free law: only g_r3 changes (paper-notes item 4)
    let e = EllipticalPrism::new(2.0, 1.0).unwrap();
    let loads = MembraneLoads {
        density: 0.5,
        thickness: 0.2,
        speed: 3.0,
        ..Default::default()
    };
    let c = loads.speed_tension();
    let p = loaded(0.6, 2.0, [-1.0, 2.5], 41, loads);
    let (err, method) = ode_vs_model(&e, &Obstacle::Ellipse(e), &p);
    assert_eq!(method, Method::ClosedForm);
    assert!(err <= 1e-10, "{err:e}");
    let model = tension_profile(&Obstacle::Ellipse(e), &p).unwrap();
    let free = tension_profile(
        &Obstacle::Ellipse(e),
        &MembraneProblem {
            t0: p.t0 - c,
            loads: MembraneLoads::default(),
            ..p
        },
    )
    .unwrap();
    for (a, b) in model.tension.iter().zip(&free.tension) {
        assert_relative_eq!(a - c, *b, max_relative = 1e-13);
    }
    // expression prism: quadrature path with speed
    let r = ReferenceEllipse::default();
    let quad = tension_profile(&r.expressions(), &p).unwrap();
    assert!(max_relative(&quad.tension, &model.tension) <= 1e-13);
}

#[test]
fn gravity_on_an_ellipse_matches_theorem_1_by_nested_quadrature() {
    // Theorem 1 with the continuous Psi:
    // T = e^{mu dPsi} [T0 - int (g_r2 + mu sqrt(a22) g_r3) e^{-mu dPsi}],  g_r2 = -w v', sqrt(a22) g_r3 = -w u'
    let (a, b) = (2.0, 1.0);
    let e = EllipticalPrism::new(a, b).unwrap();
    let loads = MembraneLoads {
        width: 1.0,
        thickness: 0.5,
        ..weighted_belt(0.2)
    };
    let w = loads.weight_per_length();
    let p = loaded(0.4, 4.0, [-1.2, 2.4], 13, loads);
    let ode = tension_profile(&Obstacle::Ellipse(e), &p).unwrap();
    assert_eq!(ode.method, Method::Ode);
    let psi = |t: f64| {
        closed_form::ellipse_turning_angle(a, b, t)
            - closed_form::ellipse_turning_angle(a, b, p.theta0)
    };
    for (&t, &tension) in ode.theta.iter().zip(&ode.tension) {
        let integral = GaussKronrod::default()
            .integrate(
                |s: f64| {
                    let (du, dv) = (a * s.cos(), -b * s.sin());
                    Ok((-w * dv - p.mu * w * du) * (-p.mu * psi(s)).exp())
                },
                p.theta0,
                t,
            )
            .unwrap()
            .value;
        let theorem = (p.mu * psi(t)).exp() * (p.t0 - integral);
        assert_relative_eq!(tension, theorem, max_relative = 1e-10);
    }
}

#[test]
fn expression_prism_with_gravity_and_speed_matches_the_ellipse() {
    let r = ReferenceEllipse::default();
    let p = loaded(0.3, 5.0, [-1.0, 2.0], 21, heavy_fast_belt());
    let exact = tension_profile(&r.closed_form(), &p).unwrap();
    let expr = tension_profile(&r.expressions(), &p).unwrap();
    assert_eq!(expr.method, Method::Ode);
    assert!(max_relative(&expr.tension, &exact.tension) <= 1e-10);
}

#[test]
fn corollary_1_is_theorem_1_divided_by_h_l() {
    let obstacle = ReferenceEllipse::default().closed_form();
    let (h, l) = (0.2, 0.7);
    let loads = MembraneLoads {
        gravity: 9.81,
        density: 0.5,
        width: l,
        thickness: h,
        speed: 1.5,
    };
    let p = loaded(0.3, 3.0, [-0.5, 2.0], 11, loads);
    let force = tension_profile(&obstacle, &p).unwrap();
    let stress = InfiniteMembrane {
        mu: p.mu,
        tau0: p.t0 / (h * l),
        theta0: p.theta0,
        theta_max: p.theta_max,
        samples: p.samples,
        density: 0.5,
        gravity: 9.81,
        speed: 1.5,
    }
    .stress_profile(&obstacle)
    .unwrap();
    for (t, tau) in force.tension.iter().zip(&stress.tension) {
        assert_relative_eq!(t / (h * l), *tau, max_relative = 1e-10);
    }
}

fn cone_from_expressions(half_angle: f64) -> GeneralCone<ExpressionProfile> {
    let k = half_angle.tan();
    GeneralCone::new(
        ExpressionProfile::parse(&format!("{k}*sin(t)"), &format!("{k}*cos(t)")).unwrap(),
    )
}

#[test]
fn right_circular_cone_closed_form_matches_theorem_2_quadrature_and_3d_geodesics() {
    let alpha = 0.5;
    let cone = RightCircularCone::new(alpha).unwrap();
    let general = cone_from_expressions(alpha);
    for (theta0, theta_max) in [(0.0, 2.0), (-1.5, 2.5), (0.7, 3.0)] {
        let p = MembraneProblem {
            samples: 9,
            ..problem(0.6, theta0, theta_max)
        };
        let exact = tension_profile(&Obstacle::CircularCone(cone), &p).unwrap();
        assert_eq!(exact.method, Method::ClosedForm);
        let quad = tension_profile(&Obstacle::Cone(general.clone()), &p).unwrap();
        assert_eq!(quad.method, Method::Quadrature);
        assert!(max_relative(&quad.tension, &exact.tension) <= 1e-12);
        // independent: a string along the geodesic crossing the generator x2 = 0 at right angles
        let strip = GeodesicStrip::new(&cone, p.mu);
        let start = [1.0, 0.0];
        let dir = strip.perpendicular_to_generator(start).unwrap();
        let mut thetas = exact.theta.clone();
        thetas.push(theta0);
        let ln = strip.log_tension(start, dir, &thetas).unwrap();
        let ln0 = *ln.last().unwrap();
        for (i, t) in exact.tension.iter().enumerate() {
            let geodesic = p.t0 * (ln[i] - ln0).exp();
            assert_relative_eq!(geodesic, *t, max_relative = 1e-10);
        }
    }
}

#[test]
fn general_cone_quadrature_matches_3d_geodesics() {
    // an elliptical cone, apex at 0, convex: ubar = 0.6 sin t, vbar = 0.3 cos t
    let profile = ExpressionProfile::parse("0.6*sin(t)", "0.3*cos(t)").unwrap();
    let cone = GeneralCone::new(profile.clone());
    let p = MembraneProblem {
        samples: 7,
        ..problem(0.5, -0.8, 1.1)
    };
    let model = ConeMembrane::new(&profile).tension_profile(&p).unwrap();
    let strip = GeodesicStrip::new(&cone, p.mu);
    let start = [2.0, 0.0]; // Theorem 2 does not depend on x1
    let dir = strip.perpendicular_to_generator(start).unwrap();
    let ln = strip.log_tension(start, dir, &model.theta).unwrap();
    for (i, t) in model.tension.iter().enumerate() {
        assert_relative_eq!(p.t0 * (ln[i] - ln[0]).exp(), *t, max_relative = 1e-10);
    }
}

#[test]
fn cone_limits_are_the_capstan_equation_and_no_gain() {
    let p = MembraneProblem {
        samples: 5,
        ..problem(0.5, 0.0, 3.0)
    };
    let narrow = tension_profile(
        &Obstacle::CircularCone(RightCircularCone::new(1e-6).unwrap()),
        &p,
    )
    .unwrap();
    assert_relative_eq!(
        narrow.tension_ratio(),
        (0.5f64 * 3.0).exp(),
        max_relative = 1e-11
    );
    // alpha -> pi/2: phi = sin(alpha) theta, so the interval must stay inside |theta| < pi/2
    let short = MembraneProblem {
        theta_max: 1.5,
        ..p
    };
    let flat = tension_profile(
        &Obstacle::CircularCone(RightCircularCone::new(FRAC_PI_2 - 1e-6).unwrap()),
        &short,
    )
    .unwrap();
    assert_relative_eq!(flat.tension_ratio(), 1.0, max_relative = 1e-6);
    // monotone in between
    let ratios: Vec<f64> = [0.1, 0.4, 0.8, 1.2, 1.5]
        .iter()
        .map(|&a| {
            tension_profile(
                &Obstacle::CircularCone(RightCircularCone::new(a).unwrap()),
                &short,
            )
            .unwrap()
            .tension_ratio()
        })
        .collect();
    assert!(ratios.windows(2).all(|w| w[0] > w[1]), "{ratios:?}");
}

#[test]
fn cone_past_the_development_limit_is_a_typed_error() {
    let alpha = FRAC_PI_4;
    let limit = FRAC_PI_2 / alpha.sin();
    let p = MembraneProblem {
        samples: 5,
        ..problem(0.5, 0.0, limit + 0.1)
    };
    let e = tension_profile(
        &Obstacle::CircularCone(RightCircularCone::new(alpha).unwrap()),
        &p,
    )
    .unwrap_err();
    match e {
        FrictionError::DevelopmentLimit { angle, .. } => {
            assert_relative_eq!(angle, limit, max_relative = 1e-15)
        }
        other => panic!("{other}"),
    }
    let e = tension_profile(&Obstacle::Cone(cone_from_expressions(alpha)), &p).unwrap_err();
    match e {
        FrictionError::DevelopmentLimit { angle, .. } => {
            assert_relative_eq!(angle, limit, max_relative = 1e-9)
        }
        other => panic!("{other}"),
    }
}

#[test]
fn non_convex_prism_names_the_first_bad_angle() {
    // (sin t + 0.3 sin 3t, cos t): v'u'' - u'v'' = 1 + 2.7 cos^2... changes sign; find it numerically
    let profile = ExpressionProfile::parse("sin(t) + 0.3*sin(3*t)", "cos(t)").unwrap();
    let obstacle = Obstacle::Prism(capstan_geometry::GeneralPrism::new(profile.clone()));
    let p = problem(0.5, -0.2, 1.5);
    let e = tension_profile(&obstacle, &p).unwrap_err();
    let FrictionError::NonPositiveCurvature { angle, .. } = e else {
        panic!("{e}")
    };
    // the first zero of H after -0.2, by the profile's own curvature
    let h = |t: f64| {
        capstan_friction::membrane::ProfilePoint::from_jet(
            capstan_geometry::ProfileCurve::<f64>::profile_jet(&profile, t),
        )
        .turning_rate
    };
    assert!(h(angle - 1e-9) > 0.0 && h(angle + 1e-9) <= 0.0, "{angle}");
    // the ODE path (with weight) reports the same angle
    let heavy = MembraneProblem {
        loads: heavy_fast_belt(),
        t0: 10.0,
        ..p
    };
    let FrictionError::NonPositiveCurvature {
        angle: ode_angle, ..
    } = tension_profile(&obstacle, &heavy).unwrap_err()
    else {
        panic!()
    };
    assert!((ode_angle - angle).abs() < 1e-9);
}

#[test]
fn heavy_membrane_lifts_off_the_bottom_of_a_cylinder() {
    // R = T/a + w cos(theta) < 0 once the light tension cannot hold the weight below the equator
    let obstacle = Obstacle::Cylinder(CircularCylinder::new(1.0).unwrap());
    let loads = weighted_belt(1.0);
    let p = loaded(0.2, 12.0, [0.0, PI], 11, loads);
    let e = tension_profile(&obstacle, &p).unwrap_err();
    let FrictionError::LiftOff { angle, .. } = e else {
        panic!("{e}")
    };
    assert!(angle > FRAC_PI_2 && angle < PI);
    let cg = closed_form::CylinderGravity {
        radius: 1.0,
        mu: 0.2,
        weight_per_length: 9.81,
        speed_tension: 0.0,
    };
    assert!(cg.reaction(angle, cg.tension(12.0, 0.0, angle)).abs() < 1e-9);
    // a light tension goes slack first, on the upper half where gravity pulls towards theta_max
    let light = MembraneProblem { t0: 1.0, ..p };
    let FrictionError::NonPositiveTension { angle: slack, .. } =
        tension_profile(&obstacle, &light).unwrap_err()
    else {
        panic!()
    };
    assert!(slack > 0.0 && slack < FRAC_PI_2);
    assert!(cg.tension(1.0, 0.0, slack).abs() < 1e-9);
    // the ODE finds the same angle
    let FrictionError::LiftOff {
        angle: ode_angle, ..
    } = MembraneEquilibrium::new(&CircularCylinder::new(1.0).unwrap(), p)
        .solve()
        .unwrap_err()
    else {
        panic!()
    };
    assert!((ode_angle - angle).abs() < 1e-8, "{ode_angle} vs {angle}");
    // too fast a belt lifts off at theta0
    let fast = MembraneProblem {
        loads: MembraneLoads {
            density: 1.0,
            speed: 4.0,
            ..Default::default()
        },
        ..p
    }; // rho_l V^2 = 16 > T0 = 12
    assert!(
        matches!(tension_profile(&obstacle, &fast), Err(FrictionError::LiftOff { angle, .. }) if angle == 0.0)
    );
}

#[test]
fn invalid_parameters_name_their_scene_keys() {
    let obstacle = ReferenceEllipse::default().closed_form();
    // each case spoils one field of the default problem
    type Spoil = fn(&mut MembraneProblem);
    let bad: [(&str, Spoil); 7] = [
        ("friction.mu", |p| p.mu = -1.0),
        ("membrane.t0", |p| p.t0 = 0.0),
        ("membrane.theta_max", |p| p.theta_max = -2.0),
        ("membrane.theta0", |p| p.theta0 = f64::NAN),
        ("membrane.samples", |p| p.samples = 1),
        ("loads.density", |p| p.loads.density = -1.0),
        ("loads.speed", |p| p.loads.speed = f64::INFINITY),
    ];
    for (key, spoil) in bad {
        let mut p = MembraneProblem::default();
        spoil(&mut p);
        match tension_profile(&obstacle, &p) {
            Err(FrictionError::InvalidParameter { field, .. }) => assert_eq!(field, key),
            other => panic!("{key}: {other:?}"),
        }
    }
    let cone = Obstacle::CircularCone(RightCircularCone::new(0.3).unwrap());
    let heavy = MembraneProblem {
        loads: heavy_fast_belt(),
        ..Default::default()
    };
    assert!(matches!(
        tension_profile(&cone, &heavy),
        Err(FrictionError::InvalidParameter {
            field: "loads.gravity",
            ..
        })
    ));
}

#[test]
fn infer_mu_inverts_every_forward_model() {
    let (circle, half) = half_turn_of_the_unit_circle();
    let est = infer_mu(&circle, &half, 2.75).unwrap();
    assert_relative_eq!(est.mu, 2.75f64.ln() / PI, max_relative = 1e-15);
    assert_eq!(format!("{:.5}", est.mu), "0.32200");
    let loads = MembraneLoads {
        gravity: 9.81,
        density: 0.2,
        width: 1.0,
        thickness: 0.5,
        speed: 1.0,
    };
    let cases = [
        (
            ReferenceEllipse::default().closed_form(),
            MembraneLoads::default(),
        ),
        (
            ReferenceEllipse::default().expressions(),
            MembraneLoads::default(),
        ),
        (
            wobbly_prism(),
            MembraneLoads {
                speed: 2.0,
                density: 0.1,
                ..Default::default()
            },
        ),
        (circle.clone(), loads),
        (ReferenceEllipse::default().closed_form(), loads),
        (
            Obstacle::CircularCone(RightCircularCone::new(0.4).unwrap()),
            MembraneLoads::default(),
        ),
        (
            Obstacle::Cone(cone_from_expressions(0.4)),
            MembraneLoads::default(),
        ),
    ];
    for (obstacle, loads) in cases {
        let p = loaded(0.37, 3.0, [-0.6, 2.2], 3, loads);
        let t_max = tension_profile(&obstacle, &p).unwrap().t_max();
        let est = infer_mu(&obstacle, &MembraneProblem { mu: 0.0, ..p }, t_max).unwrap();
        assert_relative_eq!(est.mu, 0.37, max_relative = 1e-9);
    }
}

#[test]
fn infer_mu_rejects_impossible_pairs() {
    let (circle, half) = half_turn_of_the_unit_circle();
    assert!(matches!(
        infer_mu(&circle, &half, 0.5),
        Err(FrictionError::TensionRatioBelowOne { .. })
    ));
    assert!(matches!(
        infer_mu(&circle, &half, -1.0),
        Err(FrictionError::InvalidParameter {
            field: "membrane.t_max",
            ..
        })
    ));
    // with weight: below what mu = 0 gives
    let loads = weighted_belt(0.1);
    let p = MembraneProblem {
        t0: 5.0,
        theta0: -FRAC_PI_2,
        theta_max: 0.0,
        loads,
        ..half
    };
    let frictionless = tension_profile(&circle, &MembraneProblem { mu: 0.0, ..p })
        .unwrap()
        .t_max();
    assert!(matches!(
        infer_mu(&circle, &p, 0.9 * frictionless),
        Err(FrictionError::NoFrictionCoefficient { .. })
    ));
}

/// An extra load field enters exactly as Theorem 1's `(0, g_r2, g_r3)`: gravity given as a
/// field equals gravity given as loads.
#[test]
fn gravity_as_a_load_field_equals_gravity_as_loads() {
    let e = EllipticalPrism::new(1.5, 1.0).unwrap();
    let loads = weighted_belt(0.1);
    let p = loaded(0.3, 2.0, [-1.0, 1.0], 9, loads);
    let a = MembraneEquilibrium::new(&e, p).solve().unwrap();
    let field = Gravity {
        weight_per_length: loads.weight_per_length(),
    };
    let closure = |t: f64, g: &SurfaceGeometry<f64>| field.load(t, g);
    let (b, _) = MembraneEquilibrium::new(
        &e,
        MembraneProblem {
            loads: MembraneLoads::default(),
            ..p
        },
    )
    .solve_with(&closure)
    .unwrap();
    assert!(max_relative(&a.tension, &b.tension) <= 1e-15);
}
