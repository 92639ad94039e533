//! Regularised Tresca friction: a slip-opposing traction of fixed magnitude `g`.

use capstan_geometry::Real;

use crate::error::{FrictionError, check_non_negative, check_width};
use crate::friction_law::{ContactState, FrictionLaw, TractionDerivatives};
use crate::registration::{RegisteredLaw, bind};
use crate::slip_direction::direction_kernel;

/// Tresca friction: the traction bound `g` does not depend on the normal stress.
///
/// # Math
/// ```text
/// t(u) = -g u / |u|    if |u| >= eps          g: friction bound (stress), >= 0
/// t(u) = -g u / eps    if |u| <  eps          dt/dp = 0
/// ```
/// Like [`crate::RegularisedCoulomb`], `t` is continuous at `|u| = eps` and its tangent jumps.
/// Tresca holds wherever the pressure is known in advance (thin films, clamped plates); on a
/// capstan it gives a linear, not exponential, tension rise: `dT/ds = g`.
///
/// # Example
/// ```
/// use capstan_friction::{ContactState, FrictionLaw, Tresca, TrescaParams};
/// let p = TrescaParams::new(0.7, 1e-3).unwrap();
/// let t = Tresca.traction(&ContactState::new([0.0, -0.5], -123.0), &p);
/// assert_eq!(t, [0.0, 0.7]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Tresca;

/// Parameters of [`Tresca`]: bound `g >= 0` (`friction.bound`), `eps > 0` (`friction.eps`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrescaParams<F> {
    bound: F,
    eps: F,
}

impl<F: Real> TrescaParams<F> {
    /// Friction bound and regularisation width.
    ///
    /// # Errors
    /// [`FrictionError::InvalidParameter`] naming `bound` unless `g` is finite and
    /// `>= 0`, or `eps` unless `eps` is finite and `> 0`.
    pub fn new(bound: F, eps: F) -> Result<Self, FrictionError> {
        check_non_negative("bound", bound)?;
        check_width(eps)?;
        Ok(Self { bound, eps })
    }
    /// The friction bound `g`.
    pub fn bound(&self) -> F {
        self.bound
    }
    /// The regularisation width.
    pub fn eps(&self) -> F {
        self.eps
    }
}

impl<F: Real> FrictionLaw<F> for Tresca {
    type Params = TrescaParams<F>;

    fn traction(&self, c: &ContactState<F>, p: &Self::Params) -> [F; 2] {
        direction_kernel(c.slip, -p.bound, p.eps).0
    }

    fn traction_derivatives(
        &self,
        c: &ContactState<F>,
        p: &Self::Params,
    ) -> TractionDerivatives<F> {
        let (_, d, _) = direction_kernel(c.slip, -p.bound, p.eps);
        TractionDerivatives::new(d, [F::zero(); 2])
    }
}

/// `friction.law = "tresca"`: [`Tresca`] from `friction.bound`, `friction.eps`.
pub(crate) const REGISTRATION: RegisteredLaw = RegisteredLaw {
    name: "tresca",
    summary: "Tresca friction: a traction bound g independent of the pressure",
    parameters: &["bound", "eps"],
    build: |s| Ok(bind(Tresca, TrescaParams::new(s.bound, s.eps)?)),
};
