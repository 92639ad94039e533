//! Arbitrary-order tensor-product elements Qp (`p = 1 ... 10`) for the plane-strain
//! curvilinear Navier operator: Gauss–Lobatto–Legendre (GLL) nodes, sum-factorised element
//! kernels, static condensation of the element interiors, geometry from the chart at every
//! quadrature point (`discretisation.method = "fem-qp"`, `discretisation.order = p`). The one
//! element family of the 2-D body: `fem-q1` and `fem-q2` are its orders 1 and 2 with the
//! nodal-difference recovery ([`NodalRecovery::Differences`]).
//!
//! # Rooms
//! - `gll`: GLL nodes and weights (Newton on `P_p'`), Gauss–Legendre rules of any size, the
//!   Lagrange basis and its derivative ([`gll_rule`], [`gauss_legendre`], [`lagrange_basis`]).
//! - `kernel`: the element stiffness by sum factorisation ([`ElementTables`],
//!   [`add_element_matrix`]), and by the direct quadrature loop for `p <= 2`
//!   ([`add_element_matrix_direct`], the fast path of Q1/Q2).
//! - `tensor_kernel`: the same element matrix in tensor form, its `x3` contraction as faer
//!   GEMMs, read entry by entry by the condensation (tested against `kernel`).
//! - the static condensation of each element's interior block is the solver room's dense
//!   kernel, [`capstan_solvers::CondensedBlock`] (here as [`CondensedElement`]: faer Cholesky,
//!   forward substitution, triangular product, and the back-substitution).
//! - `skeleton`: numbering and pattern of the condensed system on the element edges.
//! - `corner_mesh`: the same elements on a conforming mesh refined toward the four corners
//!   only ([`CornerRefinedNavier`], [`CornerSettings`]).
//! - `mesh`: the element boundaries, uniform or geometrically graded ([`Grading`],
//!   [`QpSettings`]).
//! - `operator`, `solve`: [`HighOrderNavier`], its assembly and its [`crate::Discretisation`].
//! - `nodal_recovery`, `recovery`: values and gradients at the nodes for the contact rows and
//!   output fields ([`NodalRecovery`]: the element polynomials for `fem-qp`, second-order
//!   nodal differences and the reduced-point divergence for `fem-q1`, `fem-q2`).
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
//! Selective reduced integration: `lambda (div v)(div w) sqrt(g)` with the `p x p` Gauss
//! rule, the shear part with the full `(p + 1) x (p + 1)` rule
//! (`discretisation.volumetric = "reduced"`); the contact rows keep the pointwise stress with
//! the element recovery and take the reduced-point divergence with the nodal differences.

pub mod corner_mesh;
mod gll;
#[cfg(test)]
mod graded_tests;
mod kernel;
mod mesh;
mod nodal_recovery;
mod operator;
mod recovery;
#[cfg(test)]
mod recovery_tests;
mod skeleton;
mod solve;
mod tensor_kernel;
#[cfg(test)]
mod tests;

/// One element after the static condensation of its interior unknowns: the solver room's
/// dense condensation, `S = K_BB - K_BI K_II^-1 K_IB` by a Cholesky factorisation of `K_II`
/// (see [`capstan_solvers::CondensedBlock`]).
pub type CondensedElement = capstan_solvers::CondensedBlock;
pub use corner_mesh::{CornerRefinedNavier, CornerSettings, TransitionGrading};
pub use gll::{basis_tables, elements_along, gauss_legendre, gll_rule, lagrange_basis};
pub use kernel::{
    DIRECT_KERNEL_ORDERS, ElementTables, add_element_matrix, add_element_matrix_direct,
};
pub use mesh::{Grading, QpSettings};
pub use nodal_recovery::NodalRecovery;
pub use operator::{HighOrderNavier, ORDERS, check_order, order_name};
pub use solve::CondensedSystem;
