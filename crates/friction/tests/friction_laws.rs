//! The friction laws beyond Kikuchi–Oden: consistent tangents against central differences,
//! agreement with regularised Coulomb where they reduce to it, typed parameter errors.

mod common;

use approx::assert_relative_eq;
use capstan_friction::{
    AnyFrictionLaw, AnyFrictionParams, ContactState, FrictionError, FrictionLaw, FrictionLawKind,
    FrictionSettings, Howell, HowellParams, OrthotropicCoulomb, OrthotropicCoulombParams,
    RegularisedCoulomb, RegularisedCoulombParams, SmoothCoulomb, SmoothCoulombParams, Tresca,
    TrescaParams,
};
use proptest::prelude::*;

/// Holds every derivative to its central difference: `|d - fd| <= tol * scale + 1e-12`.
fn check_tangent<L: FrictionLaw<f64>>(
    law: &L,
    c: &ContactState<f64>,
    p: &L::Params,
    h: f64,
    hp: f64,
    slip_scale: f64,
    pressure_scale: f64,
) -> Result<(), TestCaseError> {
    let d = law.traction_derivatives(c, p);
    let (fd_slip, fd_p) = common::central_differences(law, c, p, h, hp);
    #[allow(clippy::needless_range_loop)] // mirrors d t_i / d u_j
    for i in 0..2 {
        for j in 0..2 {
            prop_assert!(
                (d.d_slip[i][j] - fd_slip[i][j]).abs() <= 1e-6 * slip_scale + 1e-12,
                "d_slip[{}][{}] = {} vs {} at {:?}",
                i,
                j,
                d.d_slip[i][j],
                fd_slip[i][j],
                c
            );
        }
        prop_assert!(
            (d.d_pressure[i] - fd_p[i]).abs() <= 1e-6 * pressure_scale + 1e-12,
            "d_pressure[{}] = {} vs {} at {:?}",
            i,
            d.d_pressure[i],
            fd_p[i],
            c
        );
    }
    Ok(())
}

fn slip(norm: f64, angle: f64) -> [f64; 2] {
    [norm * angle.cos(), norm * angle.sin()]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// Smooth everywhere: any slip, step `1e-4 eps`.
    #[test]
    fn smooth_coulomb_derivatives_match_central_differences(
        mu in 0.0..2.0f64, eps in 1e-4..1.0f64, radius in 0.0..5.0f64,
        angle in 0.0..std::f64::consts::TAU, pressure in -10.0..0.5f64,
    ) {
        let c = ContactState::new(slip(radius * eps, angle), pressure);
        let p = SmoothCoulombParams::new(mu, eps).unwrap();
        let scale = mu * pressure.abs().max(1.0) / eps;
        check_tangent(&SmoothCoulomb, &c, &p, 1e-4 * eps, 1e-6 * pressure.abs().max(1.0), scale, mu)?;
    }

    /// Away from the kink `|u| = eps` by 20 steps.
    #[test]
    fn tresca_derivatives_match_central_differences(
        g in 0.0..3.0f64, eps in 1e-4..1.0f64, radius in 0.0..3.0f64,
        angle in 0.0..std::f64::consts::TAU, pressure in -10.0..10.0f64,
    ) {
        let h = 1e-4 * eps;
        prop_assume!((radius * eps - eps).abs() > 20.0 * h);
        let c = ContactState::new(slip(radius * eps, angle), pressure);
        let p = TrescaParams::new(g, eps).unwrap();
        check_tangent(&Tresca, &c, &p, h, 1e-3, g / (radius * eps).max(eps), 0.0)?;
    }

    /// Away from the slip kink and from `p = 0` (the power's kink): `p <= -0.1`.
    #[test]
    fn howell_derivatives_match_central_differences(
        mu in 0.0..2.0f64, n in 0.3..2.0f64, eps in 1e-4..1.0f64, radius in 0.0..3.0f64,
        angle in 0.0..std::f64::consts::TAU, pressure in -10.0..-0.1f64,
    ) {
        let h = 1e-4 * eps;
        prop_assume!((radius * eps - eps).abs() > 20.0 * h);
        let c = ContactState::new(slip(radius * eps, angle), pressure);
        let p = HowellParams::new(mu, n, eps).unwrap();
        let q = -pressure;
        let slip_scale = mu * q.powf(n).max(1.0) / (radius * eps).max(eps);
        // central differences in p: error ~ hp^2 |d3 t/dp3| ~ (1e-5 q)^2 mu q^(n-3)
        check_tangent(&Howell, &c, &p, h, 1e-5 * q, slip_scale, mu * q.powf(n - 1.0).max(1.0))?;
    }

    /// Away from the kink `m(u') = mu_bar eps` by 20 weighted steps; any axis angle.
    #[test]
    fn orthotropic_coulomb_derivatives_match_central_differences(
        mu1 in 0.05..2.0f64, mu2 in 0.05..2.0f64, phi in -3.2..3.2f64, eps in 1e-4..1.0f64,
        radius in 0.0..3.0f64, angle in 0.0..std::f64::consts::TAU, pressure in -10.0..0.5f64,
    ) {
        let h = 1e-4 * eps;
        let p = OrthotropicCoulombParams::new([mu1, mu2], phi, eps).unwrap();
        let u = slip(radius * eps, angle);
        // weighted norm in the axes: m = |diag(mu) R(-phi) u|
        let (c1, s1) = (phi.cos(), phi.sin());
        let ua = [c1 * u[0] + s1 * u[1], -s1 * u[0] + c1 * u[1]];
        let m = ((mu1 * ua[0]).powi(2) + (mu2 * ua[1]).powi(2)).sqrt();
        let mbar = mu1.max(mu2);
        prop_assume!((m - mbar * eps).abs() > 20.0 * mbar * h);
        let c = ContactState::new(u, pressure);
        let scale = mbar.powi(2) * pressure.abs().max(1.0) / (mu1.min(mu2) * radius * eps).max(mbar * eps) * (mbar / mu1.min(mu2));
        check_tangent(&OrthotropicCoulomb, &c, &p, h, 1e-6 * pressure.abs().max(1.0), scale, mbar)?;
    }

    /// `AnyFrictionLaw` returns exactly what the law it names returns.
    #[test]
    fn any_friction_law_dispatches_exactly(
        k in 0usize..6, ux in -2.0..2.0f64, uy in -2.0..2.0f64, pressure in -5.0..1.0f64,
    ) {
        let s = FrictionSettings { mu: 0.4, eps: 0.3, mu2: 0.7, axis_angle: 0.5, bound: 0.9, exponent: 0.8, ..Default::default() };
        let kind = FrictionLawKind::all()[k];
        let any = AnyFrictionParams::of_kind(kind, &s).unwrap();
        prop_assert_eq!(any.kind(), kind);
        let c = ContactState::new([ux, uy], pressure);
        let (t, d) = (AnyFrictionLaw.traction(&c, &any), AnyFrictionLaw.traction_derivatives(&c, &any));
        let (t_direct, d_direct) = match kind.name() {
            "coulomb" => { let p = RegularisedCoulombParams::new(0.4, 0.3).unwrap(); (RegularisedCoulomb.traction(&c, &p), RegularisedCoulomb.traction_derivatives(&c, &p)) }
            "smooth-coulomb" => { let p = SmoothCoulombParams::new(0.4, 0.3).unwrap(); (SmoothCoulomb.traction(&c, &p), SmoothCoulomb.traction_derivatives(&c, &p)) }
            "tresca" => { let p = TrescaParams::new(0.9, 0.3).unwrap(); (Tresca.traction(&c, &p), Tresca.traction_derivatives(&c, &p)) }
            "howell" => { let p = HowellParams::new(0.4, 0.8, 0.3).unwrap(); (Howell.traction(&c, &p), Howell.traction_derivatives(&c, &p)) }
            "orthotropic-coulomb" => { let p = OrthotropicCoulombParams::new([0.4, 0.7], 0.5, 0.3).unwrap(); (OrthotropicCoulomb.traction(&c, &p), OrthotropicCoulomb.traction_derivatives(&c, &p)) }
            "frictionless" => ([0.0; 2], capstan_friction::TractionDerivatives::new([[0.0; 2]; 2], [0.0; 2])),
            other => panic!("a law without a direct counterpart: {other}"),
        };
        prop_assert_eq!(t, t_direct);
        prop_assert_eq!(d, d_direct);
    }
}

#[test]
fn isotropic_orthotropic_and_unit_howell_equal_regularised_coulomb() {
    let coulomb = RegularisedCoulombParams::new(0.45, 0.2).unwrap();
    let ortho = OrthotropicCoulombParams::new([0.45, 0.45], 1.1, 0.2).unwrap();
    let howell = HowellParams::new(0.45, 1.0, 0.2).unwrap();
    for (u, p) in [
        ([0.05, -0.1], -3.0),
        ([1.0, 0.4], -0.7),
        ([-0.3, 2.0], -12.0),
    ] {
        let c = ContactState::new(u, p);
        let t = RegularisedCoulomb.traction(&c, &coulomb);
        let d = RegularisedCoulomb.traction_derivatives(&c, &coulomb);
        for (t2, d2) in [
            (
                OrthotropicCoulomb.traction(&c, &ortho),
                OrthotropicCoulomb.traction_derivatives(&c, &ortho),
            ),
            (
                Howell.traction(&c, &howell),
                Howell.traction_derivatives(&c, &howell),
            ),
        ] {
            for i in 0..2 {
                // rotation and powf(1.0) round-off only
                assert_relative_eq!(t2[i], t[i], epsilon = 1e-14, max_relative = 1e-13);
                assert_relative_eq!(
                    d2.d_pressure[i],
                    d.d_pressure[i],
                    epsilon = 1e-14,
                    max_relative = 1e-13
                );
                for j in 0..2 {
                    assert_relative_eq!(
                        d2.d_slip[i][j],
                        d.d_slip[i][j],
                        epsilon = 1e-13,
                        max_relative = 1e-12
                    );
                }
            }
        }
    }
}

#[test]
fn orthotropic_resists_each_axis_with_its_coefficient_and_bends_the_traction() {
    let p = OrthotropicCoulombParams::new([0.2, 0.8], 0.0, 1e-6).unwrap();
    let t = OrthotropicCoulomb.traction(&ContactState::new([1.0, 0.0], -1.0), &p);
    assert_relative_eq!(t[0], -0.2, max_relative = 1e-15);
    let t: [f64; 2] = OrthotropicCoulomb.traction(&ContactState::new([1.0, 1.0], -1.0), &p);
    // on the ellipse (t1/mu1)^2 + (t2/mu2)^2 = p^2, and not parallel to the slip
    assert_relative_eq!(
        (t[0] / 0.2).powi(2) + (t[1] / 0.8).powi(2),
        1.0,
        max_relative = 1e-14
    );
    assert!(t[1] / t[0] > 10.0);
}

#[test]
fn smooth_coulomb_approaches_coulomb_at_second_order_in_eps() {
    let c = ContactState::new([0.0, 1.0], -2.0);
    let gap = |eps: f64| {
        let t = SmoothCoulomb.traction(&c, &SmoothCoulombParams::new(0.5, eps).unwrap());
        (t[1] + 1.0).abs()
    };
    let order = (gap(0.02) / gap(0.01)).log2();
    assert!((order - 2.0).abs() < 1e-3, "order {order}");
}

#[test]
fn tresca_ignores_pressure_and_howell_has_no_traction_in_tension() {
    let p = TrescaParams::new(0.3, 1e-3).unwrap();
    let a = Tresca.traction(&ContactState::new([0.0, 2.0], -100.0), &p);
    assert_eq!(a, Tresca.traction(&ContactState::new([0.0, 2.0], 5.0), &p));
    assert_eq!(a, [0.0, -0.3]);
    let h = HowellParams::new(0.5, 0.7, 1e-3).unwrap();
    assert_eq!(
        Howell.traction(&ContactState::new([0.0, 2.0], 3.0), &h),
        [0.0, 0.0]
    );
}

#[test]
fn parameter_errors_name_the_api_parameter() {
    let field = |e: FrictionError| match e {
        FrictionError::InvalidParameter { field, .. } => field,
        other => panic!("{other}"),
    };
    assert_eq!(
        field(SmoothCoulombParams::new(-1.0, 1.0).unwrap_err()),
        "mu"
    );
    assert_eq!(
        field(SmoothCoulombParams::new(1.0, 0.0).unwrap_err()),
        "eps"
    );
    assert_eq!(field(TrescaParams::new(-0.1, 1.0).unwrap_err()), "bound");
    assert_eq!(
        field(HowellParams::new(0.5, 0.0, 1.0).unwrap_err()),
        "exponent"
    );
    assert_eq!(
        field(HowellParams::new(0.5, f64::NAN, 1.0).unwrap_err()),
        "exponent"
    );
    assert_eq!(
        field(OrthotropicCoulombParams::new([0.0, 0.0], 0.0, 1.0).unwrap_err()),
        "mu2"
    );
    assert_eq!(
        field(OrthotropicCoulombParams::new([0.1, 0.2], f64::INFINITY, 1.0).unwrap_err()),
        "axis_angle"
    );
    let s = FrictionSettings {
        exponent: 3.0,
        ..Default::default()
    };
    assert_eq!(
        field(AnyFrictionParams::new("howell", &s).unwrap_err()),
        "exponent" // the facade maps it to `friction.exponent`
    );
    // unused settings are not checked
    assert!(AnyFrictionParams::new("coulomb", &s).is_ok());
    assert_eq!(
        FrictionLawKind::parse("orthotropic-coulomb").map(|k| k.name()),
        Some("orthotropic-coulomb")
    );
    assert_eq!(FrictionLawKind::parse("amontons"), None);
    let err = AnyFrictionParams::new("amontons", &s).unwrap_err();
    assert!(err.to_string().contains("amontons") && err.to_string().contains("tresca"));
    for k in FrictionLawKind::all() {
        assert!(FrictionLawKind::names().contains(k.name()));
    }
}
