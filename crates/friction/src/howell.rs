//! Howell's power law of friction: `|t| = mu' |p|^n`, opposing the slip.

use capstan_geometry::Real;

use crate::error::{FrictionError, check, check_non_negative, check_width, to_f64};
use crate::friction_law::{ContactState, FrictionLaw, TractionDerivatives};
use crate::registration::{RegisteredLaw, bind};
use crate::slip_direction::{along, direction_kernel};

/// Howell's power law (fibres and yarns): the friction force grows like a power `n` of the
/// normal force; `n = 1` is [`crate::RegularisedCoulomb`].
///
/// # Math
/// ```text
/// q = max(-p, 0)                            compressive pressure (p = sigma_n < 0 in contact)
/// t(u, p) = -mu' q^n u / max(|u|, eps)
/// dt/dp   =  mu' n q^(n-1) u / max(|u|, eps)   (q > 0; 0 where p > 0)
/// ```
/// No traction in tension (`p >= 0`). For `n < 1` the pressure derivative is unbounded as
/// `p -> 0-`: Newton tangents there are only as good as the pressure is resolved.
///
/// # Example
/// ```
/// use capstan_friction::{ContactState, FrictionLaw, Howell, HowellParams};
/// let p = HowellParams::new(0.5, 0.5, 1e-3).unwrap();
/// let t: [f64; 2] = Howell.traction(&ContactState::new([1.0, 0.0], -4.0), &p);
/// assert!((t[0] + 0.5 * 2.0).abs() < 1e-15); // mu' |p|^(1/2)
/// ```
///
/// # References
/// Howell, J. Text. Inst. 44 (1953) T359; paper section 1 (Zurek and Frydrych).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Howell;

/// Parameters of [`Howell`]: `mu' >= 0` (`friction.mu`), `n in (0, 2]` (`friction.exponent`),
/// `eps > 0` (`friction.eps`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HowellParams<F> {
    mu: F,
    exponent: F,
    eps: F,
}

impl<F: Real> HowellParams<F> {
    /// Coefficient `mu'`, exponent `n` and regularisation width `eps`.
    ///
    /// # Errors
    /// [`FrictionError::InvalidParameter`] naming `mu`, `friction.exponent` or
    /// `friction.eps` for a value outside its range.
    pub fn new(mu: F, exponent: F, eps: F) -> Result<Self, FrictionError> {
        check_non_negative("mu", mu)?;
        check("exponent", to_f64(exponent), "(0, 2]", |v| {
            v > 0.0 && v <= 2.0
        })?;
        check_width(eps)?;
        Ok(Self { mu, exponent, eps })
    }
    /// `mu'`.
    pub fn mu(&self) -> F {
        self.mu
    }
    /// `n`.
    pub fn exponent(&self) -> F {
        self.exponent
    }
    /// The regularisation width.
    pub fn eps(&self) -> F {
        self.eps
    }
}

impl<F: Real> FrictionLaw<F> for Howell {
    type Params = HowellParams<F>;

    fn traction(&self, c: &ContactState<F>, p: &Self::Params) -> [F; 2] {
        let q = (-c.normal_pressure).max(F::zero());
        let s = if q > F::zero() {
            -p.mu * q.powf(p.exponent)
        } else {
            F::zero()
        };
        direction_kernel(c.slip, s, p.eps).0
    }

    fn traction_derivatives(
        &self,
        c: &ContactState<F>,
        p: &Self::Params,
    ) -> TractionDerivatives<F> {
        let q = (-c.normal_pressure).max(F::zero());
        let (s, ds_dp) = if q > F::zero() {
            let qn1 = q.powf(p.exponent - F::one());
            (-p.mu * qn1 * q, p.mu * p.exponent * qn1)
        } else {
            (F::zero(), F::zero())
        };
        let (_, d, inv) = direction_kernel(c.slip, s, p.eps);
        TractionDerivatives::new(d, along(c.slip, ds_dp, inv))
    }
}

/// `friction.law = "howell"`: [`Howell`] from `friction.mu`, `friction.exponent`,
/// `friction.eps`.
pub(crate) const REGISTRATION: RegisteredLaw = RegisteredLaw {
    name: "howell",
    summary: "Howell's power law |t| = mu |p|^n",
    parameters: &["mu", "exponent", "eps"],
    build: |s| Ok(bind(Howell, HowellParams::new(s.mu, s.exponent, s.eps)?)),
};
