//! Surfaces and shell charts for capstan: metric, Christoffel symbols and fundamental forms,
//! all derived exactly from a parametrisation `sigma(x1, x2)` written once.
//!
//! # Quick start
//! ```
//! use capstan_geometry::{EllipticalPrism, ShellChart, Surface};
//! // sigma = (x1, a sin t, b cos t): at t = 0, H = a b / (2 phi^3) with phi = a
//! let (a, b) = (2.0_f64, 1.0_f64);
//! let ellipse = EllipticalPrism::new(a, b).unwrap();
//! let g = ellipse.geometry([0.0, 0.0]).unwrap();
//! assert!((g.mean_curvature - b / (2.0 * a * a)).abs() < 1e-14);
//! // the shell chart sigma + x3 N: sqrt(g_22) = phi + x3 a b / phi^2
//! let p = ShellChart::new(ellipse).point([0.0, 0.0, 0.5]).unwrap();
//! assert!((p.metric[1][1].sqrt() - (a + 0.5 * b / a)).abs() < 1e-13);
//! ```
//!
//! # Conventions
//! Paper indices 1, 2, 3 are array indices 0, 1, 2. Christoffel symbols are stored as
//! `gamma[k][i][j] = Gamma^k_ij`. The unit normal is `N = a_1 x a_2 / |a_1 x a_2|`; the mean
//! curvature uses the paper's sign, `H = -1/2 b^a_a`, positive on a convex obstacle whose
//! normal points outward (e.g. the clockwise profile `(a sin t, b cos t)`).
//!
//! # Status
//! Provides the [`Surface`] trait with exact first, second and third derivatives by
//! forward-mode automatic differentiation, the shell chart `Theta = sigma + x3 N`
//! ([`ShellChart`]), the paper's obstacles (plane, circular cylinder, elliptical prism, general
//! prism, right circular cone, general cone), a test sphere, and profiles defined by math
//! expressions in `t` ([`ExpressionProfile`]). [`Obstacle`] is the run-time choice among them
//! and user obstacles ([`Obstacle::prism_over`], [`Obstacle::cone_over`],
//! [`Obstacle::surface`]); [`registry`] makes any of them nameable in scenes
//! (`obstacle.shape`), including obstacles registered at run time.
//!
//! # Limitations
//! Charts must be `C^3` where they are evaluated (the shell chart's Christoffel symbols use
//! third derivatives of `sigma`), `C^4` for the derivatives of the shell geometry
//! ([`ShellChart::point_over`] on dual coordinates). Expression profiles are evaluated by an interpreter, several
//! times slower than a compiled `sigma`. A user obstacle behind a pointer ([`SharedSurface`],
//! [`SharedProfile`]) is exact at scalars carrying up to [`TAYLOR_ORDER`] = 4 derivatives
//! (every evaluation in the workspace) and refuses more.
#![warn(missing_docs)]

pub mod ad;
mod cone;
mod elliptical_prism;
mod erased;
mod error;
pub mod expression;
mod expression_profile;
mod nalgebra_views;
mod obstacle;
mod obstacles;
mod prism;
mod profile;
mod registration;
pub mod registry;
pub mod samples;
pub mod scalar;
mod shell;
mod simple_surfaces;
mod surface;
mod vector;

pub use ad::SurfaceJet;
pub use cone::GeneralCone;
pub use elliptical_prism::{CircularCylinder, EllipticalPrism};
pub use erased::{
    DynProfile, DynSurface, FourthDerivatives, SharedProfile, SharedSurface, TAYLOR_ORDER,
};
pub use error::GeometryError;
pub use expression_profile::ExpressionProfile;
/// The nalgebra the views (`SurfaceGeometry::first_form_matrix`, `ShellPoint::metric_matrix`, ...) return.
pub use nalgebra;
pub use obstacle::{Obstacle, ObstacleProfile};
pub use prism::GeneralPrism;
pub use profile::ProfileCurve;
pub use registration::ObstacleSettings;
pub use scalar::{Real, Scalar, real};
pub use shell::{ShellChart, ShellFrame, ShellPoint, normal_derivatives};
pub use simple_surfaces::{Plane, RightCircularCone, Sphere};
pub use surface::{Surface, SurfaceGeometry};
