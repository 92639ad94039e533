//! The plane, the right circular cone and the sphere.

use crate::cone::cone_jet;
use crate::error::{GeometryError, positive};
use crate::profile::ProfileCurve;
use crate::scalar::{Real, Scalar};
use crate::surface::Surface;

/// The plane `sigma(x1, x2) = (x1, x2, 0)` with normal `(0, 0, 1)`: zero curvature everywhere.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Plane;

impl<F: Real> Surface<F> for Plane {
    fn sigma<S: Scalar<F>>(&self, [x1, x2]: [S; 2]) -> [S; 3] {
        [x1, x2, x1 * F::zero()]
    }
}

/// A right circular cone of half-aperture `alpha` (the paper's `2 alpha`-aperture cone):
/// `sigma(x1, x2) = (x1, x1 tan(alpha) sin x2, x1 tan(alpha) cos x2)`, `x1 > 0`.
///
/// # Math
/// A general cone with `ubar = tan(alpha) sin t`, `vbar = tan(alpha) cos t`;
/// `a_11 = sec^2(alpha)`, `a_12 = 0`, `a_22 = x1^2 tan^2(alpha)`, `K = 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RightCircularCone<F> {
    half_angle: F,
}

impl<F: Real> RightCircularCone<F> {
    /// A cone with half-aperture `half_angle` in `(0, pi/2)`.
    ///
    /// # Errors
    /// [`GeometryError::InvalidParameter`] unless `0 < half_angle < pi/2`.
    pub fn new(half_angle: F) -> Result<Self, GeometryError> {
        let v = half_angle.to_f64().unwrap_or(f64::NAN);
        if !(v.is_finite() && v > 0.0 && v < std::f64::consts::FRAC_PI_2) {
            return Err(GeometryError::InvalidParameter {
                field: "obstacle.half_angle",
                value: v,
                allowed: "(0, pi/2)",
            });
        }
        Ok(Self { half_angle })
    }
    /// The half-aperture `alpha`.
    pub fn half_angle(&self) -> F {
        self.half_angle
    }
}

impl<F: Real> ProfileCurve<F> for RightCircularCone<F> {
    fn profile<S: Scalar<F>>(&self, t: S) -> [S; 2] {
        let k = self.half_angle.tan();
        let (s, c) = t.sin_cos();
        [s * k, c * k]
    }
    fn profile_jet(&self, t: F) -> [[F; 4]; 2] {
        let k = self.half_angle.tan();
        let (s, c) = t.sin_cos();
        [
            [k * s, k * c, -k * s, -k * c],
            [k * c, -k * s, -k * c, k * s],
        ]
    }
}

impl<F: Real> Surface<F> for RightCircularCone<F> {
    fn sigma<S: Scalar<F>>(&self, [x1, x2]: [S; 2]) -> [S; 3] {
        let [u, v] = self.profile(x2);
        [x1, x1 * u, x1 * v]
    }
    fn jet(&self, x: [F; 2]) -> crate::ad::SurfaceJet<F> {
        cone_jet(x[0], self.profile_jet(x[1]))
    }
}

/// A sphere of radius `R` in colatitude/longitude: `sigma = R (sin x1 cos x2, sin x1 sin x2, cos x1)`.
///
/// A test surface with non-zero Gaussian curvature: `K = 1/R^2`, `H = 1/R` (outward normal).
/// The poles `x1 = 0, pi` are degenerate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere<F> {
    radius: F,
}

impl<F: Real> Sphere<F> {
    /// A sphere of the given radius.
    ///
    /// # Errors
    /// [`GeometryError::InvalidParameter`] unless `radius` is finite and positive.
    pub fn new(radius: F) -> Result<Self, GeometryError> {
        positive("obstacle.radius", radius.to_f64().unwrap_or(f64::NAN))?;
        Ok(Self { radius })
    }
}

impl<F: Real> Surface<F> for Sphere<F> {
    fn sigma<S: Scalar<F>>(&self, [x1, x2]: [S; 2]) -> [S; 3] {
        let (s1, c1) = x1.sin_cos();
        let (s2, c2) = x2.sin_cos();
        [
            s1 * c2 * self.radius,
            s1 * s2 * self.radius,
            c1 * self.radius,
        ]
    }
}
