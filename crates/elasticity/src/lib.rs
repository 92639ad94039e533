//! Curvilinear linear elasticity for capstan: thick bodies of either dimension over any
//! obstacle surface (the plane-strain body on a prism, the 3-D body on any chart), their
//! discretisations (a registry: finite differences, Q1/Q2 and Qp finite elements, or one
//! registered from outside), and the frictional contact problem on the face `x3 = 0` with
//! its solvers ([`contact`]).
//!
//! # Quick start
//! ```
//! use capstan_elasticity::Material;
//! use capstan_elasticity::contact::{BoundarySolver, ContactSettings, EndLoads, ThickBody};
//! use capstan_elasticity::finite_element::{DiscretisationMethod, VolumetricIntegration};
//! use capstan_friction::{RegularisedCoulomb, RegularisedCoulombParams};
//! use capstan_geometry::{EllipticalPrism, Obstacle};
//! use std::f64::consts::FRAC_PI_2;
//! // the paper's body (section 3) on a coarse grid, pulled with tau_max / tau0 = 1.5
//! let body = ThickBody {
//!     obstacle: Obstacle::Ellipse(EllipticalPrism::new(2.0, 2.0).unwrap()),
//!     theta: [-FRAC_PI_2, FRAC_PI_2],
//!     thickness: 1.0,
//!     material: Material::new(1e3, 0.25).unwrap(),
//!     n2: 31,
//!     n3: 7,
//!     method: DiscretisationMethod::default(),
//!     volumetric: VolumetricIntegration::default(),
//!     order: 4,
//!     grading: capstan_elasticity::finite_element::Grading::UNIFORM,
//!     body_force: None,
//! };
//! let params = RegularisedCoulombParams::new(0.5, 1e-5).unwrap();
//! let model = body.model(RegularisedCoulomb, params, 1e-5).unwrap();
//! let solver = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
//! let solution = solver.solve(EndLoads::new(1.0, 1.5)).unwrap();
//! assert!(solution.stick_interval.is_some()); // part of the contact sticks
//! assert!(solution.slip_fraction.abs() < 1.0); // and part slips
//! ```
//!
//! # Math
//! ```text
//! nabla_i T^i_j + f_j = 0,   T^ij = A^ijkl E_kl,   E_kl = (nabla_k v_l + nabla_l v_k)/2
//! A^ijkl = lambda g^ij g^kl + mu (g^ik g^jl + g^il g^jk)
//! nabla_i T^i_j = (1/sqrt(g)) d_i (sqrt(g) T^i_j) - Gamma^k_ij T^i_k
//! nabla_k v_l = g_ln (d_k v^n + Gamma^n_km v^m)
//! ```
//! on the shell chart `Theta = sigma + x3 N` of the obstacle surface. Plane strain: `d_1 = 0`,
//! `v^1 = 0`; unknowns are the contravariant `v^2` (radians on an angular chart) and `v^3`
//! (length). Paper indices 1, 2, 3 are array indices 0, 1, 2.
//!
//! # Contents
//! - Bodies: [`contact::ThickBody`] (plane strain on any prism surface),
//!   [`solid::SolidBody`] (3-D on any surface), and [`contact::Body`], one description for
//!   both with the dimension as data ([`contact::Body::model`] is the one 2-D/3-D fork).
//! - Discretisations: the [`Discretisation`] trait of plane-strain operators (dof numbering,
//!   assembly into a [`LinearSystem`] whose pattern is built once, contact rows
//!   [`ContactNode`], output [`NodalFields`]) and the [`registry`] that names them in scenes
//!   (`fd` [`FiniteDifferenceNavier`]; `fem-q1`, `fem-q2` and `fem-qp` one element family,
//!   [`finite_element::HighOrderNavier`] of order 1, 2 or `p`),
//!   each registered once with its parameters and a builder that validates; 3-D hexahedra of
//!   any order in [`solid`].
//! - Contact ([`contact`]): the model on the face `x3 = 0` of any
//!   [`contact::ContactOperator`] with a pointwise friction law, loads as a list of unit
//!   right-hand sides (end tractions first), the boundary-only and full-system solvers,
//!   limiting ratios and thresholds.
//! - [`Material`], pointwise [`kinematics`], [`Grid`], [`BoundaryConditions`] (Dirichlet,
//!   traction `n_i T^i_j = t_j`, stress `T^a_j`, periodic `x2`, pinned dofs), [`samples`]
//!   (manufactured solutions, the Lamé cylinder, the paper's ellipse) and [`verification`]
//!   (convergence studies with observed orders).
//!
//! Verified: second order in max and L2 norms (finite differences, Q1), third (Q2) and
//! `p + 1` (Qp) in L2 by manufactured solutions on elliptical and expression-defined prisms
//! and on the Lamé thick cylinder; the 3-D body by manufactured solutions on prisms and cones
//! and against the extruded plane-strain body.
//!
//! # Limitations
//! The plane-strain body needs an `x1`-invariant chart (a prism; cones are 3-D only). Finite
//! differences and Q1/Q2 elements use the grid's uniform nodes (graded meshes: `fem-qp`).
//! Contact is bilateral (`v^3 = 0` on `x3 = 0`) with one friction law for the whole face; the
//! solvers drive the two end tractions (further loads of the list enter the right-hand side).
#![warn(missing_docs)]

mod boundary;
pub mod contact;
pub mod continuum;
mod discretisation;
mod error;
mod fields;
mod finite_difference;
pub mod finite_element;
mod grid;
mod material;
pub mod mesh_discretisation;
mod plane_problem;
mod plane_strain_operator;
pub mod registration;
pub mod registry;
mod schemes;
mod shell_geometry;
pub mod solid;
pub mod studies;
pub mod verification;

pub use boundary::{
    BoundaryConditions, BoundaryFunction, Component, ComponentCondition, PinnedDof, PointFunction,
    Side, SideCondition, X2Ends,
};
pub use continuum::kinematics;
pub use discretisation::{
    ContactNode, Discretisation, LinearSystem, RowBlock, SparseRow, interpolate_nodal,
};
pub use error::ElasticityError;
pub use fields::NodalFields;
pub use finite_difference::FiniteDifferenceNavier;
pub use grid::Grid;
pub use material::Material;
pub use plane_problem::{BodyForce, PlaneProblem};
pub use registration::PlaneOperator;
pub use schemes::{FemQk, FemQp, FemQpCorner, FiniteDifferences};
pub use shell_geometry::{SharedChart, ShellGeometry};
pub use studies::{samples, studies};

/// The friction crate, re-exported for users of [`contact`].
pub use capstan_friction as friction;
/// The solver crate, re-exported for users of [`Discretisation::solve`].
pub use capstan_solvers as solvers;
