//! Qp elements on a mesh refined toward the corners only: the cure for the corner
//! singularities of the paper problem (clamped contact side against loaded ends) without the
//! whole-line grading of the tensor grid ([`super::Grading`]).
//!
//! # Rooms
//! - `layout`: the conforming quadrilateral mesh (coarse cells, geometric trapezoid layers in
//!   the four corner cells) and its Qp node numbering ([`CornerSettings`]).
//! - `operator`: [`CornerRefinedNavier`], the operator on it (bilinear element maps pulled
//!   back into the tensor elements' sum-factorised kernel), condensed solve, error norms.
//! - `contact`: the operator as a [`crate::mesh_discretisation::MeshDiscretisation`] (the
//!   contact face's nodes in `x2` order, face quadrature weights, one-sided stresses): what
//!   makes it the registered discretisation `fem-qp-corner` of the contact solvers.
//!
//! # Why this layout (measured, docs/high-order.md)
//! The tensor grid grades whole lines: `n` layers at each end of `x2` and `x3` make
//! `(2n + m2) (2n + m3)` elements, most of them thin strips along the sides far from any
//! corner. Here each corner cell alone holds its `2n + 1` elements, so the count grows by
//! `8n` instead, and the element edges stay conforming (no hanging-node constraints).

mod contact;
pub(crate) mod layout;
mod operator;
#[cfg(test)]
mod tests;

pub use layout::{CornerSettings, TransitionGrading};
pub use operator::{CornerCondensed, CornerRefinedNavier};
