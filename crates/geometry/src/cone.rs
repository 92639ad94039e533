//! The general cone `sigma = (x1, x1 ubar(x2), x1 vbar(x2))` over a profile curve.

use crate::ad::SurfaceJet;
use crate::profile::ProfileCurve;
use crate::scalar::{Real, Scalar};
use crate::surface::Surface;

/// A general cone with apex at the origin and axis `x1`:
/// `sigma(x1, x2) = x1 w(x2)`, `w = (1, ubar(x2), vbar(x2))`, for `x1 > 0`.
///
/// # Math
/// ```text
/// a_11 = 1 + ubar^2 + vbar^2,  a_12 = x1 (ubar ubar' + vbar vbar'),  a_22 = x1^2 (ubar'^2 + vbar'^2)
/// b_22 = -x1 (vbar' ubar'' - ubar' vbar'') / sqrt(ubar'^2 + vbar'^2 + (vbar ubar' - ubar vbar')^2)
/// b_11 = b_12 = 0,  K = 0
/// ```
/// (paper section 2.2). The jet comes from the 1-D jet of the profile.
#[derive(Debug, Clone, PartialEq)]
pub struct GeneralCone<C> {
    profile: C,
}

impl<C> GeneralCone<C> {
    /// The cone over `profile`.
    pub fn new(profile: C) -> Self {
        Self { profile }
    }
    /// The profile curve `(ubar, vbar)`.
    pub fn profile_curve(&self) -> &C {
        &self.profile
    }
}

/// The jet of `x1 (1, ubar(x2), vbar(x2))` from the profile's jet.
pub(crate) fn cone_jet<F: Real>(x1: F, p: [[F; 4]; 2]) -> SurfaceJet<F> {
    let z = F::zero();
    let w = |k: usize| [if k == 0 { F::one() } else { z }, p[0][k], p[1][k]];
    let sc = |s: F, v: [F; 3]| v.map(|c| s * c);
    let mut jet = SurfaceJet {
        point: sc(x1, w(0)),
        d1: [w(0), sc(x1, w(1))],
        d2: [[[z; 3]; 2]; 2],
        d3: [[[[z; 3]; 2]; 2]; 2],
    };
    jet.d2[0][1] = w(1);
    jet.d2[1][0] = w(1);
    jet.d2[1][1] = sc(x1, w(2));
    jet.d3[0][1][1] = w(2);
    jet.d3[1][0][1] = w(2);
    jet.d3[1][1][0] = w(2);
    jet.d3[1][1][1] = sc(x1, w(3));
    jet
}

impl<F: Real, C: ProfileCurve<F>> Surface<F> for GeneralCone<C> {
    fn sigma<S: Scalar<F>>(&self, [x1, x2]: [S; 2]) -> [S; 3] {
        let [u, v] = self.profile.profile(x2);
        [x1, x1 * u, x1 * v]
    }
    fn jet(&self, x: [F; 2]) -> SurfaceJet<F> {
        cone_jet(x[0], self.profile.profile_jet(x[1]))
    }
}

impl<F: Real, C: ProfileCurve<F>> ProfileCurve<F> for GeneralCone<C> {
    fn profile<S: Scalar<F>>(&self, t: S) -> [S; 2] {
        self.profile.profile(t)
    }
    fn profile_jet(&self, t: F) -> [[F; 4]; 2] {
        self.profile.profile_jet(t)
    }
}
