//! The elliptical prism `(x1, a sin x2, b cos x2)` and the circular cylinder, with closed-form jets.

use crate::ad::SurfaceJet;
use crate::error::{GeometryError, positive};
use crate::prism::prism_jet;
use crate::profile::ProfileCurve;
use crate::scalar::{Real, Scalar};
use crate::surface::Surface;

/// Closed-form profile jet of `(a sin t, b cos t)`.
fn ellipse_profile_jet<F: Real>(a: F, b: F, t: F) -> [[F; 4]; 2] {
    let (s, c) = t.sin_cos();
    [
        [a * s, a * c, -a * s, -a * c],
        [b * c, -b * s, -b * c, b * s],
    ]
}

/// An elliptical prism with horizontal semi-axis `a` and vertical semi-axis `b`:
/// `sigma(x1, x2) = (x1, a sin x2, b cos x2)` (paper section 2.3; the normal is outward).
///
/// # Math
/// ```text
/// phi = sqrt(b^2 sin^2 x2 + a^2 cos^2 x2)
/// a_22 = phi^2,  b_22 = -a b / phi,  H = a b / (2 phi^3),  K = 0
/// sqrt(g_22) = phi + x3 a b / phi^2   (shell chart)
/// ```
/// The jet is closed form (a fast path tested equal to automatic differentiation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EllipticalPrism<F> {
    a: F,
    b: F,
}

impl<F: Real> EllipticalPrism<F> {
    /// An elliptical prism with semi-axes `a` (horizontal) and `b` (vertical).
    ///
    /// # Errors
    /// [`GeometryError::InvalidParameter`] unless both are finite and positive.
    pub fn new(a: F, b: F) -> Result<Self, GeometryError> {
        positive("obstacle.a", a.to_f64().unwrap_or(f64::NAN))?;
        positive("obstacle.b", b.to_f64().unwrap_or(f64::NAN))?;
        Ok(Self { a, b })
    }
    /// Horizontal semi-axis `a`.
    pub fn a(&self) -> F {
        self.a
    }
    /// Vertical semi-axis `b`.
    pub fn b(&self) -> F {
        self.b
    }
    /// `phi(t) = sqrt(b^2 sin^2 t + a^2 cos^2 t)`.
    pub fn phi(&self, t: F) -> F {
        let (s, c) = t.sin_cos();
        (self.b * self.b * s * s + self.a * self.a * c * c).sqrt()
    }
}

impl<F: Real> ProfileCurve<F> for EllipticalPrism<F> {
    fn profile<S: Scalar<F>>(&self, t: S) -> [S; 2] {
        let (s, c) = t.sin_cos();
        [s * self.a, c * self.b]
    }
    fn profile_jet(&self, t: F) -> [[F; 4]; 2] {
        ellipse_profile_jet(self.a, self.b, t)
    }
}

impl<F: Real> Surface<F> for EllipticalPrism<F> {
    fn sigma<S: Scalar<F>>(&self, [x1, x2]: [S; 2]) -> [S; 3] {
        let [u, v] = self.profile(x2);
        [x1, u, v]
    }
    fn jet(&self, x: [F; 2]) -> SurfaceJet<F> {
        prism_jet(x[0], ellipse_profile_jet(self.a, self.b, x[1]))
    }
}

/// A circular cylinder of radius `r`: `sigma(x1, x2) = (x1, r sin x2, r cos x2)`.
///
/// # Math
/// The shell chart is cylindrical polar coordinates with radius `r + x3`:
/// `g_22 = (r + x3)^2`, `Gamma^3_22 = -(r + x3)`, `Gamma^2_23 = 1/(r + x3)`, `H = 1/(2r)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CircularCylinder<F> {
    radius: F,
}

impl<F: Real> CircularCylinder<F> {
    /// A cylinder of the given radius.
    ///
    /// # Errors
    /// [`GeometryError::InvalidParameter`] unless `radius` is finite and positive.
    pub fn new(radius: F) -> Result<Self, GeometryError> {
        positive("obstacle.radius", radius.to_f64().unwrap_or(f64::NAN))?;
        Ok(Self { radius })
    }
    /// The radius `r`.
    pub fn radius(&self) -> F {
        self.radius
    }
    /// The same surface as an [`EllipticalPrism`] with `a = b = r`, which evaluates it.
    fn ellipse(&self) -> EllipticalPrism<F> {
        EllipticalPrism {
            a: self.radius,
            b: self.radius,
        }
    }
}

impl<F: Real> ProfileCurve<F> for CircularCylinder<F> {
    fn profile<S: Scalar<F>>(&self, t: S) -> [S; 2] {
        self.ellipse().profile(t)
    }
    fn profile_jet(&self, t: F) -> [[F; 4]; 2] {
        self.ellipse().profile_jet(t)
    }
}

impl<F: Real> Surface<F> for CircularCylinder<F> {
    fn sigma<S: Scalar<F>>(&self, x: [S; 2]) -> [S; 3] {
        self.ellipse().sigma(x)
    }
    fn jet(&self, x: [F; 2]) -> SurfaceJet<F> {
        self.ellipse().jet(x)
    }
}
