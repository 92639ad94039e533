//! Finite elements beside the finite differences: a Galerkin discretisation of the
//! plane-strain curvilinear Navier operator with one element family, the tensor-product
//! Lagrange elements Qp of any order `p` on the parameter rectangle ([`HighOrderNavier`]),
//! behind the same [`crate::Discretisation`] trait (same node numbering and dofs, same
//! boundary conditions and contact rows as the finite differences).
//!
//! # Math
//! ```text
//! int A^ijkl E_kl(v) E_ij(w) sqrt(g) dx2 dx3 = int f_j w^j sqrt(g) dx2 dx3 + int_sides phi_j w^j ds
//! ```
//! See [`HighOrderNavier`] for the boundary fluxes `phi_j`, the quadrature and the symmetric
//! Dirichlet elimination, and [`NodalRecovery`] for the stresses at the nodes.
//!
//! # One family, three registered names
//! [`DiscretisationMethod`] selects `fd | fem-q1 | fem-q2 | fem-qp` (scene key
//! `discretisation.method`). All three element names build [`HighOrderNavier`]:
//! - `fem-qp`: order `p` (`discretisation.order`), Gauss–Lobatto–Legendre nodes, optional
//!   geometric grading, static condensation of the element interiors, stresses at the nodes
//!   from the element polynomials ([`NodalRecovery::Element`]);
//! - `fem-q1`, `fem-q2`: orders 1 and 2 on uniform elements (whose GLL nodes are the uniform
//!   ones), stresses at the nodes by second-order nodal differences and, under selective
//!   reduced integration, the reduced-point divergence ([`NodalRecovery::Differences`],
//!   [`HighOrderNavier::with_element`], [`QpSettings::element`]).
//!
//! For `p <= 2` the element matrices come from a direct quadrature loop
//! ([`high_order::add_element_matrix_direct`]) instead of the sum factorisation: the fast
//! path of Q1 and Q2. [`VolumetricIntegration`] selects `full | reduced` integration of the
//! volumetric part (scene key `discretisation.volumetric`: selective reduced integration
//! against volumetric locking as `nu -> 1/2`).
//!
//! # Status
//! Verified by the manufactured solutions and the Lamé cylinder of the finite-difference
//! studies ([`crate::studies::fem_studies`], [`crate::studies::high_order_studies`], run by
//! `capstan verify`): order `p + 1` in L2 (Q1 2, Q2 3).
//!
//! # Limitations
//! Structured grids on the rectangle (the node counts of [`crate::Grid`]: `n - 1` a multiple
//! of `p`, Q2 needs odd `n2`, `n3`, even `n2` when periodic).

mod assembly;
mod boundary_terms;
mod element;
pub mod high_order;
mod method;
mod norms;
mod volumetric;

/// The problem the operators here are built from (also at the crate root).
pub use crate::plane_problem::PlaneProblem;
pub use assembly::ElementAssembly;
pub use element::{ElementOrder, gauss_rule};
pub(crate) use element::{check_whole_elements, lumped_weight};
pub use high_order::{
    CornerRefinedNavier, CornerSettings, Grading, HighOrderNavier, NodalRecovery, QpSettings,
    TransitionGrading, gll_rule,
};
pub use method::DiscretisationMethod;
pub use norms::DisplacementErrors;
pub use volumetric::VolumetricIntegration;
