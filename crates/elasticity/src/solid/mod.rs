//! The 3-D curvilinear body on any obstacle: linear elasticity on the parametric box
//! `[x1a, x1b] x [x2a, x2b] x [0, h]` of the shell chart `sigma + x3 N` of any surface —
//! prisms of finite width, cones, surfaces that are not orthogonally parametrised.
//!
//! # Math
//! The weak form of `nabla_i T^i_j + f_j = 0` with all three components and directions
//! (no plane-strain reduction), from the chart's `g_ij`, `g^ij`, `sqrt(g)` and
//! `Gamma^k_ij` alone ([`crate::continuum`] with the [`crate::continuum::SOLID`] inputs);
//! see [`SolidNavier`].
//!
//! # Status
//! - [`BoxGrid`], [`SolidBoundary`] (per face and component: displacement, traction or
//!   stress as functions of the point; periodic `x2`; pinned dofs; the extrusion of a 2-D
//!   problem with plane-strain `x1` faces), [`SolidNavier`] (Q1/Q2 hexahedra, full or
//!   selective reduced integration, symmetric Dirichlet elimination, assembled once).
//! - Verified by manufactured solutions on cones (one with `g_12 != 0`) and an expression
//!   prism ([`samples`]: L2 orders 2 and 3), and against the 2-D plane-strain operator on
//!   prisms (the extruded problem reproduces it to round-off).
//!
//! # Limitations
//! The frictional contact face, scenes (`body.dimension = 3`) and VTU output of the 3-D body
//! are not wired yet; uniform grids; the direct (Cholesky) solver only.

mod body;
mod boundary;
mod contact;
mod grid;
mod operator;
pub mod samples;

pub use body::{SideFaces, SolidBody};
pub use boundary::{Face, FaceComponent, FaceCondition, FaceFunction, SolidBoundary};
pub use grid::BoxGrid;
pub use operator::{SolidForce, SolidNavier};
