//! A run-time choice of obstacle: the paper's, with their fast paths, or any user surface.

use std::fmt::Debug;

use crate::ad::SurfaceJet;
use crate::cone::GeneralCone;
use crate::elliptical_prism::{CircularCylinder, EllipticalPrism};
use crate::erased::{SharedProfile, SharedSurface};
use crate::expression_profile::ExpressionProfile;
use crate::prism::GeneralPrism;
use crate::profile::ProfileCurve;
use crate::scalar::Scalar;
use crate::simple_surfaces::{Plane, RightCircularCone};
use crate::surface::Surface;

/// An obstacle chosen at run time; dispatches to each one's fast path.
///
/// The paper's obstacles are variants of their own (closed forms stay closed forms). Any other
/// surface enters through [`Obstacle::prism_over`], [`Obstacle::cone_over`] or
/// [`Obstacle::surface`], behind a shared pointer, still exact ([`SharedSurface`]); scenes name
/// it once it is registered ([`crate::registry`]).
///
/// # Example
/// A user prism (a trough `(x1, a sin t, b cos t - c sin^2 t)`) is a prism to the models:
/// ```
/// use capstan_geometry::{Obstacle, ProfileCurve, Scalar, Surface};
/// #[derive(Debug)]
/// struct Trough { c: f64 }
/// impl ProfileCurve<f64> for Trough {
///     fn profile<S: Scalar<f64>>(&self, t: S) -> [S; 2] {
///         [t.sin() * 2.0, t.cos() * 2.0 - t.sin() * t.sin() * self.c]
///     }
/// }
/// let trough = Obstacle::prism_over(Trough { c: 0.5 });
/// assert!(trough.is_prism());
/// let g = trough.geometry([0.0, 0.0]).unwrap();
/// assert!((g.mean_curvature - 0.375).abs() < 1e-15); // H = (1 + c)/4 at t = 0
/// ```
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
    /// A prism `(x1, u(x2), v(x2))` over a user profile curve ([`Obstacle::prism_over`]).
    UserPrism(GeneralPrism<SharedProfile>),
    /// A cone `x1 (1, ubar(x2), vbar(x2))` over a user profile curve ([`Obstacle::cone_over`]).
    UserCone(GeneralCone<SharedProfile>),
    /// Any user surface ([`Obstacle::surface`]): no prism or cone structure assumed.
    UserSurface(SharedSurface),
}

/// The profile curve of a prism or cone obstacle, as one [`ProfileCurve`].
///
/// For a prism it is `(u, v)` of `(x1, u(x2), v(x2))`; for a cone `(ubar, vbar)` of
/// `x1 (1, ubar(x2), vbar(x2))`. Each variant forwards to the obstacle's own curve.
#[derive(Debug, Clone, Copy)]
pub enum ObstacleProfile<'a> {
    /// The circle `(r sin t, r cos t)`.
    Cylinder(&'a CircularCylinder<f64>),
    /// The ellipse `(a sin t, b cos t)`.
    Ellipse(&'a EllipticalPrism<f64>),
    /// `(tan(alpha) sin t, tan(alpha) cos t)`.
    CircularCone(&'a RightCircularCone<f64>),
    /// Expressions in `t`.
    Expression(&'a ExpressionProfile),
    /// A user curve.
    Shared(&'a SharedProfile),
}

impl ProfileCurve<f64> for ObstacleProfile<'_> {
    fn profile<S: Scalar<f64>>(&self, t: S) -> [S; 2] {
        match self {
            Self::Cylinder(c) => c.profile(t),
            Self::Ellipse(e) => e.profile(t),
            Self::CircularCone(c) => c.profile(t),
            Self::Expression(p) => p.profile(t),
            Self::Shared(p) => p.profile(t),
        }
    }
    fn profile_jet(&self, t: f64) -> [[f64; 4]; 2] {
        match self {
            Self::Cylinder(c) => c.profile_jet(t),
            Self::Ellipse(e) => e.profile_jet(t),
            Self::CircularCone(c) => c.profile_jet(t),
            Self::Expression(p) => ProfileCurve::<f64>::profile_jet(*p, t),
            Self::Shared(p) => p.profile_jet(t),
        }
    }
}

impl Obstacle {
    /// The prism `(x1, u(x2), v(x2))` over a user profile curve.
    ///
    /// Exact for every scalar the workspace evaluates a chart at (see [`SharedProfile`]).
    pub fn prism_over<P: ProfileCurve<f64> + Send + Sync + Debug + 'static>(profile: P) -> Self {
        Self::UserPrism(GeneralPrism::new(SharedProfile::new(profile)))
    }
    /// The cone `x1 (1, ubar(x2), vbar(x2))` over a user profile curve.
    ///
    /// Exact for every scalar the workspace evaluates a chart at (see [`SharedProfile`]).
    pub fn cone_over<P: ProfileCurve<f64> + Send + Sync + Debug + 'static>(profile: P) -> Self {
        Self::UserCone(GeneralCone::new(SharedProfile::new(profile)))
    }
    /// Any user surface (the thick bodies take it; the membrane models need a prism or cone).
    ///
    /// Exact for every scalar the workspace evaluates a chart at (see [`SharedSurface`]).
    pub fn surface<S: Surface<f64> + Send + Sync + Debug + 'static>(surface: S) -> Self {
        Self::UserSurface(SharedSurface::new(surface))
    }
    /// Whether the obstacle is a prism (cross-section independent of `x1`).
    pub fn is_prism(&self) -> bool {
        matches!(
            self,
            Self::Cylinder(_) | Self::Ellipse(_) | Self::Prism(_) | Self::UserPrism(_)
        )
    }
    /// Whether the obstacle is a cone with apex at the origin.
    pub fn is_cone(&self) -> bool {
        matches!(
            self,
            Self::CircularCone(_) | Self::Cone(_) | Self::UserCone(_)
        )
    }
    /// The profile curve of a prism or cone; `None` for the plane and general surfaces.
    pub fn profile(&self) -> Option<ObstacleProfile<'_>> {
        Some(match self {
            Self::Plane(_) | Self::UserSurface(_) => return None,
            Self::Cylinder(s) => ObstacleProfile::Cylinder(s),
            Self::Ellipse(s) => ObstacleProfile::Ellipse(s),
            Self::Prism(s) => ObstacleProfile::Expression(s.profile_curve()),
            Self::CircularCone(s) => ObstacleProfile::CircularCone(s),
            Self::Cone(s) => ObstacleProfile::Expression(s.profile_curve()),
            Self::UserPrism(s) => ObstacleProfile::Shared(s.profile_curve()),
            Self::UserCone(s) => ObstacleProfile::Shared(s.profile_curve()),
        })
    }
    /// The profile jet `[[u, u', u'', u'''], [v, ...]]` of a prism or cone at `t`; `None` for
    /// the plane and general surfaces.
    pub fn profile_jet(&self, t: f64) -> Option<[[f64; 4]; 2]> {
        self.profile().map(|p| p.profile_jet(t))
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
            Self::UserPrism(s) => s.sigma(x),
            Self::UserCone(s) => s.sigma(x),
            Self::UserSurface(s) => s.sigma(x),
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
            Self::UserPrism(s) => s.jet(x),
            Self::UserCone(s) => s.jet(x),
            Self::UserSurface(s) => s.jet(x),
        }
    }
}
