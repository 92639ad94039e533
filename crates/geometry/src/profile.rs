//! Plane profile curves `t -> (u(t), v(t))`, the cross-sections of prisms and cones.

use crate::ad::curve_jet;
use crate::scalar::{Real, Scalar};

/// A plane curve `t -> (u(t), v(t))`, written once generically over the scalar.
///
/// A prism over it is `sigma = (x1, u(x2), v(x2))` and a cone is
/// `sigma = (x1, x1 u(x2), x1 v(x2))`. The unit normal of the prism is outward when the curve
/// runs clockwise in the `(y, z)` plane, as `(a sin t, b cos t)` does.
pub trait ProfileCurve<F: Real> {
    /// `(u(t), v(t))`.
    fn profile<S: Scalar<F>>(&self, t: S) -> [S; 2];

    /// `[[u, u', u'', u'''], [v, v', v'', v''']]` at `t`, exactly (forward-mode AD).
    fn profile_jet(&self, t: F) -> [[F; 4]; 2] {
        curve_jet(|s| self.profile(s), t)
    }
}

impl<F: Real, T: ProfileCurve<F> + ?Sized> ProfileCurve<F> for &T {
    fn profile<S: Scalar<F>>(&self, t: S) -> [S; 2] {
        (**self).profile(t)
    }
    fn profile_jet(&self, t: F) -> [[F; 4]; 2] {
        (**self).profile_jet(t)
    }
}
