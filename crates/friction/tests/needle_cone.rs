//! Theorem 2 on right circular cones of every half-aperture, against the closed form
//! `T = T0 exp(mu cot(alpha) sin(sin(alpha) theta))`: the needle cone of issue 18 (two wraps
//! at `alpha = 1e-3` ran for minutes: an absolute quadrature tolerance below the rounding
//! floor of an integrand of size `cot(alpha)`) and a property over `alpha` in
//! `[1e-6, pi/2 - 1e-6]` and up to 20 wraps.

use capstan_friction::FrictionError;
use capstan_friction::membrane::{ConeMembrane, MembraneProblem};
use capstan_geometry::ExpressionProfile;
use proptest::prelude::*;

/// The cone over `(tan(alpha) sin t, tan(alpha) cos t)` as expressions (the scene's path).
fn profile(alpha: f64) -> ExpressionProfile {
    let t = format!("{:e}", alpha.tan());
    ExpressionProfile::parse(&format!("sin(t) * {t}"), &format!("cos(t) * {t}")).unwrap()
}

fn closed_form(mu: f64, alpha: f64, theta: f64) -> f64 {
    (mu / alpha.tan() * (alpha.sin() * theta).sin()).exp()
}

fn max_relative_error(alpha: f64, mu: f64, theta_max: f64) -> Result<f64, FrictionError> {
    let problem = MembraneProblem {
        mu,
        t0: 1.0,
        theta0: 0.0,
        theta_max,
        samples: 33,
        ..Default::default()
    };
    let p = profile(alpha);
    let model = ConeMembrane::new(&p).tension_profile(&problem)?;
    Ok(model
        .theta
        .iter()
        .zip(&model.tension)
        .map(|(&th, &t)| {
            let exact = closed_form(mu, alpha, th);
            (t - exact).abs() / exact
        })
        .fold(0.0, f64::max))
}

#[test]
fn the_needle_cone_answers_two_wraps_to_the_closed_form() {
    // measured: 2.7e-15 (2 wraps), 2.8e-14 (20 wraps)
    let e = max_relative_error(1e-3, 0.5, 4.0 * core::f64::consts::PI).unwrap();
    assert!(e < 1e-12, "{e:e}");
    let e = max_relative_error(1e-3, 0.5, 40.0 * core::f64::consts::PI).unwrap();
    assert!(e < 1e-12, "{e:e}");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    /// Within the development limit `theta < pi / (2 sin alpha)` the tension is the closed
    /// form to 1e-9; beyond it the answer is the typed `DevelopmentLimit`.
    #[test]
    fn right_circular_cones_match_the_closed_form_or_report_the_limit(
        log_alpha in (1e-6f64).ln()..(core::f64::consts::FRAC_PI_2 - 1e-6).ln(),
        wraps in 0.05f64..20.0,
        mu in 0.0f64..1.0,
    ) {
        let alpha = log_alpha.exp().min(core::f64::consts::FRAC_PI_2 - 1e-6);
        let theta_max = wraps * 2.0 * core::f64::consts::PI;
        let limit = core::f64::consts::FRAC_PI_2 / alpha.sin();
        match max_relative_error(alpha, mu, theta_max) {
            Ok(e) => {
                prop_assert!(theta_max < limit * (1.0 + 1e-9), "answered past the limit");
                prop_assert!(e < 1e-9, "alpha {alpha:e}, theta {theta_max}: {e:e}");
            }
            Err(FrictionError::DevelopmentLimit { angle, .. }) => {
                prop_assert!(theta_max > limit * (1.0 - 1e-9), "limit {limit} reported at {angle}");
            }
            Err(other) => prop_assert!(false, "alpha {alpha:e}, theta {theta_max}: {other}"),
        }
    }
}
