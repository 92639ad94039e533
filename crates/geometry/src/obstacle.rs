//! A run-time choice among the provided obstacles (for scene files).

use crate::ad::SurfaceJet;
use crate::cone::GeneralCone;
use crate::elliptical_prism::{CircularCylinder, EllipticalPrism};
use crate::expression_profile::ExpressionProfile;
use crate::prism::GeneralPrism;
use crate::profile::ProfileCurve;
use crate::scalar::Scalar;
use crate::simple_surfaces::{Plane, RightCircularCone};
use crate::surface::Surface;

/// One of the provided obstacles, chosen at run time; dispatches to each one's fast path.
#[derive(Debug, Clone, PartialEq)]
pub enum Obstacle {
    /// The plane `(x1, x2, 0)`.
    Plane(Plane),
    /// Circular cylinder `(x1, r sin x2, r cos x2)`.
    Cylinder(CircularCylinder<f64>),
    /// Elliptical prism `(x1, a sin x2, b cos x2)`.
    Ellipse(EllipticalPrism<f64>),
    /// General prism `(x1, u(x2), v(x2))` from expressions.
    Prism(GeneralPrism<ExpressionProfile>),
    /// Right circular cone of half-aperture `alpha`.
    CircularCone(RightCircularCone<f64>),
    /// General cone `x1 (1, ubar(x2), vbar(x2))` from expressions.
    Cone(GeneralCone<ExpressionProfile>),
}

impl Obstacle {
    /// Whether the obstacle is a prism (cross-section independent of `x1`).
    pub fn is_prism(&self) -> bool {
        matches!(self, Self::Cylinder(_) | Self::Ellipse(_) | Self::Prism(_))
    }
    /// Whether the obstacle is a cone with apex at the origin.
    pub fn is_cone(&self) -> bool {
        matches!(self, Self::CircularCone(_) | Self::Cone(_))
    }
    /// The profile jet `[[u, u', u'', u'''], [v, ...]]` of a prism or cone at `t`; `None` for the plane.
    pub fn profile_jet(&self, t: f64) -> Option<[[f64; 4]; 2]> {
        Some(match self {
            Self::Plane(_) => return None,
            Self::Cylinder(s) => s.profile_jet(t),
            Self::Ellipse(s) => s.profile_jet(t),
            Self::Prism(s) => s.profile_jet(t),
            Self::CircularCone(s) => s.profile_jet(t),
            Self::Cone(s) => s.profile_jet(t),
        })
    }
}

impl Surface<f64> for Obstacle {
    fn sigma<S: Scalar<f64>>(&self, x: [S; 2]) -> [S; 3] {
        match self {
            Self::Plane(s) => s.sigma(x),
            Self::Cylinder(s) => s.sigma(x),
            Self::Ellipse(s) => s.sigma(x),
            Self::Prism(s) => s.sigma(x),
            Self::CircularCone(s) => s.sigma(x),
            Self::Cone(s) => s.sigma(x),
        }
    }
    fn jet(&self, x: [f64; 2]) -> SurfaceJet<f64> {
        match self {
            Self::Plane(s) => s.jet(x),
            Self::Cylinder(s) => s.jet(x),
            Self::Ellipse(s) => s.jet(x),
            Self::Prism(s) => s.jet(x),
            Self::CircularCone(s) => s.jet(x),
            Self::Cone(s) => s.jet(x),
        }
    }
}
