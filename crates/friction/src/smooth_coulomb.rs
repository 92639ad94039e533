//! Smoothly regularised Coulomb friction: `mu p u / sqrt(|u|^2 + eps^2)`.

use capstan_geometry::Real;

use crate::friction_law::{ContactState, FrictionLaw, TractionDerivatives};
use crate::registration::{RegisteredLaw, bind};
use crate::regularised_coulomb::RegularisedCoulombParams;
use crate::slip_direction::{along, coulomb_traction, radial_tangent, slip_norm_squared};

/// Coulomb friction with a smooth (`C^infinity`) regularisation: no kink for Newton.
///
/// # Math
/// ```text
/// t(u, p) = mu p u / r,     r = sqrt(|u|^2 + eps^2)      u: slip (physical length)
/// dt_i/du_j = mu p (delta_ij / r - u_i u_j / r^3)          p: sigma_n (< 0 in contact)
/// dt/dp     = mu u / r
/// ```
/// `|t| < mu |p|` for every slip (the Coulomb bound is reached only as `|u|/eps -> inf`):
/// `|t| = mu |p| (1 - eps^2/(2 |u|^2) + O(eps^4/|u|^4))`, so at a slip `|u| >> eps` it differs
/// from [`crate::RegularisedCoulomb`] by `O(eps^2)`, not `O(eps)`.
///
/// # Example
/// ```
/// use capstan_friction::{ContactState, FrictionLaw, SmoothCoulomb, SmoothCoulombParams};
/// let p = SmoothCoulombParams::new(0.5, 0.03).unwrap();
/// let t: [f64; 2] = SmoothCoulomb.traction(&ContactState::new([0.04, 0.0], -2.0), &p);
/// assert!((t[0] + 0.5 * 2.0 * 0.8).abs() < 1e-15); // |u|/r = 0.04/0.05
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct SmoothCoulomb;

/// Parameters of [`SmoothCoulomb`]: those of [`RegularisedCoulomb`](crate::RegularisedCoulomb), `mu >= 0` (`friction.mu`)
/// and `eps > 0` (`friction.eps`); only the law that reads them differs.
pub type SmoothCoulombParams<F> = RegularisedCoulombParams<F>;

impl<F: Real> FrictionLaw<F> for SmoothCoulomb {
    type Params = SmoothCoulombParams<F>;

    fn traction(&self, c: &ContactState<F>, p: &Self::Params) -> [F; 2] {
        coulomb_traction(c, p.mu(), smooth_length(c.slip, p.eps()))
    }

    fn traction_derivatives(
        &self,
        c: &ContactState<F>,
        p: &Self::Params,
    ) -> TractionDerivatives<F> {
        let r = smooth_length(c.slip, p.eps());
        let (inv, mp) = (F::one() / r, p.mu() * c.normal_pressure);
        TractionDerivatives::new(radial_tangent(c.slip, mp, inv), along(c.slip, p.mu(), inv))
    }
}

/// `r = sqrt(|u|^2 + eps^2)`, the smoothly regularised slip length.
fn smooth_length<F: Real>(u: [F; 2], eps: F) -> F {
    (slip_norm_squared(u) + eps * eps).sqrt()
}

/// `friction.law = "smooth-coulomb"`: [`SmoothCoulomb`] from `friction.mu`, `friction.eps`.
pub(crate) const REGISTRATION: RegisteredLaw = RegisteredLaw {
    name: "smooth-coulomb",
    summary: "Coulomb friction with a smooth regularisation of width eps",
    parameters: &["mu", "eps"],
    build: |s| Ok(bind(SmoothCoulomb, SmoothCoulombParams::new(s.mu, s.eps)?)),
};
