//! Regularised Coulomb friction (Kikuchi–Oden).

use capstan_geometry::Real;

use crate::error::{FrictionError, check_non_negative, check_width};
use crate::friction_law::{ContactState, FrictionLaw, TractionDerivatives};
use crate::registration::{RegisteredLaw, bind};
use crate::slip_direction::{along, coulomb_traction, direction_kernel, slip_norm_squared};

/// Regularised Coulomb friction (Kikuchi–Oden): Coulomb above a slip `eps`, linear below.
///
/// # Math
/// ```text
/// t(u) = mu p u / |u|    if |u| >= eps        u: tangential slip (physical length)
/// t(u) = mu p u / eps    if |u| <  eps        p: normal stress sigma_n (< 0 in contact)
/// ```
/// `t` is continuous at `|u| = eps`, but its tangent jumps there: Newton needs the line search.
/// The derivatives are
/// ```text
/// |u| >= eps:  dt_i/du_j = mu p (delta_ij / |u| - u_i u_j / |u|^3),   dt/dp = mu u / |u|
/// |u| <  eps:  dt_i/du_j = mu p delta_ij / eps,                       dt/dp = mu u / eps
/// ```
/// With `p < 0` the traction opposes the slip and `|t| <= mu |p|`.
///
/// # References
/// Paper section 3, eq. CoulombOden; Kikuchi and Oden, *Contact problems in elasticity*, 11.3.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RegularisedCoulomb;

/// Parameters of [`RegularisedCoulomb`] at one point: `mu >= 0` and `eps > 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RegularisedCoulombParams<F> {
    mu: F,
    eps: F,
}

impl<F: Real> RegularisedCoulombParams<F> {
    /// Coefficient of friction `mu` and regularisation width `eps` (physical slip length).
    ///
    /// # Errors
    /// [`FrictionError::InvalidParameter`] naming `mu` unless `mu` is finite and
    /// `>= 0`, or `eps` unless `eps` is finite and `> 0`.
    pub fn new(mu: F, eps: F) -> Result<Self, FrictionError> {
        check_non_negative("mu", mu)?;
        check_width(eps)?;
        Ok(Self { mu, eps })
    }
    /// The coefficient of friction `mu`.
    pub fn mu(&self) -> F {
        self.mu
    }
    /// The regularisation width `eps`.
    pub fn eps(&self) -> F {
        self.eps
    }
}

impl<F: Real> FrictionLaw<F> for RegularisedCoulomb {
    type Params = RegularisedCoulombParams<F>;

    fn traction(&self, c: &ContactState<F>, p: &Self::Params) -> [F; 2] {
        // t = mu p u / max(|u|, eps)
        coulomb_traction(c, p.mu, slip_norm_squared(c.slip).sqrt().max(p.eps))
    }

    fn traction_derivatives(
        &self,
        c: &ContactState<F>,
        p: &Self::Params,
    ) -> TractionDerivatives<F> {
        let (_, d_slip, inv) = direction_kernel(c.slip, p.mu * c.normal_pressure, p.eps);
        TractionDerivatives::new(d_slip, along(c.slip, p.mu, inv))
    }
}

/// `friction.law = "coulomb"`: [`RegularisedCoulomb`] from `friction.mu`, `friction.eps`.
pub(crate) const REGISTRATION: RegisteredLaw = RegisteredLaw {
    name: "coulomb",
    summary: "regularised Coulomb friction (Kikuchi-Oden): mu |p| u / max(|u|, eps)",
    parameters: &["mu", "eps"],
    build: |s| {
        Ok(bind(
            RegularisedCoulomb,
            RegularisedCoulombParams::new(s.mu, s.eps)?,
        ))
    },
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn new_rejects_negative_mu_and_zero_eps() {
        assert!(matches!(
            RegularisedCoulombParams::new(-0.1, 1e-3),
            Err(FrictionError::InvalidParameter { field: "mu", .. })
        ));
        assert!(matches!(
            RegularisedCoulombParams::new(0.5, 0.0),
            Err(FrictionError::InvalidParameter { field: "eps", .. })
        ));
        assert!(RegularisedCoulombParams::new(f64::NAN, 1.0).is_err());
    }

    #[test]
    fn traction_is_continuous_at_eps_and_bounded_by_mu_p() {
        let p = RegularisedCoulombParams::new(0.4, 0.01).unwrap();
        let at =
            |s: f64| RegularisedCoulomb.traction(&ContactState::new([s * 0.6, s * 0.8], -3.0), &p);
        let (below, above) = (at(0.01 * (1.0 - 1e-12)), at(0.01));
        assert!((below[0] - above[0]).abs() < 1e-11 && (below[1] - above[1]).abs() < 1e-11);
        let far = at(7.0);
        let mag = (far[0] * far[0] + far[1] * far[1]).sqrt();
        assert!((mag - 1.2).abs() < 1e-15); // mu |p| = 0.4 * 3
        assert!(far[0] < 0.0 && far[1] < 0.0); // opposes slip in compression
    }
}
