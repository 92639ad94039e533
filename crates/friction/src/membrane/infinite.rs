//! Corollary 1: the infinitely long membrane, in stresses and volume densities.

use capstan_geometry::Obstacle;

use super::obstacle::tension_profile;
use super::problem::{MembraneLoads, MembraneProblem, TensionProfile};
use crate::error::{FrictionError, check};

/// A membrane infinitely long in `x1` with any Poisson's ratio (Corollary 1): the tensile
/// stress `tau(theta)` under volume force densities.
///
/// # Math
/// Theorem 1 divided by `h l`: `tau = T/(h l)`, with the loads as volume densities
/// (`rho g` for gravity, `rho V^2` for the steady speed; paper-notes item 8). It is computed
/// as Theorem 1 with `h = l = 1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InfiniteMembrane {
    /// Coefficient of friction.
    pub mu: f64,
    /// Tensile stress `tau0 > 0` at `theta0`.
    pub tau0: f64,
    /// Start of the contact interval.
    pub theta0: f64,
    /// End of the contact interval.
    pub theta_max: f64,
    /// Output samples (`>= 2`).
    pub samples: usize,
    /// Mass per unit volume.
    pub density: f64,
    /// Gravitational acceleration (gravity is `(0, 0, -g)`).
    pub gravity: f64,
    /// Steady speed `V`.
    pub speed: f64,
}

impl InfiniteMembrane {
    /// The stress profile `tau(theta)` (in [`TensionProfile::tension`]).
    ///
    /// # Errors
    /// As [`tension_profile`]; `membrane.t0` names `tau0`.
    pub fn stress_profile(&self, obstacle: &Obstacle) -> Result<TensionProfile, FrictionError> {
        check("membrane.t0", self.tau0, "(0, inf)", |v| v > 0.0)?;
        let problem = MembraneProblem {
            mu: self.mu,
            t0: self.tau0,
            theta0: self.theta0,
            theta_max: self.theta_max,
            samples: self.samples,
            loads: MembraneLoads {
                gravity: self.gravity,
                density: self.density,
                width: 1.0,
                thickness: 1.0,
                speed: self.speed,
            },
        };
        tension_profile(obstacle, &problem)
    }
}
