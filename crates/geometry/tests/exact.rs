//! Closed-form checks of the geometry layer (round-off level tolerances).
#![allow(clippy::needless_range_loop)] // tensor index loops mirror the formulas

mod common;

use approx::assert_relative_eq;
use capstan_geometry::{
    CircularCylinder, EllipticalPrism, ExpressionProfile, GeneralCone, GeneralPrism, GeometryError,
    Plane, RightCircularCone, ShellChart, Sphere, Surface,
};
use common::{christoffel_from_metric, max_diff3};

fn phi(a: f64, b: f64, t: f64) -> f64 {
    (b * b * t.sin().powi(2) + a * a * t.cos().powi(2)).sqrt()
}

#[test]
fn ellipse_b22_and_mean_curvature_match_closed_form() {
    for &(a, b) in &[(2.0, 1.0), (1.0, 2.0), (2.0, 2.0), (0.3, 5.0)] {
        let e = EllipticalPrism::new(a, b).unwrap();
        for &t in &[-1.5, -0.7, 0.0, 0.3, 1.2, 2.9] {
            let g = e.geometry([0.0, t]).unwrap();
            let p = phi(a, b, t);
            // closed form: round-off only
            assert_relative_eq!(g.second_form[1][1], -a * b / p, max_relative = 1e-13);
            assert_relative_eq!(
                g.mean_curvature,
                a * b / (2.0 * p.powi(3)),
                max_relative = 1e-13
            );
            assert_relative_eq!(g.first_form[1][1], p * p, max_relative = 1e-13);
            assert!(g.gaussian_curvature.abs() < 1e-14);
        }
    }
}

#[test]
fn ellipse_shell_sqrt_g22_matches_closed_form() {
    let (a, b) = (2.0, 1.5);
    let chart = ShellChart::new(EllipticalPrism::new(a, b).unwrap());
    for &t in &[-1.2, 0.0, 0.8] {
        for &x3 in &[0.0, 0.25, 1.0] {
            let p = chart.point([0.0, t, x3]).unwrap();
            let pt = phi(a, b, t);
            let expected = pt + x3 * a * b / (pt * pt);
            assert_relative_eq!(p.metric[1][1].sqrt(), expected, max_relative = 1e-13);
            assert_relative_eq!(p.sqrt_g, expected, max_relative = 1e-13);
            assert!(p.metric[0][1].abs() < 1e-14 && p.metric[1][2].abs() < 1e-14);
            assert_relative_eq!(p.metric[2][2], 1.0, max_relative = 1e-14);
        }
    }
}

#[test]
fn cylinder_christoffel_symbols_are_those_of_polar_coordinates() {
    let radius = 1.7;
    let chart = ShellChart::new(CircularCylinder::new(radius).unwrap());
    for &(t, x3) in &[(0.0, 0.0), (0.9, 0.3), (-2.0, 1.1)] {
        let p = chart.point([0.4, t, x3]).unwrap();
        let r = radius + x3;
        let mut expected = [[[0.0; 3]; 3]; 3];
        expected[2][1][1] = -r; // Gamma^3_22 = -r
        expected[1][1][2] = 1.0 / r; // Gamma^2_23 = 1/r
        expected[1][2][1] = 1.0 / r;
        assert!(
            max_diff3(&p.christoffel, &expected) < 1e-13,
            "{:?}",
            p.christoffel
        );
        assert_relative_eq!(p.metric[1][1], r * r, max_relative = 1e-13);
    }
}

#[test]
fn cone_first_fundamental_form_matches_paper_section_2_2() {
    let profile = ExpressionProfile::parse("0.5*sin(t) + 0.1*sin(2*t)", "0.6*cos(t)").unwrap();
    let cone = GeneralCone::new(profile);
    for &(x1, t) in &[(1.0, 0.2), (2.5, -0.9), (0.4, 1.3)] {
        let (ub, ubp) = (
            0.5 * f64::sin(t) + 0.1 * f64::sin(2.0 * t),
            0.5 * f64::cos(t) + 0.2 * f64::cos(2.0 * t),
        );
        let (vb, vbp) = (0.6 * f64::cos(t), -0.6 * f64::sin(t));
        let (ubpp, vbpp) = (
            -0.5 * f64::sin(t) - 0.4 * f64::sin(2.0 * t),
            -0.6 * f64::cos(t),
        );
        let g = cone.geometry([x1, t]).unwrap();
        let a = g.first_form;
        assert_relative_eq!(a[0][0], 1.0 + ub * ub + vb * vb, max_relative = 1e-13);
        assert_relative_eq!(a[0][1], x1 * (ub * ubp + vb * vbp), max_relative = 1e-12);
        assert_relative_eq!(
            a[1][1],
            x1 * x1 * (ubp * ubp + vbp * vbp),
            max_relative = 1e-13
        );
        let b22 = -x1 * (vbp * ubpp - ubp * vbpp)
            / (ubp * ubp + vbp * vbp + (vb * ubp - ub * vbp).powi(2)).sqrt();
        assert_relative_eq!(g.second_form[1][1], b22, max_relative = 1e-12);
        assert!(g.second_form[0][0].abs() < 1e-14 && g.second_form[0][1].abs() < 1e-14);
        assert!(g.gaussian_curvature.abs() < 1e-13);
    }
}

#[test]
fn right_circular_cone_metric_and_zero_gaussian_curvature() {
    let alpha = 0.35;
    let cone = RightCircularCone::new(alpha).unwrap();
    let g = cone.geometry([2.0, 0.7]).unwrap();
    let k = f64::tan(alpha);
    assert_relative_eq!(g.first_form[0][0], 1.0 + k * k, max_relative = 1e-14);
    assert!(g.first_form[0][1].abs() < 1e-14);
    assert_relative_eq!(g.first_form[1][1], 4.0 * k * k, max_relative = 1e-14);
    assert!(g.gaussian_curvature.abs() < 1e-14);
    assert!(g.mean_curvature > 0.0);
}

#[test]
fn every_prism_and_cone_has_zero_gaussian_curvature() {
    let prism = GeneralPrism::new(
        ExpressionProfile::parse("2*sin(t) + 0.2*sin(2*t)", "1.5*cos(t)").unwrap(),
    );
    let cone =
        GeneralCone::new(ExpressionProfile::parse("sin(t)", "cos(t) + 0.3*cos(3*t)").unwrap());
    let surfaces: Vec<Box<dyn Fn([f64; 2]) -> f64>> = vec![
        Box::new(|x| {
            CircularCylinder::new(1.3)
                .unwrap()
                .gaussian_curvature(x)
                .unwrap()
        }),
        Box::new(|x| {
            EllipticalPrism::new(3.0, 0.5)
                .unwrap()
                .gaussian_curvature(x)
                .unwrap()
        }),
        Box::new(move |x| prism.gaussian_curvature(x).unwrap()),
        Box::new(|x| {
            RightCircularCone::new(1.2)
                .unwrap()
                .gaussian_curvature([x[0] + 1.0, x[1]])
                .unwrap()
        }),
        Box::new(move |x| cone.gaussian_curvature([x[0] + 1.0, x[1]]).unwrap()),
        Box::new(|x| Surface::<f64>::gaussian_curvature(&Plane, x).unwrap()),
    ];
    for k in surfaces {
        for &x in &[[0.0, 0.0], [0.5, 1.0], [1.5, -2.0], [0.1, 3.0]] {
            assert!(k(x).abs() < 1e-12, "K = {} at {x:?}", k(x));
        }
    }
}

#[test]
fn sphere_has_gaussian_curvature_one_over_r_squared() {
    let r = 2.5;
    let s = Sphere::new(r).unwrap();
    for &x in &[[0.3, 0.0], [1.2, 2.0], [2.5, -1.0]] {
        let g = s.geometry(x).unwrap();
        assert_relative_eq!(g.gaussian_curvature, 1.0 / (r * r), max_relative = 1e-13);
        assert_relative_eq!(g.mean_curvature, 1.0 / r, max_relative = 1e-13);
    }
}

#[test]
fn shell_christoffel_symbols_agree_with_metric_formula() {
    let prism = GeneralPrism::new(
        ExpressionProfile::parse("2*sin(t) + 0.2*sin(2*t)", "1.5*cos(t)").unwrap(),
    );
    type Gamma = [[[f64; 3]; 3]; 3];
    type Case = (Box<dyn Fn([f64; 3]) -> (Gamma, Gamma)>, [f64; 3]);
    let charts_and_points: Vec<Case> = vec![
        (
            Box::new(|x| {
                let c = ShellChart::new(EllipticalPrism::new(2.0, 1.0).unwrap());
                (
                    c.point(x).unwrap().christoffel,
                    christoffel_from_metric(&c, x, 1e-3),
                )
            }),
            [0.0, 0.6, 0.4],
        ),
        (
            Box::new(|x| {
                let c = ShellChart::new(Sphere::new(1.5).unwrap());
                (
                    c.point(x).unwrap().christoffel,
                    christoffel_from_metric(&c, x, 1e-3),
                )
            }),
            [0.9, 0.3, 0.2],
        ),
        (
            Box::new(|x| {
                let c = ShellChart::new(GeneralCone::new(
                    ExpressionProfile::parse("0.5*sin(t)", "0.7*cos(t) + 0.05*cos(2*t)").unwrap(),
                ));
                (
                    c.point(x).unwrap().christoffel,
                    christoffel_from_metric(&c, x, 1e-3),
                )
            }),
            [1.5, -0.4, 0.3],
        ),
        (
            Box::new(move |x| {
                let c = ShellChart::new(&prism);
                (
                    c.point(x).unwrap().christoffel,
                    christoffel_from_metric(&c, x, 1e-3),
                )
            }),
            [0.0, 1.1, 0.5],
        ),
    ];
    for (eval, x) in charts_and_points {
        let (exact, from_metric) = eval(x);
        // fourth-order differences with h = 1e-3: truncation ~1e-12, round-off ~1e-12
        assert!(
            max_diff3(&exact, &from_metric) < 1e-8,
            "{exact:?}\nvs\n{from_metric:?}"
        );
        for k in 0..3 {
            for i in 0..3 {
                for j in 0..3 {
                    assert_eq!(exact[k][i][j], exact[k][j][i]);
                }
            }
        }
    }
}

#[test]
fn bad_parameters_are_typed_errors() {
    assert!(matches!(
        EllipticalPrism::new(-1.0, 1.0),
        Err(GeometryError::InvalidParameter {
            field: "obstacle.a",
            ..
        })
    ));
    assert!(matches!(
        EllipticalPrism::new(1.0, f64::NAN),
        Err(GeometryError::InvalidParameter {
            field: "obstacle.b",
            ..
        })
    ));
    assert!(matches!(
        CircularCylinder::new(0.0),
        Err(GeometryError::InvalidParameter {
            field: "obstacle.radius",
            ..
        })
    ));
    assert!(matches!(
        CircularCylinder::new(f64::INFINITY),
        Err(GeometryError::InvalidParameter { .. })
    ));
    assert!(matches!(
        RightCircularCone::new(std::f64::consts::FRAC_PI_2),
        Err(GeometryError::InvalidParameter {
            field: "obstacle.half_angle",
            ..
        })
    ));
    assert!(matches!(
        Sphere::new(-2.0),
        Err(GeometryError::InvalidParameter { .. })
    ));
}

#[test]
fn degenerate_parametrisations_are_typed_errors_not_nan() {
    // zero tangent: u = v = const
    let flat = GeneralPrism::new(ExpressionProfile::parse("1", "2").unwrap());
    assert!(matches!(
        flat.geometry([0.0, 0.3]),
        Err(GeometryError::Degenerate { .. })
    ));
    // cusp: u = t^3, v = t^2 has u' = v' = 0 at t = 0
    let cusp = GeneralPrism::new(ExpressionProfile::parse("t^3", "t^2").unwrap());
    assert!(matches!(
        cusp.geometry([0.0, 0.0]),
        Err(GeometryError::Degenerate { .. })
    ));
    // the apex of a cone
    let cone = RightCircularCone::new(0.5).unwrap();
    assert!(matches!(
        cone.geometry([0.0, 0.3]),
        Err(GeometryError::Degenerate { .. })
    ));
    // sphere pole
    let s = Sphere::new(1.0).unwrap();
    assert!(matches!(
        s.geometry([0.0, 0.3]),
        Err(GeometryError::Degenerate { .. })
    ));
    // non-finite: ln of a negative number
    let bad = GeneralPrism::new(ExpressionProfile::parse("ln(t)", "t").unwrap());
    assert!(matches!(
        bad.geometry([0.0, -1.0]),
        Err(GeometryError::NonFinite { .. })
    ));
    // shell past the focal surface under a cylinder of radius 1
    let chart = ShellChart::new(CircularCylinder::new(1.0).unwrap());
    assert!(matches!(
        chart.point([0.0, 0.0, -1.0]),
        Err(GeometryError::Degenerate { .. })
    ));
    assert!(matches!(
        chart.point([0.0, 0.0, -2.0]),
        Err(GeometryError::Degenerate { .. })
    ));
}
