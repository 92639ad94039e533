//! The nonsmooth laws (exact Coulomb, exact orthotropic Coulomb): projection properties
//! (idempotent, the inside stays, the outside lands on the circle / ellipse and is the nearest
//! point), generalised Jacobians against central differences away from the kink, the
//! `eps -> 0` limit of the regularised laws, the registry.

use capstan_friction::registry;
use capstan_friction::{
    AnyFrictionParams, AnyNonsmoothLaw, AnyNonsmoothParams, ContactState, ExactCoulomb,
    ExactCoulombParams, ExactOrthotropicCoulomb, ExactOrthotropicCoulombParams, FrictionError,
    FrictionLaw, FrictionSettings, FrictionState, NonsmoothFrictionLaw, OrthotropicCoulomb,
    OrthotropicCoulombParams, Projection, RegularisedCoulomb, RegularisedCoulombParams,
};
use proptest::prelude::*;

fn polar(norm: f64, angle: f64) -> [f64; 2] {
    [norm * angle.cos(), norm * angle.sin()]
}

fn norm(v: [f64; 2]) -> f64 {
    v[0].hypot(v[1])
}

/// `(t'_1/(mu_1 p))^2 + (t'_2/(mu_2 p))^2` in the axes rotated by `phi`.
fn ellipse_level(t: [f64; 2], mu: [f64; 2], phi: f64, p: f64) -> f64 {
    let (c, s) = (phi.cos(), phi.sin());
    let r = [c * t[0] + s * t[1], -s * t[0] + c * t[1]];
    (r[0] / (mu[0] * p)).powi(2) + (r[1] / (mu[1] * p)).powi(2)
}

/// Every generalised derivative against central differences of the projection with step
/// `h` (trial) and `hp` (pressure): `|d - fd| <= 1e-6 scale + 1e-10`.
fn check_jacobian<L: NonsmoothFrictionLaw<f64>>(
    law: &L,
    trial: [f64; 2],
    sigma: f64,
    params: &L::Params,
    h: f64,
    hp: f64,
) -> Result<(), TestCaseError> {
    let pr = law.project(trial, sigma, params).unwrap();
    let at = |t: [f64; 2], s: f64| law.project(t, s, params).unwrap().traction;
    for j in 0..2 {
        let (mut plus, mut minus) = (trial, trial);
        plus[j] += h;
        minus[j] -= h;
        let (tp, tm) = (at(plus, sigma), at(minus, sigma));
        for i in 0..2 {
            let fd = (tp[i] - tm[i]) / (2.0 * h);
            prop_assert!(
                (pr.d_trial[i][j] - fd).abs() <= 1e-6 + 1e-10,
                "d_trial[{}][{}] = {} vs {} at {:?}, sigma {}",
                i,
                j,
                pr.d_trial[i][j],
                fd,
                trial,
                sigma
            );
        }
    }
    let (tp, tm) = (at(trial, sigma + hp), at(trial, sigma - hp));
    for i in 0..2 {
        let fd = (tp[i] - tm[i]) / (2.0 * hp);
        prop_assert!(
            (pr.d_pressure[i] - fd).abs() <= 1e-6 + 1e-10,
            "d_pressure[{}] = {} vs {} at {:?}, sigma {}",
            i,
            pr.d_pressure[i],
            fd,
            trial,
            sigma
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// Inside stays, outside lands on the circle along the trial, and projecting twice is
    /// projecting once.
    #[test]
    fn coulomb_projection_is_idempotent_and_lands_on_the_circle(
        mu in 0.0..2.0f64, radius in 0.0..5.0f64, angle in 0.0..std::f64::consts::TAU,
        sigma in -10.0..-1e-3f64,
    ) {
        let p = ExactCoulombParams::new(mu).unwrap();
        let g = -mu * sigma;
        let trial = polar(radius * g.max(1e-3), angle);
        let pr = ExactCoulomb.project(trial, sigma, &p).unwrap();
        if norm(trial) <= g {
            prop_assert_eq!(pr.traction, trial);
            prop_assert_eq!(pr.state, FrictionState::Stick);
        } else {
            prop_assert!((norm(pr.traction) - g).abs() <= 1e-14 * g.max(1e-300));
            // along the trial: t x t* = 0, t . t* > 0
            prop_assert!((pr.traction[0] * trial[1] - pr.traction[1] * trial[0]).abs() <= 1e-13 * norm(trial) * g.max(1e-300));
            prop_assert!(g == 0.0 || pr.traction[0] * trial[0] + pr.traction[1] * trial[1] > 0.0);
            prop_assert_eq!(pr.state, FrictionState::Slip);
        }
        let again = ExactCoulomb.project(pr.traction, sigma, &p).unwrap();
        prop_assert!(norm([again.traction[0] - pr.traction[0], again.traction[1] - pr.traction[1]]) <= 1e-15 * g.max(1e-300));
    }

    /// Away from the kink (`|t*| = g`) by 20 steps.
    #[test]
    fn coulomb_jacobian_matches_central_differences(
        mu in 0.05..2.0f64, radius in 0.0..4.0f64, angle in 0.0..std::f64::consts::TAU,
        sigma in -10.0..-0.1f64,
    ) {
        let g = -mu * sigma;
        let h = 1e-6 * g;
        prop_assume!((radius - 1.0).abs() * g > 20.0 * h && radius * g > 20.0 * h);
        let p = ExactCoulombParams::new(mu).unwrap();
        check_jacobian(&ExactCoulomb, polar(radius * g, angle), sigma, &p, h, 1e-6 * sigma.abs())?;
    }

    /// The ellipse: inside stays, outside lands on the ellipse at the nearest point (the
    /// variational inequality `(t* - t) . (y - t) <= 0` for points `y` of the ellipse), and the
    /// projection is idempotent.
    #[test]
    fn orthotropic_projection_is_the_nearest_point_of_the_ellipse(
        mu1 in 0.05..2.0f64, mu2 in 0.05..2.0f64, phi in -3.0..3.0f64,
        radius in 0.0..6.0f64, angle in 0.0..std::f64::consts::TAU, sigma in -10.0..-0.01f64,
    ) {
        let p = ExactOrthotropicCoulombParams::new([mu1, mu2], phi).unwrap();
        let scale = mu1.max(mu2) * sigma.abs();
        let trial = polar(radius * scale, angle);
        let pr = ExactOrthotropicCoulomb.project(trial, sigma, &p).unwrap();
        let level = ellipse_level(trial, [mu1, mu2], phi, -sigma);
        if level <= 1.0 {
            prop_assert_eq!(pr.state, FrictionState::Stick);
            prop_assert!(norm([pr.traction[0] - trial[0], pr.traction[1] - trial[1]]) <= 1e-15 * scale);
        } else {
            prop_assert_eq!(pr.state, FrictionState::Slip);
            prop_assert!((ellipse_level(pr.traction, [mu1, mu2], phi, -sigma) - 1.0).abs() <= 1e-12);
            let r = [trial[0] - pr.traction[0], trial[1] - pr.traction[1]];
            for k in 0..64 {
                // points of the ellipse, in the axes then rotated out
                let a = std::f64::consts::TAU * k as f64 / 64.0;
                let e = [mu1 * -sigma * a.cos(), mu2 * -sigma * a.sin()];
                let y = [phi.cos() * e[0] - phi.sin() * e[1], phi.sin() * e[0] + phi.cos() * e[1]];
                let vi = r[0] * (y[0] - pr.traction[0]) + r[1] * (y[1] - pr.traction[1]);
                prop_assert!(vi <= 1e-12 * scale * scale, "VI {} at k = {}", vi, k);
            }
        }
        let again = ExactOrthotropicCoulomb.project(pr.traction, sigma, &p).unwrap();
        prop_assert!(norm([again.traction[0] - pr.traction[0], again.traction[1] - pr.traction[1]]) <= 1e-13 * scale);
    }

    /// Away from the kink (the ellipse) by 20 steps.
    #[test]
    fn orthotropic_jacobian_matches_central_differences(
        mu1 in 0.1..2.0f64, mu2 in 0.1..2.0f64, phi in -3.0..3.0f64,
        radius in 0.0..4.0f64, angle in 0.0..std::f64::consts::TAU, sigma in -10.0..-0.1f64,
    ) {
        let p = ExactOrthotropicCoulombParams::new([mu1, mu2], phi).unwrap();
        let scale = mu1.max(mu2) * sigma.abs();
        let trial = polar(radius * scale, angle);
        let h = 1e-6 * scale;
        let level = ellipse_level(trial, [mu1, mu2], phi, -sigma);
        prop_assume!((level.sqrt() - 1.0).abs() > 1e-3);
        check_jacobian(&ExactOrthotropicCoulomb, trial, sigma, &p, h, 1e-6 * sigma.abs())?;
    }

    /// Equal coefficients: the ellipse is the disc, for any axis angle.
    #[test]
    fn orthotropic_with_equal_coefficients_is_exact_coulomb(
        mu in 0.05..2.0f64, phi in -3.0..3.0f64, radius in 0.0..4.0f64,
        angle in 0.0..std::f64::consts::TAU, sigma in -10.0..1.0f64,
    ) {
        let trial = polar(radius * mu * sigma.abs().max(0.1), angle);
        let a = ExactCoulomb.project(trial, sigma, &ExactCoulombParams::new(mu).unwrap()).unwrap();
        let b = ExactOrthotropicCoulomb
            .project(trial, sigma, &ExactOrthotropicCoulombParams::new([mu, mu], phi).unwrap())
            .unwrap();
        prop_assert_eq!(a.state, b.state);
        let tol = 1e-12 * (1.0 + norm(trial));
        for i in 0..2 {
            prop_assert!((a.traction[i] - b.traction[i]).abs() <= tol);
            prop_assert!((a.d_pressure[i] - b.d_pressure[i]).abs() <= 1e-10 * (1.0 + mu));
            for j in 0..2 {
                prop_assert!((a.d_trial[i][j] - b.d_trial[i][j]).abs() <= 1e-10);
            }
        }
    }

    /// The `eps -> 0` limit: a sliding point (`du != 0`, trial `-r du` with `r` large) gets
    /// the regularised law's traction at any slip `|du| >= eps`, isotropic and orthotropic.
    #[test]
    fn sliding_traction_is_the_regularised_traction(
        mu1 in 0.05..2.0f64, mu2 in 0.05..2.0f64, phi in -3.0..3.0f64,
        slip in 1e-3..1.0f64, angle in 0.0..std::f64::consts::TAU, sigma in -10.0..-0.1f64,
    ) {
        let du = polar(slip, angle);
        let r = 1e3 * mu1.max(mu2) * sigma.abs() / slip;
        let trial = [-r * du[0], -r * du[1]];
        let iso = ExactCoulomb.project(trial, sigma, &ExactCoulombParams::new(mu1).unwrap()).unwrap();
        let reg = RegularisedCoulomb.traction(&ContactState::new(du, sigma), &RegularisedCoulombParams::new(mu1, 1e-4).unwrap());
        prop_assert!(norm([iso.traction[0] - reg[0], iso.traction[1] - reg[1]]) <= 1e-12 * mu1 * sigma.abs());
        // orthotropic: the Euclidean projection of a far trial is the support point of the
        // ellipse, whose normal is the slip direction only asymptotically; the associated law
        // is recovered through the fixed point t = P(t - r du), checked by iterating it
        let po = ExactOrthotropicCoulombParams::new([mu1, mu2], phi).unwrap();
        let mut t = [0.0, 0.0];
        for _ in 0..200 {
            t = ExactOrthotropicCoulomb.project([t[0] - r * du[0], t[1] - r * du[1]], sigma, &po).unwrap().traction;
        }
        let rego = OrthotropicCoulomb.traction(&ContactState::new(du, sigma), &OrthotropicCoulombParams::new([mu1, mu2], phi, 1e-4).unwrap());
        prop_assert!(norm([t[0] - rego[0], t[1] - rego[1]]) <= 1e-9 * mu1.max(mu2) * sigma.abs(), "{:?} vs {:?}", t, rego);
    }
}

#[test]
fn no_compression_means_no_friction() {
    let p = ExactCoulombParams::new(0.5).unwrap();
    let po = ExactOrthotropicCoulombParams::new([0.5, 0.2], 0.3).unwrap();
    for sigma in [0.0, 1.0] {
        let a = ExactCoulomb.project([1.0, -2.0], sigma, &p).unwrap();
        let b = ExactOrthotropicCoulomb
            .project([1.0, -2.0], sigma, &po)
            .unwrap();
        for pr in [a, b] {
            assert_eq!(pr, Projection::separated());
        }
    }
}

#[test]
fn a_zero_coefficient_makes_the_ellipse_a_segment() {
    // mu_2 = 0 along the second axis at phi = 0: t_2 = 0, t_1 clamped to mu_1 |sigma_n| = 1
    let p = ExactOrthotropicCoulombParams::new([0.5, 0.0], 0.0).unwrap();
    let pr = ExactOrthotropicCoulomb
        .project([3.0, 4.0], -2.0, &p)
        .unwrap();
    assert_eq!(pr.traction, [1.0, 0.0]);
    assert_eq!(pr.state, FrictionState::Slip);
    assert_eq!(pr.d_trial, [[0.0, 0.0], [0.0, 0.0]]);
    assert_eq!(pr.d_pressure, [-0.5, 0.0]);
    let pr = ExactOrthotropicCoulomb
        .project([0.5, 4.0], -2.0, &p)
        .unwrap();
    assert_eq!(pr.traction, [0.5, 0.0]);
    assert_eq!(pr.d_trial, [[1.0, 0.0], [0.0, 0.0]]);
    assert!(matches!(
        ExactOrthotropicCoulombParams::new([0.0, 0.0], 0.0),
        Err(FrictionError::InvalidParameter { field: "mu2", .. })
    ));
}

#[test]
fn nonsmooth_laws_are_named_from_scenes_and_refused_where_smooth_ones_are_needed() {
    let settings = FrictionSettings {
        mu: 0.4,
        ..Default::default()
    };
    let any = AnyNonsmoothParams::new("exact-coulomb", &settings).unwrap();
    assert_eq!(any.name(), "exact-coulomb");
    let direct = ExactCoulomb
        .project([0.0, 5.0], -1.0, &ExactCoulombParams::new(0.4).unwrap())
        .unwrap();
    assert_eq!(
        AnyNonsmoothLaw.project([0.0, 5.0], -1.0, &any).unwrap(),
        direct
    );
    assert!(matches!(
        AnyFrictionParams::new("exact-coulomb", &settings),
        Err(FrictionError::WrongLawKind { .. })
    ));
    assert!(matches!(
        AnyNonsmoothParams::new("coulomb", &settings),
        Err(FrictionError::WrongLawKind { .. })
    ));
    assert!(matches!(
        AnyNonsmoothParams::new("amontons", &settings),
        Err(FrictionError::UnknownLaw { .. })
    ));
    let bad = FrictionSettings {
        mu: -1.0,
        ..Default::default()
    };
    assert!(matches!(
        AnyNonsmoothParams::new("exact-orthotropic-coulomb", &bad),
        Err(FrictionError::InvalidParameter { field: "mu", .. })
    ));
    for law in registry::nonsmooth_registry() {
        for key in law.parameters {
            assert!(registry::is_parameter(key), "{key}");
        }
    }
}
