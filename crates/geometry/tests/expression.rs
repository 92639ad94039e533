//! Public behaviour of `capstan_geometry::expression`: values, exact derivatives, errors,
//! and robustness against arbitrary input.

use approx::assert_relative_eq;
use capstan_geometry::expression::{Expression, ExpressionError, MAX_DEPTH, MAX_LENGTH};
use num_dual::{Dual2_64, Dual3_64, Dual64, HyperDual64};
use proptest::prelude::*;
use proptest::test_runner::RngSeed;

fn parse(src: &str) -> Expression {
    Expression::parse(src).unwrap_or_else(|e| panic!("`{src}` should parse: {e}"))
}

/// Points on `[-2.5, 2.5]` avoiding the integers (and hence 0).
const GRID: [f64; 8] = [-2.3, -1.7, -0.9, -0.35, 0.15, 0.6, 1.25, 2.45];

// ---------------------------------------------------------------- values

#[test]
fn values_match_closures() {
    type Case = (&'static str, fn(f64) -> f64);
    let cases: &[Case] = &[
        ("2*sin(t) + 0.2*sin(2*t)", |t| {
            2.0 * t.sin() + 0.2 * (2.0 * t).sin()
        }),
        ("1 + 2*t", |t| 1.0 + 2.0 * t),
        ("1 + 2*t^2", |t| 1.0 + 2.0 * (t * t)),
        ("(1 + 2)*t", |t| 3.0 * t),
        ("t - 1 - 2", |t| (t - 1.0) - 2.0),
        ("t - (1 - 2)", |t| t + 1.0),
        ("1 - t - t", |t| (1.0 - t) - t),
        ("t / 2 / 3", |t| (t / 2.0) / 3.0),
        ("t / (2 / 3)", |t| t / (2.0 / 3.0)),
        ("1 / t / t", |t| (1.0 / t) / t),
        ("t * t / t * t", |t| ((t * t) / t) * t),
        ("2^3^2 + t", |t| 512.0 + t),
        ("(2^3)^2 + t", |t| 64.0 + t),
        ("-t^2", |t| -(t * t)),
        ("(-t)^2", |t| t * t),
        ("-2^2 * t", |t| -4.0 * t),
        ("2 * -t", |t| -2.0 * t),
        ("t - -t", |t| t + t),
        ("+t", |t| t),
        ("--t", |t| t),
        ("-(t + 1)", |t| -(t + 1.0)),
        ("t^-2", |t| t.powi(-2)),
        ("t^3", |t| t.powi(3)),
        ("t^2^2", |t| t.powi(4)),
        ("-t^-1", |t| -(t.powi(-1))),
        ("2^-t", |t| (-t * 2f64.ln()).exp()),
        ("2^-t^2", |t| (-(t * t) * 2f64.ln()).exp()),
        ("e^t", |t| t.exp()),
        ("pi*t + e", |t| {
            std::f64::consts::PI * t + std::f64::consts::E
        }),
        ("2*pi/4 * t", |t| std::f64::consts::FRAC_PI_2 * t),
        ("sin(t)*cos(t) + tan(t/3)", |t| {
            t.sin() * t.cos() + (t / 3.0).tan()
        }),
        ("exp(-t^2)", |t| (-(t * t)).exp()),
        ("exp(t) - ln(1 + t^2)", |t| t.exp() - (1.0 + t * t).ln()),
        ("sqrt(1 + t^2)", |t| (1.0 + t * t).sqrt()),
        ("sqrt(abs(t))", |t| t.abs().sqrt()),
        ("sinh(t) + cosh(t) - tanh(t)", |t| {
            t.sinh() + t.cosh() - t.tanh()
        }),
        ("atan(t) * 4", |t| t.atan() * 4.0),
        ("(1 + t)*(1 - t)/(2 + t^2)", |t| {
            (1.0 + t) * (1.0 - t) / (2.0 + t * t)
        }),
        ("  2 *\n\tsin ( t )  ", |t| 2.0 * t.sin()),
        ("2e-1*t + .5 + 1E1 + 3. + 1e+1 + 1.e1", |t| 0.2 * t + 33.5),
        ("sin(sin(sin(t)))", |t| t.sin().sin().sin()),
        ("cos(2*pi*t)^2 + sin(2*pi*t)^2", |t| {
            let x = 2.0 * std::f64::consts::PI * t;
            x.cos() * x.cos() + x.sin() * x.sin()
        }),
        ("t*t*t - t^3 + 1", |t| t * t * t - t.powi(3) + 1.0),
        ("1/(1 + exp(-t))", |t| 1.0 / (1.0 + (-t).exp())),
    ];
    for (src, f) in cases {
        let e = parse(src);
        for t in GRID {
            // Same operations in the same order as the closure: round-off differences only.
            assert_relative_eq!(e.eval(t), f(t), max_relative = 1e-15, epsilon = 1e-300);
        }
    }
}

#[test]
fn powers_of_positive_bases_match_closures() {
    type Case = (&'static str, fn(f64) -> f64);
    let cases: &[Case] = &[
        ("t^2.5", |t| t.powf(2.5)),
        ("t^0.5", |t| t.powf(0.5)),
        ("t^t", |t| (t * t.ln()).exp()), // documented as exp(b ln a)
        ("(t + 1)^(t / 2)", |t| (t / 2.0 * (t + 1.0).ln()).exp()),
        ("t^1025", |t| t.powf(1025.0)),
        ("ln(t)", |t| t.ln()),
        ("sqrt(t)", |t| t.sqrt()),
    ];
    for (src, f) in cases {
        let e = parse(src);
        for t in [0.15, 0.6, 1.0, 1.25, 2.45] {
            // Same operations in the same order as the closure: round-off differences only.
            assert_relative_eq!(e.eval(t), f(t), max_relative = 1e-15);
        }
    }
}

#[test]
fn constant_expressions_evaluate_to_the_folded_constant() {
    assert_eq!(parse("2^3^2").eval(0.0_f64), 512.0);
    assert_eq!(parse("-2^2").eval(0.0_f64), -4.0);
    assert_eq!(parse("(-2)^2").eval(0.0_f64), 4.0);
    assert_eq!(parse("(-2)^3").eval(7.0_f64), -8.0); // integer exponent: powi, negative base fine
    assert_eq!(parse("sqrt(4) + ln(1)").eval(-3.0_f64), 2.0);
    assert_eq!(parse("pi").eval(1.0_f64), std::f64::consts::PI);
    // A constant carries no derivative.
    let d = parse("2*pi").eval(Dual64::from(0.3).derivative());
    assert_eq!((d.re, d.eps), (2.0 * std::f64::consts::PI, 0.0));
}

#[test]
fn negative_bases_with_integer_exponents_are_exact() {
    // exact up to the rounding of the product order: the optimiser may fold a constant
    // `powi` differently from the evaluator's loop (1 ulp seen with --release)
    let ulps = 4.0 * f64::EPSILON;
    for t in [-2.5_f64, -1.0, -0.3] {
        assert_relative_eq!(parse("t^3").eval(t), t.powi(3), max_relative = ulps);
        assert_relative_eq!(parse("t^-3").eval(t), t.powi(-3), max_relative = ulps);
        assert_relative_eq!(parse("t^2").eval(t), t * t, max_relative = ulps);
        assert!(parse("t^2.5").eval(t).is_nan()); // fractional power of a negative number
    }
}

#[test]
fn fractional_power_of_zero_has_the_f64_value_on_dual_numbers() {
    // num-dual's `powf` forms `x^(c-3) x^3`, `inf * 0` at 0; the evaluator takes
    // `exp(c ln x)` there (issue 18's fuzzing). The derivatives at 0 stay non-finite.
    let e = parse("t^2.5");
    assert_eq!(e.eval(0.0_f64), 0.0);
    assert_eq!(e.eval(Dual64::from(0.0).derivative()).re, 0.0);
    assert!(e.check_finite_on(0.0, 1.0, 2).is_err());
}

#[test]
fn f32_evaluation_matches_f32_closure() {
    let e = parse("2*sin(t) + 0.2*sin(2*t)");
    for t in [-1.5_f32, 0.25, 2.0] {
        let exact = 2.0 * t.sin() + 0.2 * (2.0 * t).sin();
        assert_relative_eq!(e.eval(t), exact, max_relative = 1e-6); // f32 round-off
    }
}

#[test]
fn float_literal_arguments_infer_f64() {
    assert_eq!(parse("t + 1").eval(0.5), 1.5);
}

#[test]
fn display_returns_the_source_and_reparses_equal() {
    for src in ["2*sin(t) + 0.2*sin(2*t)", "  -t^2 ", "e^(t/2)", "1"] {
        let e = parse(src);
        assert_eq!(e.to_string(), src);
        assert_eq!(e.source(), src);
        assert_eq!(parse(&e.to_string()), e);
        assert_eq!(src.parse::<Expression>().unwrap(), e);
    }
    assert_ne!(parse("t+1"), parse("t + 1")); // equality is equality of source texts
}

#[test]
fn nesting_up_to_the_limit_evaluates() {
    let parens = format!("{}t{}", "(".repeat(MAX_DEPTH), ")".repeat(MAX_DEPTH));
    assert_eq!(parse(&parens).eval(0.7_f64), 0.7);
    let sines = format!("{}t{}", "sin(".repeat(MAX_DEPTH), ")".repeat(MAX_DEPTH));
    let iterated = (0..MAX_DEPTH).fold(0.7_f64, |x, _| x.sin());
    assert_eq!(parse(&sines).eval(0.7_f64), iterated);
    let signs = format!("{}t", "-".repeat(MAX_DEPTH));
    assert_eq!(parse(&signs).eval(0.7_f64), 0.7); // an even number of minus signs
    // Right-nested sums keep many values on the stack at once.
    let sums = format!(
        "{}t{}",
        "(t + ".repeat(MAX_DEPTH - 1),
        ")".repeat(MAX_DEPTH - 1)
    );
    assert_relative_eq!(parse(&sums).eval(0.5_f64), 32.0, max_relative = 1e-15);
    let towers = format!("{}1", "t^".repeat(MAX_DEPTH));
    assert_eq!(parse(&towers).eval(1.0_f64), 1.0);
}

#[test]
fn longest_accepted_input_evaluates() {
    let src = format!("{} ", "t+".repeat(MAX_LENGTH / 2 - 1) + "t");
    assert_eq!(src.len(), MAX_LENGTH);
    assert_eq!(parse(&src).eval(1.0_f64), (MAX_LENGTH / 2) as f64);
}

// ---------------------------------------------------------------- derivatives

/// Value and first three derivatives of `src` at `t`, from every dual number type, checked
/// against `exact = [f, f', f'', f''']` (each dual number propagates exact derivatives, so
/// only round-off separates them from the closed form).
fn check_derivatives(src: &str, t: f64, exact: [f64; 4]) {
    let e = parse(src);
    let tol = 1e-13;
    let close = |got: f64, want: f64, what: &str| {
        assert!(
            (got - want).abs() <= tol * want.abs().max(1e-300) || got == want,
            "{what} of `{src}` at t = {t}: got {got}, want {want}"
        );
    };
    close(e.eval(t), exact[0], "f64 value");

    let d1 = e.eval(Dual64::from(t).derivative());
    close(d1.re, exact[0], "Dual64 value");
    close(d1.eps, exact[1], "Dual64 f'");

    let d2 = e.eval(Dual2_64::from(t).derivative());
    close(d2.re, exact[0], "Dual2 value");
    close(d2.v1, exact[1], "Dual2 f'");
    close(d2.v2, exact[2], "Dual2 f''");

    let d3 = e.eval(Dual3_64::from(t).derivative());
    close(d3.re, exact[0], "Dual3 value");
    close(d3.v1, exact[1], "Dual3 f'");
    close(d3.v2, exact[2], "Dual3 f''");
    close(d3.v3, exact[3], "Dual3 f'''");

    let h = e.eval(HyperDual64::from(t).derivative1().derivative2());
    close(h.re, exact[0], "HyperDual value");
    close(h.eps1, exact[1], "HyperDual f' (eps1)");
    close(h.eps2, exact[1], "HyperDual f' (eps2)");
    close(h.eps1eps2, exact[2], "HyperDual f''");
}

#[test]
fn profile_derivatives_are_exact() {
    for t in GRID {
        let (s, c, s2, c2) = (t.sin(), t.cos(), (2.0 * t).sin(), (2.0 * t).cos());
        let exact = [
            2.0 * s + 0.2 * s2,
            2.0 * c + 0.4 * c2,
            -2.0 * s - 0.8 * s2,
            -2.0 * c - 1.6 * c2,
        ];
        check_derivatives("2*sin(t) + 0.2*sin(2*t)", t, exact);
    }
}

#[test]
fn gaussian_derivatives_are_exact() {
    for t in GRID {
        let g = (-t * t).exp();
        let exact = [
            g,
            -2.0 * t * g,
            (4.0 * t * t - 2.0) * g,
            (12.0 * t - 8.0 * t * t * t) * g,
        ];
        check_derivatives("exp(-t^2)", t, exact);
    }
}

#[test]
fn hypot_derivatives_are_exact() {
    for t in GRID {
        let h = (1.0 + t * t).sqrt();
        let exact = [h, t / h, 1.0 / h.powi(3), -3.0 * t / h.powi(5)];
        check_derivatives("sqrt(1 + t^2)", t, exact);
    }
}

#[test]
fn integer_power_derivatives_are_exact_at_negative_t() {
    for t in GRID {
        check_derivatives("t^3", t, [t * t * t, 3.0 * t * t, 6.0 * t, 6.0]);
        check_derivatives("(-t)^2", t, [t * t, 2.0 * t, 2.0, 0.0]);
        check_derivatives("-t^2", t, [-t * t, -2.0 * t, -2.0, 0.0]);
        check_derivatives(
            "t^-1",
            t,
            [1.0 / t, -1.0 / (t * t), 2.0 / t.powi(3), -6.0 / t.powi(4)],
        );
        check_derivatives(
            "1/t",
            t,
            [1.0 / t, -1.0 / (t * t), 2.0 / t.powi(3), -6.0 / t.powi(4)],
        );
    }
}

#[test]
fn real_and_variable_power_derivatives_are_exact() {
    for t in [0.15_f64, 0.6, 1.25, 2.45] {
        let p = t.powf(2.5);
        check_derivatives(
            "t^2.5",
            t,
            [p, 2.5 * p / t, 3.75 * p / (t * t), 1.875 * p / t.powi(3)],
        );

        let (l, f) = (2f64.ln(), 2f64.powf(t));
        check_derivatives("2^t", t, [f, l * f, l * l * f, l * l * l * f]);

        // f = t^t: f' = f (ln t + 1), f'' = f ((ln t + 1)^2 + 1/t),
        // f''' = f ((ln t + 1)^3 + 3 (ln t + 1)/t - 1/t^2).
        let (f, g) = ((t * t.ln()).exp(), t.ln() + 1.0);
        let exact = [
            f,
            f * g,
            f * (g * g + 1.0 / t),
            f * (g * g * g + 3.0 * g / t - 1.0 / (t * t)),
        ];
        check_derivatives("t^t", t, exact);
    }
}

#[test]
fn elementary_function_derivatives_are_exact() {
    for t in [-1.1_f64, -0.4, 0.3, 0.9] {
        let (s, c) = (t.sin(), t.cos());
        check_derivatives("sin(t)", t, [s, c, -s, -c]);
        check_derivatives("cos(t)", t, [c, -s, -c, s]);
        let tan = t.tan();
        let sec2 = 1.0 + tan * tan;
        check_derivatives(
            "tan(t)",
            t,
            [
                tan,
                sec2,
                2.0 * tan * sec2,
                2.0 * sec2 * (1.0 + 3.0 * tan * tan),
            ],
        );
        let (sh, ch, th) = (t.sinh(), t.cosh(), t.tanh());
        check_derivatives("sinh(t)", t, [sh, ch, sh, ch]);
        check_derivatives("cosh(t)", t, [ch, sh, ch, sh]);
        let sech2 = 1.0 - th * th;
        check_derivatives(
            "tanh(t)",
            t,
            [
                th,
                sech2,
                -2.0 * th * sech2,
                2.0 * sech2 * (3.0 * th * th - 1.0),
            ],
        );
        let q = 1.0 + t * t;
        check_derivatives(
            "atan(t)",
            t,
            [
                t.atan(),
                1.0 / q,
                -2.0 * t / (q * q),
                (6.0 * t * t - 2.0) / (q * q * q),
            ],
        );
        let a = t.abs();
        let sign = t.signum();
        check_derivatives("abs(t)", t, [a, sign, 0.0, 0.0]);
        check_derivatives(
            "ln(abs(t))",
            t,
            [a.ln(), 1.0 / t, -1.0 / (t * t), 2.0 / t.powi(3)],
        );
        let ex = t.exp();
        check_derivatives("exp(t)", t, [ex, ex, ex, ex]);
    }
}

#[test]
fn reciprocal_trigonometric_derivatives_are_exact() {
    // cot' = -csc^2, sec' = sec tan, csc' = -csc cot, and their second and third derivatives.
    for t in [-1.1_f64, -0.4, 0.3, 0.9, 2.0] {
        let (s, c) = (t.sin(), t.cos());
        let (cot, csc, sec, tan) = (c / s, 1.0 / s, 1.0 / c, s / c);
        let (csc2, sec2) = (csc * csc, sec * sec);
        check_derivatives(
            "cot(t)",
            t,
            [
                cot,
                -csc2,
                2.0 * csc2 * cot,
                -2.0 * csc2 * (csc2 + 2.0 * cot * cot),
            ],
        );
        check_derivatives(
            "sec(t)",
            t,
            [
                sec,
                sec * tan,
                sec * (tan * tan + sec2),
                sec * tan * (tan * tan + 5.0 * sec2),
            ],
        );
        check_derivatives(
            "csc(t)",
            t,
            [
                csc,
                -csc * cot,
                csc * (cot * cot + csc2),
                -csc * cot * (cot * cot + 5.0 * csc2),
            ],
        );
    }
}

#[test]
fn reciprocal_trigonometric_derivatives_match_central_differences() {
    // Independent of the closed forms above: fourth-order central differences of the f64
    // values (step 1e-3: truncation ~1e-12 relative, rounding ~1e-13).
    let h = 1e-3;
    for src in ["cot(t)", "sec(t)", "csc(t)", "cot(2*t) + sec(t/2)*csc(t)"] {
        let e = parse(src);
        for t in [-1.1_f64, -0.4, 0.3, 0.9, 1.3] {
            let f = |x: f64| e.eval(x);
            let fd =
                (f(t - 2.0 * h) - 8.0 * f(t - h) + 8.0 * f(t + h) - f(t + 2.0 * h)) / (12.0 * h);
            let d = e.eval(Dual64::from(t).derivative()).eps;
            assert!(
                (d - fd).abs() <= 1e-8 * d.abs().max(1.0),
                "{src} at {t}: dual {d}, central difference {fd}"
            );
        }
    }
}

#[test]
fn num_dual_drivers_accept_eval() {
    let e = parse("t^3");
    let (f, df) = num_dual::first_derivative(|x| e.eval(x), 2.0);
    assert_eq!((f, df), (8.0, 12.0));
    let (_, _, d2f, d3f) = num_dual::third_derivative(|x| e.eval(x), 2.0);
    assert_eq!((d2f, d3f), (12.0, 6.0));
}

// ---------------------------------------------------------------- check_finite_on

#[test]
fn check_finite_on_accepts_smooth_profiles() {
    parse("2*sin(t) + 0.2*sin(2*t)")
        .check_finite_on(-10.0, 10.0, 1001)
        .unwrap();
    parse("sqrt(1 + t^2)")
        .check_finite_on(-5.0_f64, 5.0, 64)
        .unwrap();
    parse("exp(-t^2)")
        .check_finite_on(-3.0_f32, 3.0, 64)
        .unwrap();
    parse("ln(t)").check_finite_on(2.0, 1.0, 16).unwrap(); // a reversed interval is fine
    parse("ln(t)").check_finite_on(-1.0, 1.0, 0).unwrap(); // no samples: nothing to check
}

#[test]
fn check_finite_on_reports_the_first_failure() {
    let err = parse("sqrt(t)").check_finite_on(0.0, 1.0, 5).unwrap_err();
    assert!(
        matches!(
            err,
            ExpressionError::NotFinite {
                t: 0.0,
                derivative: 1,
                ..
            }
        ),
        "{err}"
    );
    assert_eq!(err.position(), None);
    assert!(err.to_string().contains("first derivative"), "{err}");

    let err = parse("1/t").check_finite_on(-1.0, 1.0, 3).unwrap_err();
    assert!(
        matches!(
            err,
            ExpressionError::NotFinite {
                t: 0.0,
                derivative: 0,
                ..
            }
        ),
        "{err}"
    );

    let err = parse("ln(t)").check_finite_on(-1.0, 1.0, 4).unwrap_err();
    assert!(
        matches!(err, ExpressionError::NotFinite { t: -1.0, derivative: 0, value } if value.is_nan()),
        "{err}"
    );

    // f = exp(exp(t)) at exp(t) = 700: f ~ 1e304 and f' = 700 f are finite, f'' = 490700 f overflows.
    let t = 700_f64.ln();
    let err = parse("exp(exp(t))").check_finite_on(t, t, 1).unwrap_err();
    assert!(
        matches!(err, ExpressionError::NotFinite { derivative: 2, .. }),
        "{err}"
    );

    // One sample checks t0 only; the last sample is t1 exactly.
    parse("1/(t - 1)").check_finite_on(0.0, 1.0, 1).unwrap();
    let err = parse("1/(t - 0.3)")
        .check_finite_on(0.1, 0.3, 7)
        .unwrap_err();
    assert!(
        matches!(err, ExpressionError::NotFinite { t, .. } if t == 0.3),
        "{err}"
    );
}

// ---------------------------------------------------------------- properties

/// Pieces of expressions, valid and not, for the fuzzing properties.
const TOKENS: [&str; 34] = [
    "t", "t", "pi", "e", "1", "2.5", "1e3", ".5", "1e999", "1.2.3", "+", "-", "-", "*", "/", "^",
    "^", "(", "(", ")", ")", ",", "sin(", "sqrt(", "ln(", "exp(", "atan(", "abs", "x", " ", "\t",
    "#", "é", "0/0",
];

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: 512,
        rng_seed: RngSeed::Fixed(0x0ca9_57a0),
        ..ProptestConfig::default()
    }
}

/// Evaluates `e` at a few points on every scalar type; returns nothing, must not panic.
fn eval_everywhere(e: &Expression) {
    for t in [-1.5, -0.0, 0.0, 0.5, 3.0, f64::NAN, f64::INFINITY, 1e300] {
        let _ = e.eval(t);
        let _ = e.eval(t as f32);
        let _ = e.eval(Dual64::from(t).derivative());
        let _ = e.eval(Dual2_64::from(t).derivative());
        let _ = e.eval(Dual3_64::from(t).derivative());
        let _ = e.eval(HyperDual64::from(t).derivative1().derivative2());
    }
    let _ = e.check_finite_on(-2.0, 2.0, 5);
}

/// A random expression tree, rendered to text by [`render`] and evaluated directly by [`eval_tree`].
#[derive(Clone, Debug)]
enum Tree {
    Number(f64, bool), // non-negative; `true`: written in scientific notation
    T,
    Pi,
    E,
    Negate(Box<Tree>),
    Binary(char, Box<Tree>, Box<Tree>),
    Call(&'static str, Box<Tree>),
}

const FUNCTIONS: [&str; 14] = [
    "sin", "cos", "tan", "exp", "ln", "sqrt", "abs", "sinh", "cosh", "tanh", "atan", "cot", "sec",
    "csc",
];

fn tree() -> impl Strategy<Value = Tree> {
    let leaf = prop_oneof![
        (0.0..100.0_f64, any::<bool>()).prop_map(|(x, sci)| Tree::Number(x, sci)),
        prop::sample::select(vec![0.0, 0.5, 1.0, 2.0, 3.0, 10.0])
            .prop_map(|x| Tree::Number(x, false)),
        Just(Tree::T),
        Just(Tree::T),
        Just(Tree::Pi),
        Just(Tree::E),
    ];
    leaf.prop_recursive(6, 48, 2, |inner| {
        prop_oneof![
            inner.clone().prop_map(|a| Tree::Negate(Box::new(a))),
            (
                prop::sample::select(vec!['+', '-', '*', '/', '^']),
                inner.clone(),
                inner.clone()
            )
                .prop_map(|(op, a, b)| Tree::Binary(op, Box::new(a), Box::new(b))),
            (prop::sample::select(FUNCTIONS.to_vec()), inner)
                .prop_map(|(f, a)| Tree::Call(f, Box::new(a))),
        ]
    })
}

/// Binding strength: 1 for `+ -`, 2 for `* /`, 3 for unary minus, 4 for `^`, 5 for primaries.
fn precedence(tree: &Tree) -> u8 {
    match tree {
        Tree::Binary('+' | '-', ..) => 1,
        Tree::Binary('*' | '/', ..) => 2,
        Tree::Negate(_) => 3,
        Tree::Binary(..) => 4,
        _ => 5,
    }
}

/// Text for `tree`, with only the parentheses the grammar needs (all of them if `full`).
fn render(tree: &Tree, full: bool) -> String {
    let wrap = |child: &Tree, min: u8| {
        let text = render(child, full);
        if full || precedence(child) < min {
            format!("({text})")
        } else {
            text
        }
    };
    match tree {
        Tree::Number(x, false) => format!("{x}"),
        Tree::Number(x, true) => format!("{x:e}"),
        Tree::T => "t".into(),
        Tree::Pi => "pi".into(),
        Tree::E => "e".into(),
        Tree::Negate(a) => format!("-{}", wrap(a, 3)),
        // Left-associative: the right operand must bind strictly tighter.
        Tree::Binary(op @ ('+' | '-'), a, b) => format!("{} {op} {}", wrap(a, 1), wrap(b, 2)),
        Tree::Binary(op @ ('*' | '/'), a, b) => format!("{}{op}{}", wrap(a, 2), wrap(b, 3)),
        // Right-associative, and the exponent may be signed: `a^-b^c = a^(-(b^c))`.
        Tree::Binary(op, a, b) => format!("{}{op}{}", wrap(a, 5), wrap(b, 3)),
        Tree::Call(f, a) => format!("{f}({})", render(a, full)),
    }
}

fn has_t(tree: &Tree) -> bool {
    match tree {
        Tree::T => true,
        Tree::Number(..) | Tree::Pi | Tree::E => false,
        Tree::Negate(a) | Tree::Call(_, a) => has_t(a),
        Tree::Binary(_, a, b) => has_t(a) || has_t(b),
    }
}

/// `tree` at `t`, by the documented rules, operation for operation as the compiled program.
fn eval_tree(tree: &Tree, t: f64) -> f64 {
    match tree {
        Tree::Number(x, _) => *x,
        Tree::T => t,
        Tree::Pi => std::f64::consts::PI,
        Tree::E => std::f64::consts::E,
        Tree::Negate(a) => -eval_tree(a, t),
        Tree::Binary(op, a, b) => {
            let (x, y) = (eval_tree(a, t), eval_tree(b, t));
            match op {
                '+' => x + y,
                '-' => x - y,
                '*' => x * y,
                '/' => x / y,
                _ if has_t(b) => (y * x.ln()).exp(),
                _ if y.fract() == 0.0 && y.abs() <= 1024.0 => x.powi(y as i32),
                _ => x.powf(y),
            }
        }
        Tree::Call(f, a) => {
            let x = eval_tree(a, t);
            match *f {
                "sin" => x.sin(),
                "cos" => x.cos(),
                "tan" => x.tan(),
                "exp" => x.exp(),
                "ln" => x.ln(),
                "sqrt" => x.sqrt(),
                "abs" => x.abs(),
                "sinh" => x.sinh(),
                "cosh" => x.cosh(),
                "tanh" => x.tanh(),
                "cot" => x.tan().recip(),
                "sec" => x.cos().recip(),
                "csc" => x.sin().recip(),
                _ => x.atan(),
            }
        }
    }
}

/// Whether a sub-tree without `t` (folded at parse time) has a non-finite value.
fn has_non_finite_constant(tree: &Tree) -> bool {
    let children = match tree {
        Tree::Negate(a) | Tree::Call(_, a) => has_non_finite_constant(a),
        Tree::Binary(_, a, b) => has_non_finite_constant(a) || has_non_finite_constant(b),
        _ => false,
    };
    children || (!has_t(tree) && !eval_tree(tree, 0.0).is_finite())
}

fn same(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn parse_never_panics_on_arbitrary_text(src in ".{0,80}") {
        if let Ok(e) = Expression::parse(&src) {
            eval_everywhere(&e);
        }
    }

    #[test]
    fn parse_never_panics_on_token_soup(tokens in prop::collection::vec(prop::sample::select(TOKENS.to_vec()), 0..40)) {
        let src = tokens.concat();
        match Expression::parse(&src) {
            Ok(e) => eval_everywhere(&e),
            Err(err) => {
                let position = err.position().unwrap();
                prop_assert!(position <= src.len(), "{}", err);
                prop_assert!(!err.to_string().is_empty());
            }
        }
    }

    #[test]
    fn parse_never_panics_on_damaged_expressions(
        tree in tree(),
        edits in prop::collection::vec((any::<prop::sample::Index>(), prop::sample::select(TOKENS.to_vec()), any::<bool>()), 1..4),
    ) {
        // Near-misses reach the error paths deep inside the parser.
        let mut src = render(&tree, false);
        for (at, token, delete) in edits {
            let at = at.index(src.len() + 1);
            if !src.is_char_boundary(at) {
                continue;
            }
            if delete {
                let end = src[at..].char_indices().nth(1).map_or(src.len(), |(i, _)| at + i);
                src.replace_range(at..end, "");
            } else {
                src.insert_str(at, token);
            }
        }
        match Expression::parse(&src) {
            Ok(e) => eval_everywhere(&e),
            Err(err) => prop_assert!(err.position().unwrap() <= src.len(), "`{}`: {}", src, err),
        }
    }

    #[test]
    fn generated_expressions_round_trip_and_evaluate_as_written(tree in tree()) {
        let minimal = render(&tree, false);
        let full = render(&tree, true);
        match Expression::parse(&minimal) {
            Ok(e) => {
                prop_assert!(!has_non_finite_constant(&tree), "`{}`", minimal);
                prop_assert_eq!(e.to_string(), minimal.clone());
                let again = Expression::parse(&e.to_string()).unwrap();
                prop_assert_eq!(&again, &e);
                let parenthesised = Expression::parse(&full).unwrap();
                for t in [-1.3, 0.0, 0.4, 2.2] {
                    let want = eval_tree(&tree, t);
                    prop_assert!(same(e.eval(t), want), "`{}` at {}: {} vs {}", minimal, t, e.eval(t), want);
                    prop_assert!(same(again.eval(t), want));
                    prop_assert!(same(parenthesised.eval(t), want), "`{}` at {}", full, t);
                }
            }
            Err(ExpressionError::NonFiniteConstant { .. }) => {
                prop_assert!(has_non_finite_constant(&tree), "`{}`", minimal);
                prop_assert!(Expression::parse(&full).is_err());
            }
            Err(err) => prop_assert!(false, "`{}` does not parse: {}", minimal, err),
        }
    }
}
