//! The continuous turning angle `Psi` of a prism's profile (paper-notes item 1).

use std::f64::consts::FRAC_PI_2;

use capstan_geometry::ProfileCurve;

use super::validity::{first_failure, grid, merged};
use crate::error::{FrictionError, degenerate};
use crate::quadrature::{DEFAULT_MAX_SUBDIVISIONS, GaussKronrod};

/// Local quantities of a profile `(u(t), v(t))` from its jet.
///
/// # Math
/// ```text
/// a_22 = u'^2 + v'^2
/// Psi' = (v'u'' - u'v'') / (u'^2 + v'^2) = kappa sqrt(a_22)      turning rate
/// H    = (v'u'' - u'v'') / (2 a_22^(3/2)) = kappa / 2              mean curvature of the prism
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProfilePoint {
    /// `(u', v')`.
    pub tangent: [f64; 2],
    /// `a_22 = u'^2 + v'^2`.
    pub a22: f64,
    /// `Psi'`.
    pub turning_rate: f64,
    /// `H` (paper's sign: positive on a convex, clockwise profile).
    pub mean_curvature: f64,
}

impl ProfilePoint {
    /// From the jet `[[u, u', u'', u'''], [v, ...]]`.
    pub fn from_jet(p: [[f64; 4]; 2]) -> Self {
        let (du, dv, ddu, ddv) = (p[0][1], p[1][1], p[0][2], p[1][2]);
        let a22 = du * du + dv * dv;
        let cross = dv * ddu - du * ddv;
        Self {
            tangent: [du, dv],
            a22,
            turning_rate: cross / a22,
            mean_curvature: cross / (2.0 * a22 * a22.sqrt()),
        }
    }
}

/// The clockwise angle from tangent `a` to tangent `b`, in `(-pi, pi]`.
pub(crate) fn clockwise_angle(a: [f64; 2], b: [f64; 2]) -> f64 {
    -(a[0] * b[1] - a[1] * b[0]).atan2(a[0] * b[0] + a[1] * b[1])
}

fn point<C: ProfileCurve<f64> + ?Sized>(
    profile: &C,
    t: f64,
) -> Result<ProfilePoint, FrictionError> {
    let p = ProfilePoint::from_jet(profile.profile_jet(t));
    (p.turning_rate.is_finite() && p.a22 > 0.0)
        .then_some(p)
        .ok_or_else(|| {
            degenerate(
                "profile not regular (u' = v' = 0) or not finite",
                [0.0, t, 0.0],
            )
        })
}

/// `Psi(theta_i) - Psi(theta0)` at sorted angles `thetas` (all `>= theta0`), checking that the
/// profile is convex (`H > 0`) on `[theta0, thetas.last()]`.
///
/// # Math
/// `Psi' = (v'u'' - u'v'')/(u'^2 + v'^2)` is integrated by adaptive Gauss–Kronrod with every
/// panel's turning angle below `pi/2`; on such a panel the increment equals the clockwise
/// `atan2` angle between the end tangents, which gives each value to rounding (the quadrature
/// fixes the branch, the `atan2` the digits). Zeros of `u'` need no care: nothing divides by it.
///
/// # Errors
/// [`FrictionError::NonPositiveCurvature`] at the first angle with `H <= 0`; a degenerate or
/// non-finite profile; quadrature failure.
pub fn turning_angles<C: ProfileCurve<f64> + ?Sized>(
    profile: &C,
    theta0: f64,
    thetas: &[f64],
) -> Result<Vec<f64>, FrictionError> {
    turning_angles_within(profile, theta0, thetas, DEFAULT_MAX_SUBDIVISIONS)
}

/// [`turning_angles`] within a budget of `max_subdivisions` quadrature panels
/// (`membrane.max_subdivisions`).
///
/// # Errors
/// As [`turning_angles`]; [`FrictionError::QuadratureNotConverged`] when the budget runs out.
pub fn turning_angles_within<C: ProfileCurve<f64> + ?Sized>(
    profile: &C,
    theta0: f64,
    thetas: &[f64],
    max_subdivisions: usize,
) -> Result<Vec<f64>, FrictionError> {
    let end = thetas.last().copied().unwrap_or(theta0).max(theta0);
    let mut bad: Option<f64> = None;
    let gk = GaussKronrod {
        max_panel_integral: FRAC_PI_2,
        max_panels: max_subdivisions,
        ..Default::default()
    };
    let q = gk.integrate(
        |t| {
            let p = point(profile, t)?;
            if p.turning_rate <= 0.0 && bad.is_none_or(|b| t < b) {
                bad = Some(t);
            }
            Ok(p.turning_rate)
        },
        theta0,
        end,
    )?;
    let convex = |t: f64| Ok(point(profile, t)?.turning_rate > 0.0);
    let mut checks = merged(thetas.to_vec(), &[theta0]);
    if let Some(b) = bad {
        checks = merged(checks, &grid(theta0, b, 64));
    }
    checks.retain(|&t| t >= theta0 && t <= end);
    if let Some(angle) = first_failure(&checks, convex)? {
        return Err(FrictionError::NonPositiveCurvature {
            angle,
            mean_curvature: point(profile, angle)?.mean_curvature,
        });
    }
    // Cumulative turning angle at the panel starts, snapped to the atan2 of the tangents.
    let mut starts = Vec::with_capacity(q.panels.len());
    let mut psi = 0.0;
    for panel in &q.panels {
        let ta = point(profile, panel.a)?.tangent;
        starts.push((panel.a, ta, psi));
        let exact = clockwise_angle(ta, point(profile, panel.b)?.tangent);
        let tol = 1e-6 * (1.0 + panel.integral.abs());
        psi += if (exact - panel.integral).abs() <= tol {
            exact
        } else {
            panel.integral
        };
    }
    thetas
        .iter()
        .map(|&t| {
            if t <= theta0 {
                return Ok(0.0);
            }
            let i = starts.partition_point(|s| s.0 <= t).saturating_sub(1);
            let (_, ta, base) = starts[i];
            Ok(base + clockwise_angle(ta, point(profile, t)?.tangent))
        })
        .collect()
}
