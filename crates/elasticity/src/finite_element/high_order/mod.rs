//! Arbitrary-order tensor-product elements Qp (`p = 1 ... 10`) for the plane-strain
//! curvilinear Navier operator: Gauss–Lobatto–Legendre (GLL) nodes, sum-factorised element
//! kernels, static condensation of the element interiors, geometry from the chart at every
//! quadrature point (`discretisation.method = "fem-qp"`, `discretisation.order = p`).
//!
//! # Rooms
//! - `gll`: GLL nodes and weights (Newton on `P_p'`), Gauss–Legendre rules of any size, the
//!   Lagrange basis and its derivative ([`gll_rule`], [`gauss_legendre`], [`lagrange_basis`]).
//! - `kernel`: the element stiffness by sum factorisation ([`ElementTables`],
//!   [`add_element_matrix`]).
//! - `tensor_kernel`: the same element matrix in tensor form, its `x3` contraction as faer
//!   GEMMs, read entry by entry by the condensation (tested against `kernel`).
//! - `condensation`: the Schur complement of each element's interior block (faer Cholesky,
//!   forward substitution, triangular product) and the back-substitution
//!   ([`CondensedElement`]).
//! - `skeleton`: numbering and pattern of the condensed system on the element edges.
//! - `mesh`: the element boundaries, uniform or geometrically graded ([`Grading`],
//!   [`QpSettings`]).
//! - `operator`, `solve`: [`HighOrderNavier`], its assembly and its [`crate::Discretisation`].
//! - the convergence studies (in `crate::studies`) of `capstan verify` ([`crate::studies::high_order_studies`]).
//!
//! # Nodes and the grid
//! The operator takes a [`crate::Grid`] with `n2 = p e2 + 1` (periodic `p e2`) and
//! `n3 = p e3 + 1` nodes: the element boundaries are every `p`-th line of that uniform grid
//! (or, with a geometric [`Grading`], layers shrinking toward the ends: `mesh`), and inside
//! each element the node lines sit at the GLL points, not uniformly. The node
//! numbering and the dofs are those of every other plane-strain operator (`2 node + c`,
//! `x3` fastest), so contact, sweeps and outputs index nodes unchanged; positions come from
//! [`HighOrderNavier::node_coordinates`] (contact entries carry the GLL `x2`, output fields are
//! evaluated at the GLL positions). Known limitation: consumers that place nodes by
//! `Grid::coordinates` (the VTU writer's mesh, `interpolate_nodal`, the contact extremes'
//! positions) see the uniform positions.
//!
//! # Static condensation
//! [`crate::Discretisation::system`] is the whole system on every node (the contact
//! solvers factorise it once, with the element nested dissection of degree `p`, which
//! eliminates element interiors first). [`crate::Discretisation::solve`] condenses: per
//! element `S = K_BB - K_BI K_II^-1 K_IB` onto the `4p` edge nodes, a sparse factorisation of
//! the skeleton system only, and `u_I = K_II^-1 (f_I - K_IB u_B)` element by element. Equal
//! to the full solve to round-off (tested to `1e-10`).
//!
//! # Near incompressibility
//! Selective reduced integration as for Q1/Q2: `lambda (div v)(div w) sqrt(g)` with the
//! `p x p` Gauss rule, the shear part with the full `(p + 1) x (p + 1)` rule
//! (`discretisation.volumetric = "reduced"`); the contact rows keep the pointwise stress.

mod condensation;
mod gll;
#[cfg(test)]
mod graded_tests;
mod kernel;
mod mesh;
mod operator;
mod recovery;
mod skeleton;
mod solve;
mod tensor_kernel;
#[cfg(test)]
mod tests;

pub use condensation::CondensedElement;
pub use gll::{basis_tables, elements_along, gauss_legendre, gll_rule, lagrange_basis};
pub use kernel::{
    DIRECT_KERNEL_ORDERS, ElementTables, add_element_matrix, add_element_matrix_direct,
};
pub use mesh::{Grading, QpSettings};
pub use operator::{HighOrderNavier, ORDERS, check_order, order_name};
pub use recovery::NodalRecovery;
pub use solve::CondensedSystem;
