//! The fuzzed properties, shared by the fuzz targets (`fuzz_targets/*.rs`) and the corpus replay
#![allow(dead_code)] // each fuzz target uses one of the properties; the corpus replay uses all
//! in the normal test suite (`tests/fuzz_corpus.rs`). Each function panics when its property
//! fails; anything else (a typed error included) is a pass.

use capstan::scene::Scene;
use capstan_geometry::ad::curve_jet;
use capstan_geometry::expression::Expression;

/// Expression parser and evaluator: parsing never panics; a parsed expression reparses from its
/// source; its value at `t` (the first 8 bytes, when an angle: `|t| <= 1e6`, and 0 or
/// `|t| >= 1e-12`) is the same in `f64` and in the third-order dual numbers that carry its
/// derivatives; `check_finite_on` answers. (At `|t| ~ 1e-300` or `1e150` dual arithmetic
/// over/underflows in its derivative parts where `f64` does not; scenes check finiteness.)
pub fn expression(data: &[u8]) {
    let angle = |t: f64| t.abs() <= 1e6 && (t == 0.0 || t.abs() >= 1e-12);
    let (t, src) = match data.split_first_chunk::<8>() {
        Some((head, rest)) if angle(f64::from_le_bytes(*head)) => (f64::from_le_bytes(*head), rest),
        Some((_, rest)) => (0.7, rest),
        None => (0.7, data),
    };
    let Ok(src) = std::str::from_utf8(src) else {
        return;
    };
    let Ok(e) = Expression::parse(src) else {
        return;
    };
    assert!(Expression::parse(e.source()).is_ok(), "reparse of {src:?}");
    for x in [t, -t, 0.0, 1.5, t * 1e-3] {
        let v: f64 = e.eval(x);
        let [jet] = curve_jet(|s| [e.eval(s)], x);
        // A rounding difference of an intermediate (num-dual's `tan` is `sin/cos`) is amplified
        // by the expression's condition: allow ten times the change a 1e-13 relative change of
        // `t` makes (a power tower inside `sin` turns the last bit into any value).
        let h = 1e-13 * x.abs().max(1e-13);
        let sensitivity = [x - h, x + h]
            .map(|y| (e.eval(y) - v).abs())
            .into_iter()
            .fold(
                0.0f64,
                |a, b| if b.is_nan() { f64::INFINITY } else { a.max(b) },
            );
        if sensitivity > 1e-6 * v.abs() {
            continue; // ill-conditioned at x: the last bit of an intermediate decides the value
        }
        let same = v == jet[0]
            || (v.is_nan() && jet[0].is_nan())
            || (v - jet[0]).abs() <= 1e-12 * v.abs().max(jet[0].abs()) + 10.0 * sensitivity
            || (v - jet[0]).abs() < f64::MIN_POSITIVE; // subnormal round-off
        assert!(same, "{src:?} at t = {x}: f64 {v}, dual {}", jet[0]);
    }
    let _ = e.check_finite_on(t.min(1e6), t.min(1e6) + 1.0, 9);
}

/// Scene text (lines starting `--set ` are overrides): loading never panics, and a scene that
/// loads serialises to TOML that loads back to the same scene (what `--out DIR/scene.toml`
/// relies on).
pub fn scene(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let mut toml_text = String::new();
    let mut sets = Vec::new();
    for line in text.lines() {
        match line.strip_prefix("--set ") {
            Some(set) => sets.push(set.to_string()),
            None => {
                toml_text.push_str(line);
                toml_text.push('\n');
            }
        }
    }
    let Ok(scene) = Scene::from_text(Some((&toml_text, "fuzz.toml")), &sets) else {
        return;
    };
    let again = toml::to_string(&scene).expect("a loaded scene serialises");
    let back = Scene::from_text(Some((&again, "again.toml")), &[])
        .unwrap_or_else(|e| panic!("a loaded scene reloads: {e}\n{again}"));
    assert_eq!(scene, back, "{again}");
}

/// Bytes read as numbers in given ranges (zero once the data runs out).
struct Reader<'a>(&'a [u8]);

impl Reader<'_> {
    fn u16(&mut self) -> u16 {
        match self.0 {
            [a, b, rest @ ..] => {
                self.0 = rest;
                u16::from_le_bytes([*a, *b])
            }
            _ => 0,
        }
    }
    /// A value in `[lo, hi]`, on a log scale when `log` (both ends positive).
    fn range(&mut self, lo: f64, hi: f64, log: bool) -> f64 {
        let s = f64::from(self.u16()) / f64::from(u16::MAX);
        if log {
            (lo.ln() + s * (hi.ln() - lo.ln())).exp()
        } else {
            lo + s * (hi - lo)
        }
    }
    fn pick<'s>(&mut self, options: &[&'s str]) -> &'s str {
        options[usize::from(self.u16()) % options.len()]
    }
}

/// Membrane models on random valid scenes (every shape, loads, speeds, intervals up to many
/// wraps, budgets): `capstan tension` and `capstan infer-mu` answer with finite, positive
/// tensions or a typed error of exit code 2, 3 or 4 — never a panic or NaN.
pub fn membrane(data: &[u8]) {
    let mut r = Reader(data);
    let shape = r.pick(&["cylinder", "ellipse", "prism", "circular-cone", "cone"]);
    let (c1, c2, c3) = (
        r.range(0.05, 20.0, true),
        r.range(0.05, 20.0, true),
        r.range(-0.5, 0.5, false),
    );
    let profile = r.pick(&[
        "{a}*sin(t)",
        "{a}*sin(t)+{c}*sin(2*t)",
        "{a}*sin(t)^3+{b}*sin(t)",
    ]);
    let fill = |s: &str| {
        s.replace("{a}", &format!("{c1}"))
            .replace("{b}", &format!("{c2}"))
            .replace("{c}", &format!("{c3}"))
    };
    let theta0 = r.range(-4.0, 4.0, false);
    let span = r.range(1e-6, 130.0, true);
    let mut sets = vec![
        format!("obstacle.shape={shape}"),
        format!("obstacle.radius={c1}"),
        format!("obstacle.a={c1}"),
        format!("obstacle.b={c2}"),
        format!(
            "obstacle.half_angle={}",
            r.range(1e-7, std::f64::consts::FRAC_PI_2 * (1.0 - 1e-9), true)
        ),
        format!("obstacle.u={}", fill(profile)),
        format!("obstacle.v={}*cos(t)", c2),
        format!("obstacle.ubar={}", fill(profile)),
        format!("obstacle.vbar={}*cos(t)", c2),
        format!("friction.mu={}", r.range(0.0, 3.0, false)),
        format!("membrane.t0={}", r.range(1e-3, 1e3, true)),
        format!("membrane.theta0={theta0}"),
        format!("membrane.theta_max={}", theta0 + span),
        format!("membrane.samples={}", 2 + r.u16() % 64),
    ];
    if r.u16() % 2 == 1 {
        sets.push(format!("loads.gravity={}", r.range(0.0, 20.0, false)));
        sets.push(format!("loads.density={}", r.range(0.0, 5.0, false)));
        sets.push(format!("loads.speed={}", r.range(-5.0, 5.0, false)));
    }
    let Ok(scene) = Scene::from_text(None, &sets) else {
        return;
    };
    let check = |e: &capstan::error::CliError| {
        assert!(
            (2..=4).contains(&e.exit_code()),
            "untyped failure (exit code {}): {e}\n{sets:?}",
            e.exit_code()
        );
    };
    match capstan::commands::tension::report(&scene) {
        Ok(report) => {
            assert!(
                report.tension.iter().all(|t| t.is_finite() && *t > 0.0),
                "{sets:?}: {:?}",
                report.tension
            );
            // The inverse problem on the computed tension pair: mu comes back (or a typed error).
            if report.tension_ratio > 1.0 {
                let mut with = sets.clone();
                with.push(format!("membrane.t_max={}", report.t_max));
                if let Ok(scene) = Scene::from_text(None, &with) {
                    match capstan::commands::infer_mu::report_for(
                        &scene,
                        capstan::commands::infer_mu::FrictionModel::Capstan,
                    ) {
                        Ok(inferred) => {
                            let json = serde_json::to_value(&inferred).expect("serialises");
                            assert!(!json.to_string().contains("NaN"), "{with:?}: {json}");
                        }
                        Err(e) => check(&e),
                    }
                }
            }
        }
        Err(e) => check(&e),
    }
}
