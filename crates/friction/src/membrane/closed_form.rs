//! Closed forms of the membrane capstan equation (paper section 2.3), exact to rounding.
//!
//! Each is derived from the membrane equilibrium (see [`crate::membrane`]) and checked in the
//! tests against Dormand–Prince integration of that equilibrium built from the geometry layer.

use capstan_geometry::{Real, real};

/// The ordinary capstan equation `T0 exp(mu theta)`.
///
/// # Example
/// ```
/// use capstan_friction::membrane::closed_form::capstan;
/// assert!((capstan(0.5, 1.0, std::f64::consts::PI) - (0.5 * std::f64::consts::PI).exp()).abs() < 1e-15);
/// ```
pub fn capstan<F: Real>(mu: F, t0: F, angle: F) -> F {
    t0 * (mu * angle).exp()
}

/// The continuous turning angle of the ellipse `(a sin t, b cos t)`.
///
/// # Math
/// ```text
/// Psi'(t) = (v'u'' - u'v'')/(u'^2 + v'^2) = a b / (a^2 cos^2 t + b^2 sin^2 t)
/// Psi(t)  = atan2(b sin t, a cos t) + 2 pi round((t - atan2(b sin t, a cos t)) / (2 pi))
///         = atan((b/a) tan t) + pi round(t/pi)     (away from t = pi/2 + k pi)
/// ```
/// The `atan2` form never divides by `u' = a cos t`, so `t = pi/2` is an ordinary point
/// (paper-notes items 1 and 2); `Psi(pi/2 + alpha) = pi/2 + atan((a/b) tan alpha)`.
pub fn ellipse_turning_angle<F: Real>(a: F, b: F, t: F) -> F {
    let (s, c) = t.sin_cos();
    let base = (b * s).atan2(a * c);
    let two_pi = F::PI() + F::PI();
    base + two_pi * ((t - base) / two_pi).round()
}

/// Tension on the elliptical prism `(x1, a sin t, b cos t)` without loads.
///
/// # Math
/// ```text
/// T(theta) = T0 exp(mu (Psi(theta) - Psi(theta0)))     (eq. PrismEqn, any contact angle)
/// ```
pub fn ellipse_tension<F: Real>(mu: F, t0: F, a: F, b: F, theta0: F, theta: F) -> F {
    let x = mu * (ellipse_turning_angle(a, b, theta) - ellipse_turning_angle(a, b, theta0));
    (t0.ln() + x).exp()
}

/// The paper's tension ratio on `[-pi/4, pi/4]` of an ellipse: `exp(2 mu atan(b/a))`
/// (eq. PrismEqnPlot).
pub fn ellipse_quarter_ratio<F: Real>(mu: F, b_over_a: F) -> F {
    (real::<F>(2.0) * mu * b_over_a.atan()).exp()
}

/// Gravity and steady speed on the circular cylinder `(x1, a sin t, a cos t)` (eq. capGrav).
///
/// # Math
/// With `w = rho_l g` the weight per unit length, `c = rho_l V^2`, `A = (1 - mu^2)/(1 + mu^2)`,
/// `B = 2 mu/(1 + mu^2)`, the equilibrium `dT/dtheta = mu (T - c) + w a (mu cos theta - sin theta)`
/// has the solution
/// ```text
/// T_p(theta) = c + w a (A cos theta + B sin theta)
/// T(theta)   = T_p(theta) + (T0 - T_p(theta0)) exp(mu (theta - theta0))
/// R(theta)   = (T - c)/a + w cos theta     (normal reaction per unit length)
/// ```
/// With `theta0 = 0` and `c = 0` this is the paper's eq. capGrav.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CylinderGravity<F> {
    /// Cylinder radius `a`.
    pub radius: F,
    /// Coefficient of friction.
    pub mu: F,
    /// Weight per unit length `w = rho h l g`.
    pub weight_per_length: F,
    /// `c = rho_l V^2`.
    pub speed_tension: F,
}

impl<F: Real> CylinderGravity<F> {
    fn particular(&self, theta: F) -> F {
        let one = F::one();
        let m2 = self.mu * self.mu;
        let (s, c) = theta.sin_cos();
        let a = (one - m2) / (one + m2);
        let b = real::<F>(2.0) * self.mu / (one + m2);
        self.speed_tension + self.weight_per_length * self.radius * (a * c + b * s)
    }
    /// `T(theta)` with `T(theta0) = t0`.
    pub fn tension(&self, t0: F, theta0: F, theta: F) -> F {
        let tp = self.particular(theta);
        tp + (t0 - self.particular(theta0)) * (self.mu * (theta - theta0)).exp()
    }
    /// The normal reaction per unit length `R = (T - c)/a + w cos theta`.
    pub fn reaction(&self, theta: F, tension: F) -> F {
        (tension - self.speed_tension) / self.radius + self.weight_per_length * theta.cos()
    }
}

/// The development angle `phi(theta) = sin(alpha) theta` of the right circular cone.
pub fn right_circular_cone_phi<F: Real>(half_angle: F, theta: F) -> F {
    half_angle.sin() * theta
}

/// Tension on the right circular cone of half-aperture `alpha` (Theorem 2).
///
/// # Math
/// ```text
/// T(theta) = T0 exp(mu cot(alpha) (sin(sin(alpha) theta) - sin(sin(alpha) theta0)))
/// ```
/// valid while `|sin(alpha) theta| < pi/2` on the interval (paper-notes item 5; `phi` is
/// measured from 0 even when `theta0 != 0`). `alpha -> 0` gives `T0 exp(mu (theta - theta0))`,
/// `alpha -> pi/2` gives `T0`.
pub fn right_circular_cone_tension<F: Real>(mu: F, t0: F, half_angle: F, theta0: F, theta: F) -> F {
    let s = half_angle.sin();
    let x = mu / half_angle.tan() * ((s * theta).sin() - (s * theta0).sin());
    (t0.ln() + x).exp()
}

/// The exponent `cot(alpha) (sin(sin(alpha) theta) - sin(sin(alpha) theta0))` of the right
/// circular cone for `mu = 1`.
pub fn right_circular_cone_exponent<F: Real>(half_angle: F, theta0: F, theta: F) -> F {
    let s = half_angle.sin();
    ((s * theta).sin() - (s * theta0).sin()) / half_angle.tan()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

    #[test]
    fn ellipse_turning_angle_is_continuous_through_pi_over_2() {
        let (a, b) = (2.0, 1.0);
        let at = |t: f64| ellipse_turning_angle(a, b, t);
        assert!((at(FRAC_PI_2) - FRAC_PI_2).abs() < 1e-15);
        let h = 1e-7;
        assert!((at(FRAC_PI_2 + h) - at(FRAC_PI_2 - h)).abs() < 1e-6);
        // Psi(pi/2 + alpha) = pi/2 + atan((a/b) tan alpha) (paper-notes item 2)
        let alpha = FRAC_PI_4;
        assert!((at(FRAC_PI_2 + alpha) - (FRAC_PI_2 + (a / b * alpha.tan()).atan())).abs() < 1e-15);
        // full turns add 2 pi
        assert!((at(0.3 + 4.0 * PI) - at(0.3) - 4.0 * PI).abs() < 1e-13);
    }

    #[test]
    fn cylinder_gravity_matches_cap_grav_as_printed() {
        // T_g = (T0 - a h l rho g (1-mu^2)/(1+mu^2)) e^{mu theta} + a h l rho g ((1-mu^2)/(1+mu^2) cos + 2mu/(1+mu^2) sin)
        let (a, mu, w, t0): (f64, f64, f64, f64) = (2.0, 0.3, 0.7, 5.0);
        let cg = CylinderGravity {
            radius: a,
            mu,
            weight_per_length: w,
            speed_tension: 0.0,
        };
        for theta in [0.0_f64, 0.4, 1.3, 2.9] {
            let k = (1.0 - mu * mu) / (1.0 + mu * mu);
            let printed = (t0 - a * w * k) * (mu * theta).exp()
                + a * w * (k * theta.cos() + 2.0 * mu / (1.0 + mu * mu) * theta.sin());
            let ours = cg.tension(t0, 0.0, theta);
            assert!((ours - printed).abs() < 1e-14 * printed.abs(), "{theta}");
        }
    }

    #[test]
    fn cone_limits_are_capstan_and_no_gain() {
        let (mu, theta): (f64, f64) = (0.4, 2.0);
        let narrow = right_circular_cone_tension(mu, 1.0, 1e-7, 0.0, theta);
        assert!((narrow - (mu * theta).exp()).abs() < 1e-12);
        let flat = right_circular_cone_tension(mu, 1.0, FRAC_PI_2 - 1e-9, 0.0, theta);
        assert!((flat - 1.0).abs() < 1e-9);
    }
}
