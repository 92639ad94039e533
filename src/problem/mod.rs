//! The library API: a thick-body contact problem built in code, the same for 2-D and 3-D.
//!
//! A [`Problem`] is a body over any surface ([`Body`]: the obstacle, plane strain or the 3-D
//! box, thickness, material, grid, any registered discretisation), a friction law by its
//! registered name ([`Friction`]), the loads ([`EndLoads`]) and a solver ([`Solver`]). It is
//! what a scene file describes ([`crate::Scene::build`] is the one place scene values become
//! these typed objects) and what the command line and the Python package solve; a program that
//! never writes TOML builds it directly.
//!
//! # Math
//! The curvilinear Navier equations `nabla_i T^i_j = 0` of the body on the shell chart
//! `Theta = sigma + x3 N` of the obstacle, `A^ijkl = lambda g^ij g^kl + mu (g^ik g^jl + g^il g^jk)`,
//! end tensions `T^2_2 = tau0`, `tau_max` on the `x2` ends, a free outer face, and on the
//! contact face `x3 = 0` bilateral contact `v^3 = 0` with the friction traction `t(u, sigma_n)`
//! of the chosen law on the physical slip `u` (regularised Coulomb by default:
//! `t = mu |sigma_n| u / max(|u|, eps)`, Kikuchi–Oden), or unilateral (Signorini) contact
//! `v^3 + g >= 0`, `lambda >= 0`, `(v^3 + g) lambda = 0` with friction where in contact
//! (`body.contact`, [`ContactKind`]; the full-system solvers).
//!
//! # Example
//! The paper's body on a coarse grid, then the same body in 3-D, without a scene file:
//! ```
//! use capstan::problem::{Dimension, Problem};
//! use capstan::elasticity::solid::SideFaces;
//! let mut problem = Problem::paper().with_grid(41, 9);
//! let plane = problem.solve().unwrap();
//! assert!(plane.solution.slip_fraction > 0.0);
//! problem.body.method = "fem-q1".parse().unwrap();
//! problem.body.dimension = Dimension::Solid { x1: [0.5, 1.5], n1: 3, sides: SideFaces::PlaneStrain };
//! let solid = problem.solve().unwrap();
//! // the extruded plane-strain body slides where Q1 in plane strain does
//! problem.body.dimension = Dimension::Plane;
//! let q1 = problem.solve().unwrap();
//! assert!((solid.solution.slip_fraction - q1.solution.slip_fraction).abs() < 1e-9);
//! ```

mod accuracy;
mod builder;
pub mod estimate;
mod exact_start;
mod friction;
pub mod nonlinear_registry;
mod path;
mod plain_attempts;
mod run_off;
mod solve;
mod solver;
mod target;
mod transitions;

pub use builder::Problem;
pub use capstan_elasticity::contact::{Body, ContactKind, Dimension, EndLoads, Gap};
pub use friction::Friction;
pub use path::SolvedPath;
pub use run_off::LowerEnd;
pub use solve::{Model, ProblemError, Solved, SolvedModel};
pub use solver::{
    AUTO_MATRIX_FREE_CONTACT_UNKNOWNS, SolveMethod, Solver, SolverChoice, auto_matrix_free,
};
pub use target::{AccuracyTarget, Assessment, Refined, Scaled, Step, assess, assess_twin};
pub use transitions::{
    DEFAULT_TRANSITION_GRADING, TRANSITION_FIRST_PASS, TRANSITION_LADDER_CELLS, TWIN_FACE_LAYERS,
    TwoPass, transition_corner_layers,
};
