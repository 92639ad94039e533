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
//! Provides the `Surface` trait with automatic first, second and third derivatives, the shell
//! chart `Theta = sigma + x3 N`, the paper's obstacles (plane, circular cylinder, elliptical
//! prism, general prism, right circular cone, general cone) and expression-defined profiles.
#![warn(missing_docs)]

pub mod expression;
pub mod scalar;

pub use scalar::{Real, Scalar, real};
