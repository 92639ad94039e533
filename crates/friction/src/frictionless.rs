//! The frictionless law: zero tangential traction.

use capstan_geometry::Real;

use crate::friction_law::{ContactState, FrictionLaw, TractionDerivatives};
use crate::registration::{RegisteredLaw, bind};

/// A perfectly smooth contact: `t(u, p) = 0` for every slip and pressure.
///
/// # Example
/// ```
/// use capstan_friction::{ContactState, FrictionLaw, Frictionless};
/// let t = Frictionless.traction(&ContactState::new([0.3, -0.1], -5.0), &());
/// assert_eq!(t, [0.0, 0.0]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Frictionless;

impl<F: Real> FrictionLaw<F> for Frictionless {
    type Params = ();

    fn traction(&self, _contact: &ContactState<F>, _params: &()) -> [F; 2] {
        [F::zero(); 2]
    }

    fn traction_derivatives(
        &self,
        _contact: &ContactState<F>,
        _params: &(),
    ) -> TractionDerivatives<F> {
        TractionDerivatives::new([[F::zero(); 2]; 2], [F::zero(); 2])
    }
}

/// `friction.law = "frictionless"`: [`Frictionless`] (reads no parameter).
pub(crate) const REGISTRATION: RegisteredLaw = RegisteredLaw {
    name: "frictionless",
    summary: "no tangential traction",
    parameters: &[],
    build: |_| Ok(bind(Frictionless, ())),
};
