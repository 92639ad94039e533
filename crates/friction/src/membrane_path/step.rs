//! What one load step of the semismooth membrane takes and gives: settings, per-iteration
//! progress, the state a step starts from and the step's solution.

use crate::nonsmooth_law::FrictionState;

/// Settings of the semismooth Newton iteration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SemismoothSettings {
    /// Largest number of Newton steps per load step (`membrane.max_newton_iterations`).
    pub max_iterations: usize,
    /// Converged when `max(|E_i|, |l_i F_i|) <= tolerance * scale` (`scale`: the largest end
    /// tension), or below the round-off floor.
    pub tolerance: f64,
    /// The augmentation `r` (traction per unit length per unit slip); `None`: `k / (d J_i)^2`
    /// at each node.
    pub augmentation: Option<f64>,
    /// Start each step between two tension ends from the capstan sweep (the slip balance
    /// marched in from the loaded end until it meets the previous tensions) rather than from
    /// the previous state. Semismooth Newton moves a slip front by about one node per
    /// iteration, so without it a step costs about as many iterations as its front moves
    /// nodes; with it a belt step takes a few. Default `true`.
    pub sweep: bool,
}

impl Default for SemismoothSettings {
    fn default() -> Self {
        Self {
            max_iterations: 100,
            tolerance: 1e-12,
            augmentation: None,
            sweep: true,
        }
    }
}

/// One semismooth Newton iteration, for observers: residual and the active set.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SemismoothIteration {
    /// Iteration (0: the start).
    pub iteration: usize,
    /// `max(|E_i|, |l_i F_i|)` after it.
    pub residual: f64,
    /// Line-search step length (0 at the start).
    pub step: f64,
    /// Nodes in stick.
    pub stick: usize,
    /// Nodes in slip.
    pub slip: usize,
    /// Nodes without compression.
    pub separated: usize,
    /// Nodes whose state changed in this iteration.
    pub changes: usize,
}

/// The history a load step starts from: displacements and friction forces at the nodes.
#[derive(Debug, Clone, PartialEq)]
pub struct MembraneState {
    /// Tangential displacement `w` at the nodes.
    pub displacement: Vec<f64>,
    /// Friction force per unit length `t` at the nodes (on the membrane, along the tangent).
    pub friction: Vec<f64>,
}

/// The solution of one load step.
#[derive(Debug, Clone, PartialEq)]
pub struct MembraneStep {
    /// Node angles.
    pub theta: Vec<f64>,
    /// Tangential displacement `w` at the nodes.
    pub displacement: Vec<f64>,
    /// The step's slip increment `w - w_old`.
    pub slip_increment: Vec<f64>,
    /// Friction force per unit length `t` at the nodes.
    pub friction: Vec<f64>,
    /// Tension at the nodes (given at tension ends).
    pub tension: Vec<f64>,
    /// Normal reaction `kappa T` per unit length.
    pub reaction: Vec<f64>,
    /// Stick, slip or separated at each node.
    pub states: Vec<FrictionState>,
    /// Semismooth Newton iterations.
    pub iterations: usize,
    /// Final residual.
    pub residual: f64,
    /// Energy dissipated by friction in the step, `sum_i -l_i t_i du_i >= 0`.
    pub dissipation: f64,
}

impl MembraneStep {
    /// The state the next step starts from.
    pub fn state(&self) -> MembraneState {
        MembraneState {
            displacement: self.displacement.clone(),
            friction: self.friction.clone(),
        }
    }

    /// `T(theta1) / T(theta0)`.
    ///
    /// # Panics
    /// Never for steps built here (at least three nodes).
    pub fn tension_ratio(&self) -> f64 {
        self.tension.last().expect("nodes") / self.tension[0]
    }

    /// The maximal runs of slipping nodes, as `[theta_first, theta_last]` node angles.
    pub fn slip_intervals(&self) -> Vec<[f64; 2]> {
        let mut out: Vec<[f64; 2]> = Vec::new();
        let mut open = false;
        for (i, s) in self.states.iter().enumerate() {
            if *s == FrictionState::Slip {
                if open {
                    out.last_mut().expect("open interval")[1] = self.theta[i];
                } else {
                    out.push([self.theta[i], self.theta[i]]);
                    open = true;
                }
            } else {
                open = false;
            }
        }
        out
    }
}
