//! [`Problem`] and its builder methods.

use capstan_elasticity::contact::{Body, EndLoads};
use capstan_geometry::Obstacle;

use super::friction::Friction;
use super::solver::Solver;

/// A thick-body contact problem: body, friction, loads and solver (see the [module
/// docs](super)). `S` is the obstacle surface: a registered [`Obstacle`] (what scenes name) or
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
