//! Fuzzing the scene parser and the expression evaluator with proptest: arbitrary TOML-ish
//! text and `--set` strings through [`Scene::load`], arbitrary expressions through
//! [`Expression::parse`], `eval` and `check_finite_on`. Nothing may panic or hang; a scene
//! that loads has passed validation, so its numbers are finite.
//!
//! Bounded for CI: 2000 cases per property from a fixed seed (a few seconds in the dev profile).

use std::path::PathBuf;

use capstan::scene::Scene;
use capstan_geometry::expression::Expression;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

fn config() -> Config {
    Config {
        cases: 2000,
        rng_seed: RngSeed::Fixed(0x5eed_cafe),
        failure_persistence: None,
        ..Config::default()
    }
}

const SECTIONS: &[&str] = &[
    "obstacle",
    "friction",
    "membrane",
    "loads",
    "body",
    "grid",
    "solver",
    "discretisation",
    "bogus",
    "",
];
const KEYS: &[&str] = &[
    "shape",
    "radius",
    "a",
    "b",
    "half_angle",
    "u",
    "v",
    "ubar",
    "vbar",
    "law",
    "mu",
    "eps",
    "t0",
    "theta0",
    "theta_max",
    "samples",
    "t_max",
    "gravity",
    "density",
    "width",
    "thickness",
    "speed",
    "tau0",
    "tau_max",
    "young",
    "poisson",
    "n2",
    "n3",
    "linear",
    "nonlinear",
    "method",
    "volumetric",
    "x",
];
const VALUES: &[&str] = &[
    "0",
    "-1",
    "1",
    "2.5",
    "1e308",
    "-1e-308",
    "nan",
    "inf",
    "-inf",
    "+inf",
    "3",
    "4",
    "251",
    "9223372036854775807",
    "99999999999999999999",
    "1e400",
    "0.4999",
    "0.5",
    "\"ellipse\"",
    "\"prism\"",
    "\"cone\"",
    "\"circular-cone\"",
    "\"cylinder\"",
    "\"2*sin(t)\"",
    "\"ln(t)\"",
    "\"sqrt(t)\"",
    "\"1/0\"",
    "\"t^t^t^t\"",
    "\"fem-q2\"",
    "\"reduced\"",
    "\"lu\"",
    "true",
    "[1, 2]",
    "{ a = 1 }",
    "\"\"",
    "'lit'",
    "1979-05-27",
    "0x10",
    "1_000",
];

/// A line of TOML-ish text: a header, an assignment, a comment, or noise.
fn line() -> impl Strategy<Value = String> {
    prop_oneof![
        prop::sample::select(SECTIONS).prop_map(|s| format!("[{s}]")),
        (prop::sample::select(KEYS), prop::sample::select(VALUES))
            .prop_map(|(k, v)| format!("{k} = {v}")),
        (
            prop::sample::select(SECTIONS),
            prop::sample::select(KEYS),
            prop::sample::select(VALUES)
        )
            .prop_map(|(s, k, v)| format!("{s}.{k} = {v}")),
        "[ -~]{0,40}",
        "\\PC{0,20}",
        Just("# comment".to_string()),
        Just(String::new()),
    ]
}

fn set_string() -> impl Strategy<Value = String> {
    prop_oneof![
        (
            prop::sample::select(SECTIONS),
            prop::sample::select(KEYS),
            prop_oneof![
                prop::sample::select(VALUES).prop_map(str::to_string),
                "[ -~]{0,20}"
            ]
        )
            .prop_map(|(s, k, v)| format!("{s}.{k}={v}")),
        "[ -~]{0,30}",
        "\\PC{0,20}",
    ]
}

fn scratch_file() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("capstan-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join("scene.toml")
}

/// A loaded scene has finite numbers everywhere (validation passed).
fn assert_finite(s: &Scene) {
    for x in [
        s.obstacle.radius,
        s.obstacle.a,
        s.obstacle.b,
        s.obstacle.half_angle,
        s.friction.mu,
        s.friction.eps,
        s.membrane.t0,
        s.membrane.theta0,
        s.membrane.theta_max,
        s.loads.gravity,
        s.loads.tau0,
        s.loads.tau_max,
        s.body.thickness,
        s.body.young,
        s.body.poisson,
    ] {
        assert!(x.is_finite(), "{s:?}");
    }
}

/// Tokens of the expression language plus noise.
fn expression() -> impl Strategy<Value = String> {
    let token = prop_oneof![
        prop::sample::select(
            &[
                "t", "1", "2.5", "1e308", "0", "pi", "e", "+", "-", "*", "/", "^", "(", ")", ",",
                "sin(", "cos(", "tan(", "exp(", "ln(", "sqrt(", "abs(", "sinh(", "cosh(", "tanh(",
                "atan(", "atan2(", "x", " ", "1e-320", "9e99999",
            ][..]
        )
        .prop_map(str::to_string),
        "[ -~]{1,3}",
    ];
    prop::collection::vec(token, 0..40).prop_map(|v| v.concat())
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn scene_load_never_panics_on_arbitrary_text(
        lines in prop::collection::vec(line(), 0..12),
        sets in prop::collection::vec(set_string(), 0..3),
    ) {
        let path = scratch_file();
        std::fs::write(&path, lines.join("\n")).unwrap();
        if let Ok(scene) = Scene::load(Some(&path), &sets) {
            assert_finite(&scene);
        }
    }

    #[test]
    fn set_strings_never_panic(sets in prop::collection::vec(set_string(), 0..6)) {
        if let Ok(scene) = Scene::load(None, &sets) {
            assert_finite(&scene);
        }
    }

    #[test]
    fn expressions_never_panic(src in expression(), t in -1e3f64..1e3, wide in any::<bool>()) {
        if let Ok(e) = Expression::parse(&src) {
            let _ = e.eval(t);
            let (a, b) = if wide { (-1e300, 1e300) } else { (t, t + 1.0) };
            let _ = e.check_finite_on(a, b, 33);
            prop_assert_eq!(e.source(), src.as_str());
        }
    }
}

#[test]
fn deep_nesting_and_long_input_are_refused_not_overflowed() {
    assert!(Expression::parse(&("(".repeat(100_000) + "t" + &")".repeat(100_000))).is_err());
    assert!(Expression::parse(&"-".repeat(10_000)).is_err());
    assert!(Expression::parse(&"sin(".repeat(5_000)).is_err());
    let path = scratch_file();
    std::fs::write(&path, "[".repeat(100_000)).unwrap();
    assert!(Scene::load(Some(&path), &[]).is_err());
    std::fs::write(&path, format!("a = {}", "[".repeat(50_000))).unwrap();
    assert!(Scene::load(Some(&path), &[]).is_err());
}
