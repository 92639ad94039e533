//! Surfaces and shell charts for capstan: metric, Christoffel symbols and fundamental forms,
//! all derived exactly from a parametrisation `sigma(x1, x2)` written once.
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
//! expressions in `t` ([`ExpressionProfile`]).
//!
//! # Limitations
//! Charts must be `C^3` where they are evaluated (the shell chart's Christoffel symbols use
//! third derivatives of `sigma`). Expression profiles are evaluated by an interpreter, several
//! times slower than a compiled `sigma`.
#![warn(missing_docs)]

pub mod ad;
mod cone;
mod elliptical_prism;
mod error;
pub mod expression;
mod expression_profile;
mod obstacle;
mod prism;
mod profile;
pub mod scalar;
mod shell;
mod simple_surfaces;
mod surface;
mod vector;

pub use ad::SurfaceJet;
pub use cone::GeneralCone;
pub use elliptical_prism::{CircularCylinder, EllipticalPrism};
pub use error::GeometryError;
pub use expression_profile::ExpressionProfile;
pub use obstacle::Obstacle;
pub use prism::GeneralPrism;
pub use profile::ProfileCurve;
pub use scalar::{Real, Scalar, real};
pub use shell::{ShellChart, ShellFrame, ShellPoint, normal_derivatives};
pub use simple_surfaces::{Plane, RightCircularCone, Sphere};
pub use surface::{Surface, SurfaceGeometry};
