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
//! `t = mu |sigma_n| u / max(|u|, eps)`, Kikuchi–Oden).
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

mod friction;
mod solve;
mod solver;

pub use capstan_elasticity::contact::{Body, Dimension, EndLoads};
pub use friction::Friction;
pub use solve::{Model, ProblemError, Solved, SolvedModel};
pub use solver::{SolveMethod, Solver};

use capstan_geometry::Obstacle;

/// A thick-body contact problem: body, friction, loads and solver (see the [module
/// docs](self)). `S` is the obstacle surface: a registered [`Obstacle`] (what scenes name) or
/// any user `Surface`.
#[derive(Debug, Clone)]
pub struct Problem<S = Obstacle> {
    /// The body on its obstacle, of either dimension, with its grid and discretisation.
    pub body: Body<S>,
    /// The friction law on the contact face.
    pub friction: Friction,
    /// The end tractions `tau0`, `tau_max`.
    pub loads: EndLoads,
    /// The contact solver and its work budgets.
    pub solver: Solver,
}

impl Problem<Obstacle> {
    /// The paper's section-3 problem (the default scene): the circle `a = b = 2`, `h = 1`,
    /// `E = 1e3`, `nu = 1/4`, `x2 in [-pi/2, pi/2]`, finite differences on 250 x 41 nodes,
    /// regularised Coulomb `mu = 1/2`, `eps = 1e-5`, `tau0 = 1`, `tau_max = 2`, the condensed
    /// (boundary-only) Newton.
    ///
    /// # Panics
    /// Never: the paper's obstacle is valid.
    pub fn paper() -> Self {
        let circle = capstan_geometry::EllipticalPrism::new(2.0, 2.0).expect("a = b = 2 is valid");
        Self::new(Body::new(Obstacle::Ellipse(circle), 250, 41))
    }
}

impl<S> Problem<S> {
    /// `body` with the paper's friction (regularised Coulomb, `mu = 1/2`, `eps = 1e-5`), loads
    /// (`tau0 = 1`, `tau_max = 2`) and the default solver.
    pub fn new(body: Body<S>) -> Self {
        Self {
            body,
            friction: Friction::default(),
            loads: EndLoads::new(1.0, 2.0),
            solver: Solver::default(),
        }
    }

    /// With `n2 x n3` nodes in the `(x2, x3)` plane (and the 3-D body's `n1` unchanged).
    #[must_use]
    pub fn with_grid(mut self, n2: usize, n3: usize) -> Self {
        self.body.n2 = n2;
        self.body.n3 = n3;
        self
    }

    /// With the friction law `friction`.
    #[must_use]
    pub fn with_friction(mut self, friction: Friction) -> Self {
        self.friction = friction;
        self
    }

    /// With the end tractions `loads`.
    #[must_use]
    pub fn with_loads(mut self, loads: EndLoads) -> Self {
        self.loads = loads;
        self
    }

    /// With the solver `solver`.
    #[must_use]
    pub fn with_solver(mut self, solver: Solver) -> Self {
        self.solver = solver;
        self
    }
}
