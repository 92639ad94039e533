//! Friction laws: consistent tangents against central differences.

mod common;

use approx::assert_relative_eq;
use capstan_friction::{
    ContactState, FrictionLaw, Frictionless, RegularisedCoulomb, RegularisedCoulombParams,
};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    /// Away from the kink `|u| = eps` (by 20 steps), with the step `1e-4 eps` well inside `eps`.
    #[test]
    fn regularised_coulomb_derivatives_match_central_differences(
        mu in 0.0..2.0f64,
        eps in 1e-4..1.0f64,
        radius in 0.0..3.0f64,
        angle in 0.0..std::f64::consts::TAU,
        pressure in -10.0..0.5f64,
    ) {
        let norm = radius * eps;
        let h = 1e-4 * eps;
        prop_assume!((norm - eps).abs() > 20.0 * h);
        let c = ContactState::new([norm * angle.cos(), norm * angle.sin()], pressure);
        let p = RegularisedCoulombParams::new(mu, eps).unwrap();
        let d = RegularisedCoulomb.traction_derivatives(&c, &p);
        // t is linear in p: a step relative to |p| keeps round-off small
        let hp = 1e-6 * c.normal_pressure.abs().max(1.0);
        let (fd_slip, fd_p) = common::central_differences(&RegularisedCoulomb, &c, &p, h, hp);
        // scale of the slip derivatives: mu |p| / min(|u|, eps); central differences are O(h^2)
        let scale = mu * pressure.abs().max(1.0) / norm.max(eps);
        #[allow(clippy::needless_range_loop)] // mirrors d t_i / d u_j
        for i in 0..2 {
            for j in 0..2 {
                prop_assert!((d.d_slip[i][j] - fd_slip[i][j]).abs() <= 1e-6 * scale.max(1e-300) + 1e-12,
                    "d_slip[{}][{}] = {} vs {}", i, j, d.d_slip[i][j], fd_slip[i][j]);
            }
            prop_assert!((d.d_pressure[i] - fd_p[i]).abs() <= 4e-9 * mu.max(1e-300) + 1e-12);
        }
    }
}

#[test]
fn frictionless_traction_and_derivatives_are_zero() {
    let c = ContactState::new([0.2, -0.7], -3.0);
    assert_eq!(Frictionless.traction(&c, &()), [0.0, 0.0]);
    let d = FrictionLaw::<f64>::traction_derivatives(&Frictionless, &c, &());
    assert_eq!(d.d_slip, [[0.0; 2]; 2]);
    assert_eq!(d.d_pressure, [0.0; 2]);
}

#[test]
fn regularised_coulomb_is_linear_below_eps_and_coulomb_above() {
    let p = RegularisedCoulombParams::new(0.5, 0.1).unwrap();
    let t = RegularisedCoulomb.traction(&ContactState::new([0.03, 0.04], -2.0), &p);
    assert_relative_eq!(t[0], -0.5 * 2.0 * 0.03 / 0.1, max_relative = 1e-15); // mu p u / eps
    let t = RegularisedCoulomb.traction(&ContactState::new([0.3, 0.4], -2.0), &p);
    assert_relative_eq!(t[1], -0.5 * 2.0 * 0.8, max_relative = 1e-15); // mu p u/|u|
    let d = RegularisedCoulomb.traction_derivatives(&ContactState::new([0.0, 0.0], -2.0), &p);
    assert_relative_eq!(d.d_slip[0][0], -10.0, max_relative = 1e-15); // mu p / eps at u = 0
}

#[test]
fn f32_is_supported() {
    let p = RegularisedCoulombParams::new(0.5f32, 0.1).unwrap();
    let t = RegularisedCoulomb.traction(&ContactState::new([1.0f32, 0.0], -1.0), &p);
    assert_eq!(t, [-0.5, 0.0]);
}
