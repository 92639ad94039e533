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
//!   problem with plane-strain `x1` faces), [`SolidNavier`] (Q1/Q2 hexahedra and Qp
//!   hexahedra with GLL nodes, [`HexElement`]; full or selective reduced integration,
//!   symmetric Dirichlet elimination, assembled once).
//! - Verified by manufactured solutions on cones (one with `g_12 != 0`) and an expression
//!   prism ([`crate::studies::solid`]: L2 orders 2 and 3), and against the 2-D plane-strain operator on
//!   prisms (the extruded problem reproduces it to round-off).
//!
//! - The frictional contact face `x3 = 0` ([`SolidBody`]: end tensions, free or plane-strain
//!   sides): every contact solver of [`crate::contact`] works on it, with two tangential
//!   entries per contact node (`v^1`, `v^2`) and the physical slip in the orthonormal frame
//!   `e_1 = a_1/|a_1|`, `e_2 = a^2/|a^2|`; the plane-strain extrusion reproduces the 2-D
//!   contact solution.
//!
//! - A geometric multigrid hierarchy of the box ([`box_hierarchy`]: trilinear prolongations
//!   per component, Dirichlet dofs constrained, periodic `x2`), used by the full-system
//!   Newton's iterative bulk solver (`solver.linear = "multigrid"`, [`capstan_solvers::KrylovSolver`]).
//!
//! # Limitations
//! Uniform grids; the contact rows recover `T^3_j` pointwise (no
//! reduced-point pressure with selective reduced integration, unlike the 2-D elements).

mod body;
mod boundary;
mod corner;
mod corner_output;
#[cfg(test)]
mod corner_tests;
mod element;
mod fields;
mod grid;
pub(crate) mod matrix_free;
mod multigrid;
mod norms;
mod operator;
pub(crate) mod setup;

pub use body::{SideFaces, SolidBody};
pub use boundary::{Face, FaceComponent, FaceCondition, FaceFunction, SolidBoundary};
pub use corner::SolidCornerNavier;
pub use element::HexElement;
pub use fields::{SolidFields, SolidOutput, SolidOutputMesh};
pub use grid::BoxGrid;
pub use matrix_free::{
    MultigridParts, PLevel, SolidMatrixFree, SolidMultigridParams, cell_sizes, coarse_level_nodes,
};
pub use multigrid::{BoxHierarchy, box_hierarchy, coarser_count, semicoarsening_hierarchy};
pub(crate) use norms::length_squared;
pub use operator::{SolidForce, SolidNavier};
