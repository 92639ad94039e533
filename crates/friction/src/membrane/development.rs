//! The development of a general cone onto the plane (paper section 2.2), on which Theorem 2 is
//! built.

use capstan_geometry::ProfileCurve;

use super::cone::ConeMembrane;
use crate::error::{FrictionError, check, degenerate};

/// The development map `(x1, x2) -> (chi1, chi2)` of the cone `x1 w(x2)`, `w = (1, ubar, vbar)`,
/// at one point, with its Jacobian.
///
/// # Math
/// ```text
/// rbar = |w| = sqrt(1 + ubar^2 + vbar^2)
/// phi(x2) = int_0^{x2} |w' x w| / |w|^2 dt      the angle of the developed generator
/// chi1 = x1 rbar cos(phi),  chi2 = x1 rbar sin(phi)
/// J = [ rbar cos(phi)   x1 (rbar' cos(phi) - rbar phi' sin(phi)) ]
///     [ rbar sin(phi)   x1 (rbar' sin(phi) + rbar phi' cos(phi)) ]
/// ```
/// The map is an isometry: `J^T J = a_ab` (the cone's first fundamental form), so the
/// developed coordinates have the identity metric; `det J = x1 rbar^2 phi' > 0` for `x1 > 0`.
/// For the right circular cone of half-aperture `alpha`: `rbar = sec(alpha)`, `rbar' = 0`,
/// `phi = sin(alpha) x2`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DevelopmentPoint {
    /// `phi(x2)`, measured from `x2 = 0`.
    pub phi: f64,
    /// `phi'(x2) = |w' x w| / |w|^2`.
    pub phi_rate: f64,
    /// `rbar = |w|`.
    pub radius: f64,
    /// `rbar' = (ubar ubar' + vbar vbar') / rbar`.
    pub radius_rate: f64,
    /// `(chi1, chi2)`.
    pub chi: [f64; 2],
    /// `jacobian[i][j] = d chi_(i+1) / d x_(j+1)`.
    pub jacobian: [[f64; 2]; 2],
}

/// The development map of the cone over `profile` at `x1` and each of `thetas`.
///
/// # Errors
/// [`FrictionError::InvalidParameter`] naming `x1` unless `x1 > 0`; a degenerate profile
/// (`w' x w = 0`); [`FrictionError::QuadratureNotConverged`] when the quadrature of `phi`
/// exceeds `max_subdivisions` panels.
pub fn development<C: ProfileCurve<f64> + ?Sized>(
    profile: &C,
    x1: f64,
    thetas: &[f64],
    max_subdivisions: usize,
) -> Result<Vec<DevelopmentPoint>, FrictionError> {
    check("x1", x1, "(0, inf)", |v| v > 0.0)?;
    let cone = ConeMembrane::new(profile).with_max_subdivisions(max_subdivisions);
    thetas
        .iter()
        .map(|&t| {
            let p = profile.profile_jet(t);
            let (u, du, v, dv) = (p[0][0], p[0][1], p[1][0], p[1][1]);
            let cross = [du * v - dv * u, dv, -du];
            let c = (cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]).sqrt();
            let radius = (1.0 + u * u + v * v).sqrt();
            if !(c > 0.0 && c.is_finite() && radius.is_finite()) {
                return Err(degenerate(
                    "cone profile not regular or not finite",
                    [x1, t, 0.0],
                ));
            }
            let phi_rate = c / (radius * radius);
            let radius_rate = (u * du + v * dv) / radius;
            let phi = cone.phi(t)?;
            let (s, co) = phi.sin_cos();
            Ok(DevelopmentPoint {
                phi,
                phi_rate,
                radius,
                radius_rate,
                chi: [x1 * radius * co, x1 * radius * s],
                jacobian: [
                    [radius * co, x1 * (radius_rate * co - radius * phi_rate * s)],
                    [radius * s, x1 * (radius_rate * s + radius * phi_rate * co)],
                ],
            })
        })
        .collect()
}
