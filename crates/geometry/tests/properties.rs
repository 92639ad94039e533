//! Property tests over random parameters and points (fixed seed, bounded domains).
#![allow(clippy::needless_range_loop)] // tensor index loops mirror the formulas

mod common;

use capstan_geometry::ad::surface_jet;
use capstan_geometry::{
    CircularCylinder, EllipticalPrism, ExpressionProfile, GeneralCone, GeneralPrism,
    RightCircularCone, ShellChart, Surface, SurfaceJet,
};
use common::{christoffel_from_metric, max_diff3};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

fn runner(cases: u32) -> TestRunner {
    let config = Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    };
    TestRunner::new_with_rng(config, TestRng::from_seed(RngAlgorithm::ChaCha, &[7; 32]))
}

fn jet_diff(a: &SurfaceJet<f64>, b: &SurfaceJet<f64>) -> f64 {
    let mut m: f64 = 0.0;
    let mut upd = |x: &[f64; 3], y: &[f64; 3]| {
        for c in 0..3 {
            m = m.max((x[c] - y[c]).abs() / (1.0 + y[c].abs()));
        }
    };
    upd(&a.point, &b.point);
    for i in 0..2 {
        upd(&a.d1[i], &b.d1[i]);
        for j in 0..2 {
            upd(&a.d2[i][j], &b.d2[i][j]);
            for k in 0..2 {
                upd(&a.d3[i][j][k], &b.d3[i][j][k]);
            }
        }
    }
    m
}

fn default_jet<S: Surface<f64>>(s: &S, x: [f64; 2]) -> SurfaceJet<f64> {
    surface_jet(|y| s.sigma(y), x)
}

#[test]
fn analytic_fast_paths_agree_with_automatic_derivatives() {
    runner(256)
        .run(
            &(
                0.2..5.0f64,
                0.2..5.0f64,
                -4.0..4.0f64,
                -3.0..3.0f64,
                0.05..1.5f64,
            ),
            |(a, b, x1, t, alpha)| {
                let e = EllipticalPrism::new(a, b).unwrap();
                prop_assert!(jet_diff(&e.jet([x1, t]), &default_jet(&e, [x1, t])) < 1e-14);
                let c = CircularCylinder::new(a).unwrap();
                prop_assert!(jet_diff(&c.jet([x1, t]), &default_jet(&c, [x1, t])) < 1e-14);
                let cone = RightCircularCone::new(alpha).unwrap();
                prop_assert!(jet_diff(&cone.jet([x1, t]), &default_jet(&cone, [x1, t])) < 1e-14);
                Ok(())
            },
        )
        .unwrap();
}

#[test]
fn profile_jets_of_prisms_and_cones_agree_with_surface_ad() {
    runner(64)
        .run(
            &(
                0.5..2.0f64,
                -0.3..0.3f64,
                0.5..2.0f64,
                0.1..3.0f64,
                -3.0..3.0f64,
            ),
            |(a, c, b, x1, t)| {
                let u = format!("{a}*sin(t) + {c}*sin(2*t)");
                let v = format!("{b}*cos(t)");
                let p = ExpressionProfile::parse(&u, &v).unwrap();
                let prism = GeneralPrism::new(p.clone());
                prop_assert!(jet_diff(&prism.jet([x1, t]), &default_jet(&prism, [x1, t])) < 1e-13);
                let cone = GeneralCone::new(p);
                prop_assert!(jet_diff(&cone.jet([x1, t]), &default_jet(&cone, [x1, t])) < 1e-13);
                Ok(())
            },
        )
        .unwrap();
}

#[test]
fn inverse_metric_and_christoffel_identities_hold_on_random_ellipses() {
    runner(64)
        .run(
            &(0.3..4.0f64, 0.3..4.0f64, -3.0..3.0f64, 0.0..1.0f64),
            |(a, b, t, s)| {
                // keep x3 well inside the shell (convex side: any x3 >= 0 is regular)
                let x = [0.0, t, s * a.min(b)];
                let chart = ShellChart::new(EllipticalPrism::new(a, b).unwrap());
                let p = chart.point(x).unwrap();
                for i in 0..3 {
                    for k in 0..3 {
                        let d: f64 = (0..3)
                            .map(|j| p.inverse_metric[i][j] * p.metric[j][k])
                            .sum();
                        let delta = if i == k { 1.0 } else { 0.0 };
                        prop_assert!((d - delta).abs() < 1e-12, "g^ij g_jk = {d} at {i}{k}");
                    }
                }
                let scale = 1.0 + p.christoffel_scale();
                let fd = christoffel_from_metric(&chart, x, 1e-3);
                prop_assert!(max_diff3(&p.christoffel, &fd) < 1e-7 * scale);
                Ok(())
            },
        )
        .unwrap();
}

#[test]
fn random_prisms_and_cones_have_zero_gaussian_curvature() {
    runner(128)
        .run(
            &(
                0.5..2.0f64,
                -0.2..0.2f64,
                0.5..2.0f64,
                0.1..3.0f64,
                -3.0..3.0f64,
            ),
            |(a, c, b, x1, t)| {
                let p = ExpressionProfile::parse(
                    &format!("{a}*sin(t) + {c}*cos(3*t)"),
                    &format!("{b}*cos(t)"),
                )
                .unwrap();
                let kp = GeneralPrism::new(p.clone()).gaussian_curvature([x1, t]);
                let kc = GeneralCone::new(p).gaussian_curvature([x1, t]);
                // a random profile may be singular somewhere: then a typed error, else K = 0
                if let Ok(k) = kp {
                    prop_assert!(k.abs() < 1e-11);
                }
                if let Ok(k) = kc {
                    prop_assert!(k.abs() < 1e-11);
                }
                Ok(())
            },
        )
        .unwrap();
}
