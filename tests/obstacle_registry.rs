//! Obstacles registered at run time, named from scenes: the same numbers as the equivalent
//! expression obstacle (the general method of the class either way), their keys known and
//! validated, and the paper's keys unchanged.

use capstan::geometry::registry::{self, ObstacleParameter, ParameterDefault, RegisteredObstacle};
use capstan::geometry::{Obstacle, ProfileCurve, Scalar, Surface};
use capstan::{Scene, commands};

/// `(2 sin t, 2 cos t - sag sin^2 t)`, the profile of `obstacle.shape = "trough"`.
#[derive(Debug, Clone, Copy)]
struct Trough {
    sag: f64,
}

impl ProfileCurve<f64> for Trough {
    fn profile<S: Scalar<f64>>(&self, t: S) -> [S; 2] {
        let s = t.sin();
        [s * 2.0, t.cos() * 2.0 - s * s * self.sag]
    }
}

/// `(0.25 sin t + w sin 2t, 0.25 cos t)`: the cross-section of `obstacle.shape = "wobbly-cone"`.
#[derive(Debug, Clone, Copy)]
struct WobblyCone {
    wobble: f64,
}

impl ProfileCurve<f64> for WobblyCone {
    fn profile<S: Scalar<f64>>(&self, t: S) -> [S; 2] {
        [
            t.sin() * 0.25 + (t * 2.0).sin() * self.wobble,
            t.cos() * 0.25,
        ]
    }
}

/// `(x1, x2, -x2^2/2)` as a general surface: no prism structure declared.
#[derive(Debug, Clone, Copy)]
struct Parabolic;

impl Surface<f64> for Parabolic {
    fn sigma<S: Scalar<f64>>(&self, [x1, x2]: [S; 2]) -> [S; 3] {
        [x1, x2, x2 * x2 * (-0.5)]
    }
}

fn register() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        registry::register(RegisteredObstacle {
            name: "trough",
            summary: "a circle of radius 2 whose top sags by obstacle.sag",
            parameters: &[ObstacleParameter {
                key: "sag",
                default: ParameterDefault::Number(0.3),
                allowed: "[0, 1)",
            }],
            build: |s| {
                let sag = registry::check("obstacle.sag", s.number("sag")?, "[0, 1)", |c| {
                    (0.0..1.0).contains(&c)
                })?;
                Ok(Obstacle::prism_over(Trough { sag }))
            },
        })
        .unwrap();
        registry::register(RegisteredObstacle {
            name: "wobbly-cone",
            summary: "a cone whose cross-section wobbles by obstacle.wobble",
            parameters: &[ObstacleParameter {
                key: "wobble",
                default: ParameterDefault::Number(0.02),
                allowed: "[0, 0.05]",
            }],
            build: |s| {
                let wobble =
                    registry::check("obstacle.wobble", s.number("wobble")?, "[0, 0.05]", |w| {
                        (0.0..=0.05).contains(&w)
                    })?;
                Ok(Obstacle::cone_over(WobblyCone { wobble }))
            },
        })
        .unwrap();
        registry::register(RegisteredObstacle {
            name: "parabolic",
            summary: "the parabolic cylinder (x1, x2, -x2^2/2) as a general surface",
            parameters: &[],
            build: |_| Ok(Obstacle::surface(Parabolic)),
        })
        .unwrap();
    });
}

fn scene(sets: &[&str]) -> Result<Scene, capstan::CliError> {
    register();
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    Scene::from_toml_str("", "test", &sets)
}

fn same_profile(a: &commands::tension::TensionReport, b: &commands::tension::TensionReport) {
    assert_eq!(a.method, b.method);
    assert_eq!(a.theta, b.theta);
    for (x, y) in a.tension.iter().zip(&b.tension) {
        // the same method on the same curve, compiled against interpreted: round-off only
        assert!((x - y).abs() <= 1e-12 * y, "{x} against {y}");
    }
}

#[test]
fn a_registered_trough_gives_the_tension_of_the_equivalent_expression_prism() {
    let wrap = ["membrane.theta0=-0.6", "membrane.theta_max=1.0"];
    let trough =
        scene(&[&["obstacle.shape=trough", "obstacle.sag=0.4"][..], &wrap].concat()).unwrap();
    let prism = scene(
        &[
            &[
                "obstacle.shape=prism",
                "obstacle.u=2*sin(t)",
                "obstacle.v=2*cos(t) - 0.4*sin(t)^2",
            ][..],
            &wrap,
        ]
        .concat(),
    )
    .unwrap();
    let (a, b) = (
        commands::tension::report(&trough).unwrap(),
        commands::tension::report(&prism).unwrap(),
    );
    assert_eq!(a.method, "quadrature");
    same_profile(&a, &b);
    // with weight: the ODE of Theorem 1, the same steps on both
    let (trough, prism) = (
        trough
            .with_raw("loads.gravity", "9.81", "t")
            .unwrap()
            .with_raw("loads.density", "0.05", "t")
            .unwrap(),
        prism
            .with_raw("loads.gravity", "9.81", "t")
            .unwrap()
            .with_raw("loads.density", "0.05", "t")
            .unwrap(),
    );
    let (a, b) = (
        commands::tension::report(&trough).unwrap(),
        commands::tension::report(&prism).unwrap(),
    );
    assert_eq!(a.method, "ode");
    same_profile(&a, &b);
}

#[test]
fn a_registered_trough_gives_the_implied_mu_of_the_equivalent_expression_prism() {
    use commands::infer_mu::{FrictionModel, report_for};
    let common = [
        "membrane.theta0=-0.6",
        "membrane.theta_max=1.0",
        "membrane.t_max=1.6",
    ];
    let trough =
        scene(&[&["obstacle.shape=trough", "obstacle.sag=0.4"][..], &common].concat()).unwrap();
    let prism = scene(
        &[
            &[
                "obstacle.shape=prism",
                "obstacle.u=2*sin(t)",
                "obstacle.v=2*cos(t) - 0.4*sin(t)^2",
            ][..],
            &common,
        ]
        .concat(),
    )
    .unwrap();
    for model in [FrictionModel::Capstan, FrictionModel::Membrane] {
        let (a, b) = (
            report_for(&trough, model).unwrap(),
            report_for(&prism, model).unwrap(),
        );
        assert!(
            (a.mu - b.mu).abs() <= 1e-12 * b.mu,
            "{model:?}: {} against {}",
            a.mu,
            b.mu
        );
        assert_eq!(a.method, b.method);
    }
}

#[test]
fn a_registered_cone_gives_the_tension_of_the_equivalent_expression_cone() {
    let wrap = ["membrane.theta0=-1.0", "membrane.theta_max=1.5"];
    let user = scene(
        &[
            &["obstacle.shape=wobbly-cone", "obstacle.wobble=0.03"][..],
            &wrap,
        ]
        .concat(),
    )
    .unwrap();
    let expression = scene(
        &[
            &[
                "obstacle.shape=cone",
                "obstacle.ubar=0.25*sin(t) + 0.03*sin(2*t)",
                "obstacle.vbar=0.25*cos(t)",
            ][..],
            &wrap,
        ]
        .concat(),
    )
    .unwrap();
    let (a, b) = (
        commands::tension::report(&user).unwrap(),
        commands::tension::report(&expression).unwrap(),
    );
    same_profile(&a, &b);
}

#[test]
fn registered_keys_are_known_and_validated_by_building() {
    let err = scene(&["obstacle.shape=trough", "obstacle.sag=1.5"])
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("obstacle.sag") && err.contains("[0, 1)"),
        "{err}"
    );
    let err = scene(&["obstacle.sags=0.5"]).unwrap_err().to_string();
    assert!(err.contains("obstacle.sags"), "{err}");
    let err = scene(&["obstacle.shape=torus"]).unwrap_err().to_string();
    assert!(
        err.contains("obstacle.shape") && err.contains("trough") && err.contains("circular-cone"),
        "{err}"
    );
    // a scene names the shape and the key; written back, it reads the same
    let s = scene(&["obstacle.shape=trough", "obstacle.sag=0.25"]).unwrap();
    let text = toml::to_string(&s).unwrap();
    assert!(
        text.contains("shape = \"trough\"") && text.contains("sag = 0.25"),
        "{text}"
    );
    assert_eq!(Scene::from_toml_str(&text, "again", &[]).unwrap(), s);
}

#[test]
fn a_general_user_surface_is_refused_by_the_membrane_but_has_its_geometry() {
    let s = scene(&["obstacle.shape=parabolic"]).unwrap();
    let err = commands::tension::report(&s).unwrap_err().to_string();
    assert!(err.contains("prism or a cone"), "{err}");
    let g = s.obstacle.build().unwrap().geometry([0.0, 0.0]).unwrap();
    assert!((g.mean_curvature - 0.5).abs() < 1e-15);
}

#[test]
fn the_paper_obstacles_keep_their_keys_and_defaults() {
    // the registered defaults are the scene's defaults (one source of truth for each key)
    let spec = Scene::default().obstacle;
    let settings = spec.settings().unwrap();
    for name in ["cylinder", "ellipse", "prism", "circular-cone", "cone"] {
        let o = registry::find(name).unwrap();
        for p in o.parameters {
            let expected: registry::ParameterValue = p.default.into();
            assert_eq!(
                settings.get(p.key),
                Some(&expected),
                "{name}: obstacle.{}",
                p.key
            );
        }
    }
    assert_eq!(spec.shape, "ellipse");
}
