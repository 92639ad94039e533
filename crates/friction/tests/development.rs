//! The cone's development map (paper section 2.2) against closed forms for the right circular
//! cone, and the isometry `J^T J = a_ab` on a general cone.

use capstan_friction::FrictionError;
use capstan_friction::membrane::development;
use capstan_geometry::{ExpressionProfile, GeneralCone, RightCircularCone, Surface};

const THETAS: [f64; 7] = [-2.0, -1.1, -0.3, 0.0, 0.4, 1.3, 2.5];

#[test]
fn right_circular_cone_development_matches_closed_forms() {
    for alpha in [0.1_f64, 0.5, 1.0, 1.4] {
        let cone = RightCircularCone::new(alpha).unwrap();
        for x1 in [0.5, 2.0] {
            let d = development(&cone, x1, &THETAS, 1 << 16).unwrap();
            for (t, p) in THETAS.iter().zip(&d) {
                let (sa, sec) = (alpha.sin(), 1.0 / alpha.cos());
                let phi = sa * t;
                let (s, c) = phi.sin_cos();
                // closed forms: round-off only (phi by Gauss–Kronrod of a constant rate)
                let close = |a: f64, b: f64, what: &str| {
                    assert!(
                        (a - b).abs() <= 1e-12 * b.abs().max(1.0),
                        "alpha {alpha}, x1 {x1}, theta {t}: {what} {a} vs {b}"
                    );
                };
                close(p.phi, phi, "phi");
                close(p.phi_rate, sa, "phi'");
                close(p.radius, sec, "rbar");
                close(p.radius_rate, 0.0, "rbar'");
                close(p.chi[0], x1 * sec * c, "chi1");
                close(p.chi[1], x1 * sec * s, "chi2");
                close(p.jacobian[0][0], sec * c, "J11");
                close(p.jacobian[0][1], -x1 * alpha.tan() * s, "J12");
                close(p.jacobian[1][0], sec * s, "J21");
                close(p.jacobian[1][1], x1 * alpha.tan() * c, "J22");
            }
        }
    }
}

#[test]
fn development_is_an_isometry_of_a_general_cone() {
    // J^T J equals the first fundamental form of sigma = x1 (1, ubar, vbar): the developed
    // coordinates have the identity metric (paper: F_I^phi = delta).
    let profile = ExpressionProfile::parse("0.5*sin(t) + 0.1*sin(2*t)", "0.4*cos(t)").unwrap();
    let cone = GeneralCone::new(profile.clone());
    for x1 in [0.7, 1.0, 3.0] {
        let d = development(&profile, x1, &THETAS, 1 << 16).unwrap();
        for (t, p) in THETAS.iter().zip(&d) {
            let a = Surface::<f64>::geometry(&cone, [x1, *t])
                .unwrap()
                .first_form;
            let j = p.jacobian;
            for al in 0..2 {
                for be in 0..2 {
                    let jtj = j[0][al] * j[0][be] + j[1][al] * j[1][be];
                    assert!(
                        (jtj - a[al][be]).abs() <= 1e-12 * a[al][be].abs().max(1.0),
                        "x1 {x1}, theta {t}: (J^T J)[{al}][{be}] = {jtj}, a = {}",
                        a[al][be]
                    );
                }
            }
            let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
            let expected = x1 * p.radius * p.radius * p.phi_rate;
            assert!(det > 0.0 && (det / expected - 1.0).abs() < 1e-12);
        }
    }
}

#[test]
fn development_needs_a_positive_x1() {
    let cone = RightCircularCone::new(0.5).unwrap();
    let err = development(&cone, 0.0, &[0.0], 1 << 16).unwrap_err();
    assert!(
        matches!(err, FrictionError::InvalidParameter { field: "x1", .. }),
        "{err}"
    );
}

#[test]
fn developed_second_form_is_the_printed_matrix() {
    // F_II^phi = J^-T b J^-1 = -(rbar^2 D / (x1 |w' x w|^3)) [[s^2, -s c], [-s c, c^2]],
    // D = vbar' ubar'' - ubar' vbar'' (paper section 2.2).
    let (u, v) = ("0.5*sin(t) + 0.1*sin(2*t)", "0.4*cos(t)");
    let profile = ExpressionProfile::parse(u, v).unwrap();
    let cone = GeneralCone::new(profile.clone());
    let x1 = 1.7;
    let d = development(&profile, x1, &THETAS, 1 << 16).unwrap();
    for (t, p) in THETAS.iter().zip(&d) {
        let b = Surface::<f64>::geometry(&cone, [x1, *t])
            .unwrap()
            .second_form;
        let j = p.jacobian;
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        let inv = [
            [j[1][1] / det, -j[0][1] / det],
            [-j[1][0] / det, j[0][0] / det],
        ];
        let jet = capstan_geometry::ProfileCurve::<f64>::profile_jet(&profile, *t);
        let (ub, dub, ddub) = (jet[0][0], jet[0][1], jet[0][2]);
        let (vb, dvb, ddvb) = (jet[1][0], jet[1][1], jet[1][2]);
        let c2 = dub * dub + dvb * dvb + (vb * dub - ub * dvb).powi(2);
        let scale = -(1.0 + ub * ub + vb * vb) * (dvb * ddub - dub * ddvb) / (x1 * c2.powf(1.5));
        let (s, c) = p.phi.sin_cos();
        let printed = [[s * s, -s * c], [-s * c, c * c]].map(|r| r.map(|x| scale * x));
        for i in 0..2 {
            for k in 0..2 {
                let mut f = 0.0;
                for a in 0..2 {
                    for e in 0..2 {
                        f += inv[a][i] * b[a][e] * inv[e][k];
                    }
                }
                assert!(
                    (f - printed[i][k]).abs() <= 1e-12 * scale.abs().max(1.0),
                    "theta {t}: F_II^phi[{i}][{k}] = {f}, printed {}",
                    printed[i][k]
                );
            }
        }
    }
}
