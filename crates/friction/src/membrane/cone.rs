//! Theorem 2: the membrane on a general cone `x1 (1, ubar(x2), vbar(x2))`.

use std::f64::consts::FRAC_PI_2;

use capstan_geometry::ProfileCurve;

use super::problem::{MembraneProblem, Method, TensionProfile, exp_tension};
use super::validity::{first_failure, grid, merged};
use crate::error::{FrictionError, degenerate};
use crate::quadrature::{GaussKronrod, gauss_kronrod_15};

/// Relative accuracy of a panel of the cone's nested quadrature (against `int|f|` over the
/// panel): nine times the rounding floor `50 eps` of the Gauss–Kronrod error estimate.
const RELATIVE_TOLERANCE: f64 = 1e-13;

/// Work budget of the cone's nested quadrature: panels over all of `[theta0, theta_max]`
/// (the default of `membrane.max_subdivisions`).
pub const MAX_CONE_PANELS: usize = crate::quadrature::DEFAULT_MAX_SUBDIVISIONS;

/// Local quantities of a cone `x1 w(t)`, `w = (1, ubar, vbar)`, from the profile jet.
///
/// # Math
/// ```text
/// c    = w' x w,  |c|^2 = ubar'^2 + vbar'^2 + (vbar ubar' - ubar vbar')^2,  rbar = |w|
/// D    = w'' . (w' x w) = vbar' ubar'' - ubar' vbar''
/// phi' = |w' x w| / |w|^2                      development angle rate
/// e'   = |w| D / |w' x w|^2                    Theorem 2's integrand without cos(phi)
/// H    = |w|^2 D / (2 x1 |w' x w|^3)           mean curvature (paper's sign)
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConePoint {
    /// `phi'`.
    pub phi_rate: f64,
    /// `|w| D / |w' x w|^2`.
    pub exponent_rate: f64,
    /// `D = w'' . (w' x w)`.
    pub convexity: f64,
    /// `H` at `x1 = 1`.
    pub mean_curvature: f64,
}

impl ConePoint {
    /// From the profile jet `[[ubar, ubar', ...], [vbar, vbar', ...]]`.
    pub fn from_jet(p: [[f64; 4]; 2]) -> Self {
        let (u, du, ddu) = (p[0][0], p[0][1], p[0][2]);
        let (v, dv, ddv) = (p[1][0], p[1][1], p[1][2]);
        let cross = [du * v - dv * u, dv, -du];
        let c2 = cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2];
        let r2 = 1.0 + u * u + v * v;
        let d = dv * ddu - du * ddv;
        Self {
            phi_rate: c2.sqrt() / r2,
            exponent_rate: r2.sqrt() * d / c2,
            convexity: d,
            mean_curvature: r2 * d / (2.0 * c2 * c2.sqrt()),
        }
    }
}

/// A membrane on the general cone over `(ubar, vbar)` (Theorem 2).
///
/// # Math
/// ```text
/// T(theta) = T0 exp(mu int_{theta0}^{theta} |w| D cos(phi) / |w' x w|^2 dt)
/// phi(t)   = int_0^t |w' x w| / |w|^2 dt        (measured from 0 even when theta0 != 0)
/// ```
/// Valid while `|phi| < pi/2` (the developed strip is a straight line) and `D > 0` (positive
/// mean curvature) on the interval (paper-notes items 5 and 6). The nested integral is
/// computed by adaptive Gauss–Kronrod: each panel integrates `phi'` from its start to each
/// node, so `phi` is as accurate as the outer rule.
#[derive(Debug, Clone, Copy)]
pub struct ConeMembrane<'a, C: ?Sized> {
    profile: &'a C,
    tolerance: f64,
    max_panels: usize,
}

impl<'a, C: ProfileCurve<f64> + ?Sized> ConeMembrane<'a, C> {
    /// The membrane on the cone over `profile`, integrating to absolute tolerance `1e-13`.
    pub fn new(profile: &'a C) -> Self {
        Self {
            profile,
            tolerance: 1e-13,
            max_panels: MAX_CONE_PANELS,
        }
    }

    /// The same within a budget of `max_subdivisions` quadrature panels
    /// (`membrane.max_subdivisions`, default `2^16`).
    pub fn with_max_subdivisions(&self, max_subdivisions: usize) -> Self {
        Self {
            profile: self.profile,
            tolerance: self.tolerance,
            max_panels: max_subdivisions,
        }
    }

    fn point(&self, t: f64) -> Result<ConePoint, FrictionError> {
        let p = ConePoint::from_jet(self.profile.profile_jet(t));
        (p.phi_rate.is_finite() && p.exponent_rate.is_finite() && p.phi_rate > 0.0)
            .then_some(p)
            .ok_or_else(|| degenerate("cone profile not regular or not finite", [1.0, t, 0.0]))
    }

    /// `phi(t) = int_0^t phi'`.
    ///
    /// # Errors
    /// Degenerate profile; quadrature failure.
    pub fn phi(&self, t: f64) -> Result<f64, FrictionError> {
        Ok(GaussKronrod {
            max_panels: self.max_panels,
            ..GaussKronrod::default()
        }
        .integrate(|s| Ok(self.point(s)?.phi_rate), 0.0, t)?
        .value)
    }

    /// Integrates `(exponent, phi)` over `[a, b]` from `phi(a)`, adaptively and depth first.
    ///
    /// A panel is accepted when each error estimate is below
    /// `max(tol_per_length (b - a), RELATIVE_TOLERANCE int_a^b |f|)`: the Gauss–Kronrod
    /// estimate never falls below its rounding floor `50 eps int|f|`, so an absolute tolerance
    /// alone is out of reach for large integrands (a needle cone of half-aperture `alpha` has
    /// `|w| D / |w' x w|^2 ~ cot(alpha)`: `1e3` at `alpha = 1e-3`, and bisection then ran to
    /// depth 40 on every branch). `panels` counts the panels against [`MAX_CONE_PANELS`].
    #[allow(clippy::too_many_arguments)] // the recursion's state, private
    fn segment(
        &self,
        a: f64,
        b: f64,
        phi_a: f64,
        tol_per_length: f64,
        depth: usize,
        bad: &mut Option<f64>,
        panels: &mut usize,
    ) -> Result<(f64, f64), FrictionError> {
        *panels += 1;
        let mut phi_rate = |s: f64| Ok(self.point(s)?.phi_rate);
        let phi_panel = gauss_kronrod_15(&mut phi_rate, a, b)?;
        let exponent = gauss_kronrod_15(
            &mut |x: f64| {
                let p = self.point(x)?;
                if p.convexity <= 0.0 && bad.is_none_or(|t| x < t) {
                    *bad = Some(x);
                }
                let phi =
                    phi_a + gauss_kronrod_15(&mut |s| Ok(self.point(s)?.phi_rate), a, x)?.integral;
                Ok(p.exponent_rate * phi.cos())
            },
            a,
            b,
        )?;
        let tol = tol_per_length * (b - a).abs();
        let accepted = |p: &crate::quadrature::Panel<f64>| {
            p.error <= tol.max(RELATIVE_TOLERANCE * p.abs_integral)
        };
        if *panels > self.max_panels {
            return Err(FrictionError::QuadratureNotConverged {
                a,
                b,
                error: exponent.error,
                panels: *panels,
                limit: self.max_panels,
            });
        }
        if (accepted(&exponent) && accepted(&phi_panel)) || depth >= 40 {
            if depth >= 40
                && exponent.error > 1e3 * tol.max(RELATIVE_TOLERANCE * exponent.abs_integral)
            {
                return Err(FrictionError::QuadratureNotConverged {
                    a,
                    b,
                    error: exponent.error,
                    panels: 1 << depth.min(30),
                    limit: self.max_panels,
                });
            }
            return Ok((exponent.integral, phi_a + phi_panel.integral));
        }
        let m = 0.5 * (a + b);
        let (e1, phi_m) = self.segment(a, m, phi_a, tol_per_length, depth + 1, bad, panels)?;
        let (e2, phi_b) = self.segment(m, b, phi_m, tol_per_length, depth + 1, bad, panels)?;
        Ok((e1 + e2, phi_b))
    }

    /// The exponent `int_{theta0}^{theta_i} |w| D cos(phi)/|w' x w|^2` at sorted angles
    /// `thetas >= theta0`, with the validity checks of Theorem 2.
    ///
    /// # Errors
    /// [`FrictionError::NonPositiveCurvature`] where `D <= 0`; [`FrictionError::DevelopmentLimit`]
    /// where `|phi| >= pi/2`; degenerate profile; quadrature failure.
    pub fn exponents(&self, theta0: f64, thetas: &[f64]) -> Result<Vec<f64>, FrictionError> {
        let end = thetas.last().copied().unwrap_or(theta0).max(theta0);
        let tol_per_length = self.tolerance / (end - theta0).abs().max(1.0);
        let mut bad = None;
        let mut panels = 0;
        let mut phi = self.phi(theta0)?;
        let mut phis = Vec::with_capacity(thetas.len());
        let mut out = Vec::with_capacity(thetas.len());
        let (mut at, mut sum) = (theta0, 0.0);
        for &t in thetas {
            if t > at {
                let (e, phi_t) =
                    self.segment(at, t, phi, tol_per_length, 0, &mut bad, &mut panels)?;
                sum += e;
                phi = phi_t;
                at = t;
            }
            out.push(sum);
            phis.push(phi);
        }
        // Positive mean curvature: D > 0 at the samples and every node visited.
        let mut checks = merged(thetas.to_vec(), &[theta0]);
        if let Some(b) = bad {
            checks = merged(checks, &grid(theta0, b, 64));
        }
        checks.retain(|&t| t >= theta0 && t <= end);
        if let Some(angle) = first_failure(&checks, |t| Ok(self.point(t)?.convexity > 0.0))? {
            return Err(FrictionError::NonPositiveCurvature {
                angle,
                mean_curvature: self.point(angle)?.mean_curvature,
            });
        }
        // |phi| < pi/2: phi increases, so only its ends matter.
        let phi0 = self.phi(theta0)?;
        if phi0 <= -FRAC_PI_2 {
            return Err(FrictionError::DevelopmentLimit {
                angle: theta0,
                phi: phi0,
            });
        }
        if let Some(i) = phis.iter().position(|&p| p >= FRAC_PI_2) {
            let (lo, hi) = (if i == 0 { theta0 } else { thetas[i - 1] }, thetas[i]);
            let angle = first_failure(&[lo, hi], |t| Ok(self.phi(t)? < FRAC_PI_2))?.unwrap_or(hi);
            return Err(FrictionError::DevelopmentLimit {
                angle,
                phi: self.phi(angle)?,
            });
        }
        Ok(out)
    }

    /// The tension profile (no loads act on cones in Theorem 2).
    ///
    /// # Errors
    /// [`FrictionError::InvalidParameter`] for loads (`loads.gravity`, `loads.speed`) or other
    /// bad parameters; see [`ConeMembrane::exponents`].
    pub fn tension_profile(
        &self,
        problem: &MembraneProblem,
    ) -> Result<TensionProfile, FrictionError> {
        validate_cone_problem(problem)?;
        let thetas = problem.thetas();
        let e = self.exponents(problem.theta0, &thetas)?;
        let tension = thetas
            .iter()
            .zip(&e)
            .map(|(&t, &x)| exp_tension(problem.t0, 0.0, problem.mu * x, t))
            .collect::<Result<_, _>>()?;
        Ok(TensionProfile {
            theta: thetas,
            tension,
            method: Method::Quadrature,
        })
    }
}

/// Theorem 2 has no external loads: weight or steady speed on a cone is rejected.
pub(crate) fn validate_cone_problem(problem: &MembraneProblem) -> Result<(), FrictionError> {
    problem.validate()?;
    let l = &problem.loads;
    if l.weight_per_length() != 0.0 {
        return Err(FrictionError::InvalidParameter {
            field: "loads.gravity",
            value: l.gravity,
            allowed: "0 on cones (Theorem 2 has no loads; or loads.density = 0)",
        });
    }
    if l.speed_tension() != 0.0 {
        return Err(FrictionError::InvalidParameter {
            field: "loads.speed",
            value: l.speed,
            allowed: "0 on cones (Theorem 2 has no loads; or loads.density = 0)",
        });
    }
    Ok(())
}
