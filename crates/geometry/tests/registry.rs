//! The obstacle registry, and type-erased user obstacles against their concrete types.
//!
//! A user obstacle behind a pointer ([`Obstacle::prism_over`], [`Obstacle::cone_over`],
//! [`Obstacle::surface`]) evaluates `sigma` at a dual number by its Taylor polynomial of order
//! four: exact for every scalar carrying at most four derivatives. Checked here against the
//! concrete type at each scalar the workspace evaluates charts at (f64, the third-order jet,
//! the jet over a dual point) and at the other num-dual types up to order four; a fifth-order
//! scalar is refused.

use capstan_geometry::registry::{self, ParameterValue};
use capstan_geometry::samples::{TROUGH, Trough};
use capstan_geometry::{
    GeneralCone, GeneralPrism, GeometryError, Obstacle, ObstacleSettings, ProfileCurve, Scalar,
    ShellChart, Surface, ad,
};
use num_dual::{Dual, Dual2_64, Dual3, Dual3_64, Dual64, HyperDual64};
use proptest::prelude::*;
use proptest::test_runner::{Config as ProptestConfig, RngSeed};

/// A general surface with every fourth derivative nonzero somewhere.
#[derive(Debug, Clone, Copy)]
struct Wavy;

impl Surface<f64> for Wavy {
    fn sigma<S: Scalar<f64>>(&self, [x1, x2]: [S; 2]) -> [S; 3] {
        [
            x1 + x2 * x2 * x1 * 0.1,
            x2.sin() * 2.0 + x1 * x1 * x1 * x2 * 0.05,
            (x1 * 0.7).cos() * (x2 * 2.0).cos() * 0.3 + x2.cos() * 2.0,
        ]
    }
}

fn close(a: f64, b: f64, what: &str) {
    // different operation order only (Taylor polynomial against AD through sigma): round-off
    assert!(
        (a - b).abs() <= 1e-13 * b.abs().max(1.0),
        "{what}: erased {a:e} against concrete {b:e}"
    );
}

fn flatten(j: &capstan_geometry::SurfaceJet<f64>) -> Vec<f64> {
    let mut v = j.point.to_vec();
    v.extend(j.d1.iter().flatten());
    v.extend(j.d2.iter().flatten().flatten());
    v.extend(j.d3.iter().flatten().flatten().flatten());
    v
}

/// Every scalar type: the erased surface's `sigma` (and what the workspace derives from it)
/// equals the concrete surface's.
fn erased_equals_concrete<C: Surface<f64>>(
    erased: &Obstacle,
    concrete: &C,
    x: [f64; 2],
    dx: [f64; 2],
) {
    // f64
    let (a, b) = (erased.sigma(x), concrete.sigma(x));
    (0..3).for_each(|c| close(a[c], b[c], "sigma at f64"));
    // the third-order jet (Jet3<f64>, Surface::geometry and the shell charts)
    let ja = flatten(&ad::surface_jet(|y| erased.sigma(y), x));
    let jb = flatten(&concrete.jet(x));
    ja.iter()
        .zip(&jb)
        .for_each(|(a, b)| close(*a, *b, "jet through sigma"));
    let je = flatten(&erased.jet(x));
    ja.iter()
        .zip(&je)
        .for_each(|(a, b)| close(*a, *b, "jet against Surface::jet"));
    // the jet over a dual point (Jet3<Dual1<f64>>: ShellChart::point_over, fourth derivatives)
    let y = [ad::seed(x[0], dx[0]), ad::seed(x[1], dx[1])];
    let da = ad::surface_jet_over(|z| erased.sigma(z), y);
    let db = ad::surface_jet_over(|z| concrete.sigma(z), y);
    let parts = |j: &capstan_geometry::SurfaceJet<Dual64>| {
        let mut v = flatten(&capstan_geometry::SurfaceJet {
            point: j.point.map(|d| d.re),
            d1: j.d1.map(|r| r.map(|d| d.re)),
            d2: j.d2.map(|m| m.map(|r| r.map(|d| d.re))),
            d3: j.d3.map(|t| t.map(|m| m.map(|r| r.map(|d| d.re)))),
        });
        v.extend(flatten(&capstan_geometry::SurfaceJet {
            point: j.point.map(|d| d.eps),
            d1: j.d1.map(|r| r.map(|d| d.eps)),
            d2: j.d2.map(|m| m.map(|r| r.map(|d| d.eps))),
            d3: j.d3.map(|t| t.map(|m| m.map(|r| r.map(|d| d.eps)))),
        }));
        v
    };
    parts(&da)
        .iter()
        .zip(&parts(&db))
        .for_each(|(a, b)| close(*a, *b, "jet over a dual point"));
    // the other num-dual types up to order four, along the direction dx
    let along = |f: &dyn Fn(Dual3_64) -> [Dual3_64; 3]| f(Dual3_64::from_re(0.0).derivative());
    let d3a = along(&|t| erased.sigma(line_dual(x, dx, t)));
    let d3b = along(&|t| concrete.sigma(line_dual(x, dx, t)));
    for c in 0..3 {
        close(d3a[c].v1, d3b[c].v1, "Dual3 first");
        close(d3a[c].v2, d3b[c].v2, "Dual3 second");
        close(d3a[c].v3, d3b[c].v3, "Dual3 third");
    }
    let d2a = erased.sigma(line_dual(x, dx, Dual2_64::from_re(0.0).derivative()));
    let d2b = concrete.sigma(line_dual(x, dx, Dual2_64::from_re(0.0).derivative()));
    (0..3).for_each(|c| close(d2a[c].v2, d2b[c].v2, "Dual2 second"));
    let h = HyperDual64::from_re(0.0).derivative1().derivative2();
    let (ha, hb) = (
        erased.sigma(line_dual(x, dx, h)),
        concrete.sigma(line_dual(x, dx, h)),
    );
    (0..3).for_each(|c| close(ha[c].eps1eps2, hb[c].eps1eps2, "HyperDual mixed"));
    // nested first-order duals, four deep (NDERIV = 4): the fourth derivative along dx
    type D4 = Dual<Dual<Dual<Dual64>>>;
    let t = D4::new(
        Dual::new(
            Dual::new(Dual64::new(0.0, 1.0), Dual64::from_re(1.0)),
            Dual::from_re(Dual64::from_re(1.0)),
        ),
        Dual::from_re(Dual::from_re(Dual64::from_re(1.0))),
    );
    let (na, nb) = (
        erased.sigma(line_dual(x, dx, t)),
        concrete.sigma(line_dual(x, dx, t)),
    );
    (0..3).for_each(|c| {
        close(
            na[c].eps.eps.eps.eps,
            nb[c].eps.eps.eps.eps,
            "nested dual fourth",
        )
    });
}

/// The point `x + t dx` at a scalar `t`.
fn line_dual<S: Scalar<f64>>(x: [f64; 2], dx: [f64; 2], t: S) -> [S; 2] {
    [t * dx[0] + x[0], t * dx[1] + x[1]]
}

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: 64,
        rng_seed: RngSeed::Fixed(0x0b57_ac1e),
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn user_obstacles_equal_their_concrete_types(x1 in -2.0..2.0_f64, x2 in -1.5..1.5_f64, d1 in -1.0..1.0_f64, d2 in -1.0..1.0_f64, sag in 0.0..0.9_f64) {
        let (x, dx, profile) = ([x1, x2], [d1, d2], Trough { sag });
        let cone_x = [x1.abs() + 0.2, x2]; // the cone away from its apex
        // Surface::jet is the concrete type's own, bit for bit
        prop_assert_eq!(Obstacle::prism_over(profile).jet(x), GeneralPrism::new(profile).jet(x));
        prop_assert_eq!(Obstacle::cone_over(profile).jet(cone_x), GeneralCone::new(profile).jet(cone_x));
        prop_assert_eq!(Obstacle::surface(Wavy).jet(x), Wavy.jet(x));
        erased_equals_concrete(&Obstacle::prism_over(profile), &GeneralPrism::new(profile), x, dx);
        erased_equals_concrete(&Obstacle::cone_over(profile), &GeneralCone::new(profile), cone_x, dx);
        erased_equals_concrete(&Obstacle::surface(Wavy), &Wavy, x, dx);
    }
}

#[test]
fn shell_point_over_a_user_surface_equals_the_concrete_one() {
    // the exact manufactured forcing's path: fourth derivatives of sigma through point_over
    let x = [ad::seed(0.4, 0.3), ad::seed(-0.7, 1.0), ad::seed(0.2, -0.5)];
    let a = ShellChart::new(Obstacle::surface(Wavy))
        .point_over(x)
        .unwrap();
    let b = ShellChart::new(Wavy).point_over(x).unwrap();
    for i in 0..3 {
        for j in 0..3 {
            close(a.metric[i][j].eps, b.metric[i][j].eps, "d g_ij");
            for k in 0..3 {
                close(
                    a.christoffel[k][i][j].eps,
                    b.christoffel[k][i][j].eps,
                    "d Gamma",
                );
            }
        }
    }
    close(a.sqrt_g.eps, b.sqrt_g.eps, "d sqrt(g)");
}

#[test]
#[should_panic(expected = "exact to derivative order 4")]
fn a_fifth_order_scalar_is_refused_not_truncated() {
    type D5 = Dual3<Dual<Dual64>>; // NDERIV = 3 + 1 + 1
    let erased = Obstacle::surface(Wavy);
    let _ = erased.sigma([D5::from_re(Dual::from_re(Dual64::from_re(0.1))); 2]);
}

#[test]
fn builtins_are_registered_under_their_scene_names() {
    // built-ins first (another test registers one more, in any order)
    assert!(
        registry::names().starts_with("cylinder, ellipse, prism, circular-cone, cone"),
        "{}",
        registry::names()
    );
    assert!(registry::find("torus").is_none());
    assert!(registry::is_parameter("half_angle") && !registry::is_parameter("shape"));
    let ellipse = registry::find("ellipse").unwrap();
    let err = registry::register(*ellipse).unwrap_err();
    assert_eq!(err, GeometryError::DuplicateObstacle { name: "ellipse" });
    let err = registry::build("torus", &ObstacleSettings::new()).unwrap_err();
    assert!(
        err.to_string()
            .contains("cylinder, ellipse, prism, circular-cone, cone"),
        "{err}"
    );
}

#[test]
fn builtins_build_their_variants_and_name_the_key_of_a_bad_value() {
    let with = |k: &str, v: f64| ObstacleSettings::new().with(k, ParameterValue::Number(v));
    assert!(
        matches!(registry::build("cylinder", &with("radius", 1.5)), Ok(Obstacle::Cylinder(c)) if c.radius() == 1.5)
    );
    assert!(
        matches!(registry::build("ellipse", &ObstacleSettings::new()), Ok(Obstacle::Ellipse(e)) if e.a() == 2.0 && e.b() == 2.0)
    );
    assert!(matches!(
        registry::build("prism", &ObstacleSettings::new()),
        Ok(Obstacle::Prism(_))
    ));
    assert!(matches!(
        registry::build("cone", &ObstacleSettings::new()),
        Ok(Obstacle::Cone(_))
    ));
    assert!(matches!(
        registry::build("circular-cone", &ObstacleSettings::new()),
        Ok(Obstacle::CircularCone(_))
    ));
    let err = registry::build("circular-cone", &with("half_angle", 2.0)).unwrap_err();
    assert!(
        matches!(
            err,
            GeometryError::InvalidParameter {
                field: "obstacle.half_angle",
                ..
            }
        ),
        "{err}"
    );
    let err = registry::build(
        "cylinder",
        &ObstacleSettings::new().with("radius", ParameterValue::Expression("2".into())),
    )
    .unwrap_err();
    assert_eq!(err.to_string(), "`obstacle.radius` must be a number");
    let err = registry::build(
        "prism",
        &ObstacleSettings::new().with("u", ParameterValue::Expression("2*sin(".into())),
    )
    .unwrap_err();
    assert!(
        matches!(
            err,
            GeometryError::Expression {
                field: "obstacle.u",
                ..
            }
        ),
        "{err}"
    );
}

#[test]
fn a_user_obstacle_registered_at_run_time_is_found_by_name() {
    registry::register(TROUGH).unwrap();
    assert!(registry::names().ends_with(", trough"));
    assert!(registry::is_parameter("sag"));
    let trough = registry::build("trough", &ObstacleSettings::new()).unwrap();
    assert!(trough.is_prism() && !trough.is_cone());
    // H = (1 + sag)/4 at the top, sag at its default 0.3
    let h = trough.geometry([0.0, 0.0]).unwrap().mean_curvature;
    assert!((h - 0.325).abs() < 1e-15, "{h}");
    let p = trough.profile_jet(0.3).unwrap();
    assert_eq!(p, Trough { sag: 0.3 }.profile_jet(0.3));
    let err = registry::build(
        "trough",
        &ObstacleSettings::new().with("sag", ParameterValue::Number(1.0)),
    )
    .unwrap_err();
    assert!(
        matches!(
            err,
            GeometryError::InvalidParameter {
                field: "obstacle.sag",
                ..
            }
        ),
        "{err}"
    );
}
