//! Obstacles registered at run time, named from scenes: the same numbers as the equivalent
//! expression obstacle (the general method of the class either way), their keys known and
//! validated, and the paper's keys unchanged.

use capstan::geometry::registry::{self, ObstacleParameter, ParameterDefault, RegisteredObstacle};
use capstan::geometry::samples::TROUGH;
use capstan::geometry::{Obstacle, ProfileCurve, Scalar, Surface};
use capstan::{Scene, commands};

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
        registry::register(TROUGH).unwrap();
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

/// The trough with sag 0.4 and the expression prism of the same curve, with `common` settings.
fn trough_and_prism(common: &[&str]) -> (Scene, Scene) {
    let both = [
        vec!["obstacle.shape=trough", "obstacle.sag=0.4"],
        vec![
            "obstacle.shape=prism",
            "obstacle.u=2*sin(t)",
            "obstacle.v=2*cos(t) - 0.4*sin(t)^2",
        ],
    ]
    .map(|mut sets| {
        sets.extend(common);
        scene(&sets).unwrap()
    });
    let [a, b] = both;
    (a, b)
}

/// Both tension profiles: the same method on the same curve, compiled against interpreted,
/// so equal to round-off.
fn same_tension(a: &Scene, b: &Scene, method: &str) {
    let (a, b) = (
        commands::tension::report(a).unwrap(),
        commands::tension::report(b).unwrap(),
    );
    assert_eq!((a.method, b.method), (method, method));
    assert_eq!(a.theta, b.theta);
    for (x, y) in a.tension.iter().zip(&b.tension) {
        assert!((x - y).abs() <= 1e-12 * y, "{x} against {y}");
    }
}

#[test]
fn a_registered_trough_gives_the_tension_of_the_equivalent_expression_prism() {
    let (trough, prism) = trough_and_prism(&["membrane.theta0=-0.6", "membrane.theta_max=1.0"]);
    same_tension(&trough, &prism, "quadrature");
    // with weight: the ODE of Theorem 1, the same steps on both
    let weighted = |s: Scene| {
        s.with_raw("loads.gravity", "9.81", "t")
            .and_then(|s| s.with_raw("loads.density", "0.05", "t"))
            .unwrap()
    };
    same_tension(&weighted(trough), &weighted(prism), "ode");
}

#[test]
fn a_registered_trough_gives_the_implied_mu_of_the_equivalent_expression_prism() {
    use commands::infer_mu::{FrictionModel, report_for};
    let wrap = [
        "membrane.theta0=-0.6",
        "membrane.theta_max=1.0",
        "membrane.t_max=1.6",
    ];
    let (trough, prism) = trough_and_prism(&wrap);
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
    let user = scene(&[
        "obstacle.shape=wobbly-cone",
        "obstacle.wobble=0.03",
        "membrane.theta0=-1.0",
        "membrane.theta_max=1.5",
    ]);
    let expression = scene(&[
        "obstacle.shape=cone",
        "obstacle.ubar=0.25*sin(t) + 0.03*sin(2*t)",
        "obstacle.vbar=0.25*cos(t)",
        "membrane.theta0=-1.0",
        "membrane.theta_max=1.5",
    ]);
    same_tension(&user.unwrap(), &expression.unwrap(), "quadrature");
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
