//! Finite elements beside the finite differences: a Galerkin discretisation of the
//! plane-strain curvilinear Navier operator with Q1 and Q2 Lagrange elements on the
//! parameter rectangle, behind the same [`crate::Discretisation`] trait (same nodes, same dof
//! numbering, same boundary conditions and contact rows).
//!
//! # Math
//! ```text
//! int A^ijkl E_kl(v) E_ij(w) sqrt(g) dx2 dx3 = int f_j w^j sqrt(g) dx2 dx3 + int_sides phi_j w^j ds
//! ```
//! See [`FiniteElementNavier`] for the boundary fluxes `phi_j`, the quadrature and the
//! symmetric Dirichlet elimination, and [`ElementOrder`] for the elements.
//!
//! # Status
//! Verified by the manufactured solutions and the Lamé cylinder of the finite-difference
//! studies ([`crate::studies::fem_studies`], run by `capstan verify`): order 2 (Q1) and 3 (Q2) in L2.
//! [`DiscretisationMethod`] selects `fd | fem-q1 | fem-q2 | fem-qp` (scene key
//! `discretisation.method`; `fem-qp` is [`HighOrderNavier`], elements of any order `p` with
//! Gauss–Lobatto–Legendre nodes and static condensation, module [`high_order`]);
//! [`VolumetricIntegration`] selects `full | reduced` integration of the volumetric part
//! (scene key `discretisation.volumetric`: selective reduced integration against volumetric
//! locking as `nu -> 1/2`).
//!
//! # Limitations
//! Uniform structured grids on the rectangle (the nodes of [`crate::Grid`]); Q2 needs odd
//! `n2`, `n3` (even `n2` when periodic). Output fields and contact stresses use a
//! second-order nodal gradient recovery (also for Q2).

mod assembly;
mod element;
pub mod high_order;
mod method;
mod navier;
mod volumetric;

/// The problem the operators here are built from (also at the crate root).
pub use crate::plane_problem::PlaneProblem;
pub use assembly::ElementAssembly;
pub use element::{ElementOrder, gauss_rule};
pub(crate) use element::{check_whole_elements, lumped_weight};
pub use high_order::{Grading, HighOrderNavier, NodalRecovery, QpSettings, gll_rule};
pub use method::DiscretisationMethod;
pub use navier::FiniteElementNavier;
pub use navier::norms::DisplacementErrors;
pub use volumetric::VolumetricIntegration;
