//! The general prism `sigma = (x1, u(x2), v(x2))` over a profile curve.

use crate::ad::SurfaceJet;
use crate::profile::ProfileCurve;
use crate::scalar::{Real, Scalar};
use crate::surface::Surface;

/// A general prism over a profile curve: `sigma(x1, x2) = (x1, u(x2), v(x2))`.
///
/// # Math
/// ```text
/// a_11 = 1, a_12 = 0, a_22 = u'^2 + v'^2
/// b_22 = -(v' u'' - u' v'') / sqrt(u'^2 + v'^2),  K = 0
/// H = (v' u'' - u' v'') / (2 (u'^2 + v'^2)^(3/2))
/// ```
/// The jet is computed from the 1-D jet of the profile (cheaper than the 2-D default).
#[derive(Debug, Clone, PartialEq)]
pub struct GeneralPrism<C> {
    profile: C,
}

impl<C> GeneralPrism<C> {
    /// The prism over `profile`.
    pub fn new(profile: C) -> Self {
        Self { profile }
    }
    /// The profile curve.
    pub fn profile_curve(&self) -> &C {
        &self.profile
    }
}

/// The jet of `(x1, u(x2), v(x2))` from the profile's jet `[[u, u', u'', u'''], [v, ...]]`.
pub(crate) fn prism_jet<F: Real>(x1: F, p: [[F; 4]; 2]) -> SurfaceJet<F> {
    let z = F::zero();
    let mut jet = SurfaceJet {
        point: [x1, p[0][0], p[1][0]],
        d1: [[F::one(), z, z], [z, p[0][1], p[1][1]]],
        d2: [[[z; 3]; 2]; 2],
        d3: [[[[z; 3]; 2]; 2]; 2],
    };
    jet.d2[1][1] = [z, p[0][2], p[1][2]];
    jet.d3[1][1][1] = [z, p[0][3], p[1][3]];
    jet
}

impl<F: Real, C: ProfileCurve<F>> Surface<F> for GeneralPrism<C> {
    fn sigma<S: Scalar<F>>(&self, [x1, x2]: [S; 2]) -> [S; 3] {
        let [u, v] = self.profile.profile(x2);
        [x1, u, v]
    }
    fn jet(&self, x: [F; 2]) -> SurfaceJet<F> {
        prism_jet(x[0], self.profile.profile_jet(x[1]))
    }
}

impl<F: Real, C: ProfileCurve<F>> ProfileCurve<F> for GeneralPrism<C> {
    fn profile<S: Scalar<F>>(&self, t: S) -> [S; 2] {
        self.profile.profile(t)
    }
    fn profile_jet(&self, t: F) -> [[F; 4]; 2] {
        self.profile.profile_jet(t)
    }
}
