//! Exact (unregularised) Coulomb friction: the return map onto the friction disc.

use capstan_geometry::Real;

use crate::error::{FrictionError, check_non_negative};
use crate::nonsmooth_law::{
    FrictionState, NonsmoothFrictionLaw, Projection, RegisteredNonsmoothLaw, bind_nonsmooth,
    check_finite_input,
};

/// Exact Coulomb friction (no regularisation): the projection onto the disc `|t| <= mu |sigma_n|`.
///
/// # Math
/// With `g = mu max(-sigma_n, 0)` (no friction without compression) and the trial `t*`
/// (see [`crate::nonsmooth_law`]):
/// ```text
/// stick      |t*| <= g:   t = t*,   (also within 8 round-off units outside: the limit itself)            dt/dt* = I,                        dt/dsigma_n = 0
/// slip       |t*| >  g:   t = g n,  n = t*/|t*|,
///                         dt/dt* = (g/|t*|) (I - n n^T),                      dt/dsigma_n = -mu n
/// separated  sigma_n >= 0: t = 0,           dt/dt* = 0,                        dt/dsigma_n = 0
/// ```
/// At the solution `t = P(t - r du)` this is Coulomb's law: `du = 0` where `|t| < g`, and
/// `t = -g du/|du|` (the traction opposes the slip) where `du != 0`. It is the `eps -> 0`
/// limit of [`crate::RegularisedCoulomb`]. The 1-D membrane uses the trial `(0, t*)`, for
/// which the projection is the clamp of `t*` to `[-g, g]`.
///
/// # References
/// Alart and Curnier, *A mixed formulation for frictional contact problems prone to Newton like
/// solution methods*, CMAME 92 (1991); paper section 3, eq. CoulombOden (the regularised form).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ExactCoulomb;

/// Parameters of [`ExactCoulomb`]: the coefficient of friction `mu >= 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExactCoulombParams<F> {
    mu: F,
}

impl<F: Real> ExactCoulombParams<F> {
    /// The coefficient of friction `mu`.
    ///
    /// # Errors
    /// [`FrictionError::InvalidParameter`] naming `mu` unless `mu` is finite and `>= 0`.
    pub fn new(mu: F) -> Result<Self, FrictionError> {
        check_non_negative("mu", mu)?;
        Ok(Self { mu })
    }
    /// The coefficient of friction `mu`.
    pub fn mu(&self) -> F {
        self.mu
    }
}

impl<F: Real> NonsmoothFrictionLaw<F> for ExactCoulomb {
    type Params = ExactCoulombParams<F>;

    fn project(
        &self,
        trial: [F; 2],
        normal_pressure: F,
        params: &Self::Params,
    ) -> Result<Projection<F>, FrictionError> {
        check_finite_input(trial, normal_pressure)?;
        if normal_pressure >= F::zero() {
            return Ok(Projection::separated());
        }
        let g = -params.mu * normal_pressure;
        let norm = (trial[0] * trial[0] + trial[1] * trial[1]).sqrt();
        // within round-off of the circle counts as on it (a traction left on the limit by a
        // previous slip, with no new slip, sticks)
        let eight = F::one() + F::one() + F::one() + F::one();
        let eight = eight + eight;
        if norm <= g * (F::one() + eight * F::epsilon()) {
            return Ok(Projection::stick(trial));
        }
        let n = [trial[0] / norm, trial[1] / norm];
        let s = g / norm;
        let d_trial = [
            [s * (F::one() - n[0] * n[0]), -s * n[0] * n[1]],
            [-s * n[1] * n[0], s * (F::one() - n[1] * n[1])],
        ];
        Ok(Projection::new(
            [g * n[0], g * n[1]],
            d_trial,
            [-params.mu * n[0], -params.mu * n[1]],
            FrictionState::Slip,
        ))
    }
}

/// `friction.law = "exact-coulomb"`: [`ExactCoulomb`] from `friction.mu` (no `eps`).
pub(crate) const REGISTRATION: RegisteredNonsmoothLaw = RegisteredNonsmoothLaw {
    name: "exact-coulomb",
    summary: "exact Coulomb friction (no eps): projection onto the disc |t| <= mu |p|, semismooth Newton",
    parameters: &["mu"],
    build: |s| Ok(bind_nonsmooth(ExactCoulomb, ExactCoulombParams::new(s.mu)?)),
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn new_rejects_negative_mu() {
        assert!(matches!(
            ExactCoulombParams::new(-0.1),
            Err(FrictionError::InvalidParameter { field: "mu", .. })
        ));
        assert!(ExactCoulombParams::new(f64::NAN).is_err());
    }

    #[test]
    fn project_rejects_non_finite_input() {
        let p = ExactCoulombParams::new(0.5).unwrap();
        let e = ExactCoulomb.project([f64::NAN, 0.0], -1.0, &p).unwrap_err();
        assert!(matches!(
            e,
            FrictionError::InvalidParameter {
                field: "trial traction",
                ..
            }
        ));
        assert!(ExactCoulomb.project([0.0, 0.0], f64::INFINITY, &p).is_err());
    }

    #[test]
    fn one_dimensional_trial_is_clamped() {
        let p = ExactCoulombParams::new(0.25).unwrap();
        // sigma_n = -4: g = 1
        for (t, want, state) in [
            (0.5, 0.5, FrictionState::Stick),
            (-1.0, -1.0, FrictionState::Stick),
            (3.0, 1.0, FrictionState::Slip),
            (-7.0, -1.0, FrictionState::Slip),
        ] {
            let pr = ExactCoulomb.project([0.0, t], -4.0, &p).unwrap();
            assert_eq!(pr.traction, [0.0, want]);
            assert_eq!(pr.state, state);
        }
        let pr = ExactCoulomb.project([0.0, 3.0], 2.0, &p).unwrap();
        assert_eq!(pr.state, FrictionState::Separated);
        assert_eq!(pr.traction, [0.0, 0.0]);
    }
}
