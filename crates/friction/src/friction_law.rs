//! The pointwise friction-law trait and its contact data.

use capstan_geometry::Real;

/// The contact data a pointwise friction law reads at one point of the contact surface.
///
/// Built with [`ContactState::new`]; new fields may be added without breaking any law.
///
/// # Math
/// `slip = (u_1, u_2)` are the tangential slip components in an orthonormal tangent frame
/// (physical length, not curvilinear components); `normal_pressure` is the normal stress
/// `sigma_n` on the contact surface with the paper's sign (eq. CoulombOden): negative in
/// compression, so that a Coulomb traction `mu sigma_n u/|u|` opposes the slip.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct ContactState<F> {
    /// Tangential slip `(u_1, u_2)` in an orthonormal tangent frame (physical length).
    pub slip: [F; 2],
    /// Normal stress `sigma_n` (negative in compression).
    pub normal_pressure: F,
}

impl<F> ContactState<F> {
    /// The contact state with the given slip and normal stress.
    pub fn new(slip: [F; 2], normal_pressure: F) -> Self {
        Self {
            slip,
            normal_pressure,
        }
    }
}

/// The consistent tangent of a friction law: derivatives of the traction `t(u, p)`.
///
/// # Math
/// ```text
/// d_slip[i][j]  = d t_i / d u_j
/// d_pressure[i] = d t_i / d p
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct TractionDerivatives<F> {
    /// `d t_i / d u_j`, indexed `[i][j]`.
    pub d_slip: [[F; 2]; 2],
    /// `d t_i / d p`.
    pub d_pressure: [F; 2],
}

impl<F> TractionDerivatives<F> {
    /// The derivatives with the given slip and pressure parts.
    pub fn new(d_slip: [[F; 2]; 2], d_pressure: [F; 2]) -> Self {
        Self { d_slip, d_pressure }
    }
}

/// A pointwise friction law: tangential traction from tangential slip and normal stress.
///
/// Per-point data (coefficient of friction, regularisation width, ...) lives in
/// [`FrictionLaw::Params`], so one law value serves a whole contact surface.
///
/// # Example
/// ```
/// use capstan_friction::{ContactState, FrictionLaw, RegularisedCoulomb, RegularisedCoulombParams};
/// let params = RegularisedCoulombParams::new(0.5, 1e-3).unwrap();
/// // slip 0.01 along u_1 under compression sigma_n = -2: full sliding, |t| = mu |sigma_n| = 1
/// let t = RegularisedCoulomb.traction(&ContactState::new([0.01, 0.0], -2.0), &params);
/// assert_eq!(t, [-1.0, 0.0]);
/// ```
pub trait FrictionLaw<F: Real> {
    /// Per-point parameters of the law (`mu`, regularisation width, orthotropy axes, ...).
    type Params: Clone + core::fmt::Debug;

    /// The tangential traction `t = (t_1, t_2)` on the body, in the frame of the slip.
    fn traction(&self, contact: &ContactState<F>, params: &Self::Params) -> [F; 2];

    /// The consistent Newton tangent of [`FrictionLaw::traction`].
    fn traction_derivatives(
        &self,
        contact: &ContactState<F>,
        params: &Self::Params,
    ) -> TractionDerivatives<F>;
}
