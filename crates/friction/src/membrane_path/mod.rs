//! The membrane displacement model with exact (nonsmooth) friction and load paths with memory:
//! belt creep, hysteresis.
//!
//! # Math
//! The discrete membrane of [`crate::membrane_displacement`] (nodes `theta_i`, half-cell
//! tensions `T_{i+1/2} = c_{i+1/2} (w_{i+1} - w_i)`), with the friction force per unit length
//! `t_i` a second unknown at each node. A load step goes from the state `(w_old, t_old)` to
//! `(w, t)`; friction acts on the slip *increment* `du_i = w_i - w_old_i`:
//! ```text
//! E_i = T_{i+1/2} - T_{i-1/2} + l_i t_i = 0                         equilibrium (l_i = d J_i;
//!                                                                   half cells at tension ends)
//! F_i = t_i - P_[-g_i, g_i](t_i - r_i du_i) = 0,  g_i = mu kappa_i T_i    exact Coulomb
//! ```
//! (`P` is the law's return map on the trial `(0, t*)`, [`crate::NonsmoothFrictionLaw`];
//! `T_i` is the node tension, the given tension at a tension end). `F_i = 0` says: stick
//! (`du_i = 0`, `|t_i| <= g_i`) or slip (`t_i = -g_i sign(du_i)`). Semismooth Newton linearises
//! `P` with its generalised derivatives (`D_i = dt/dt*`, 1 in stick, 0 in slip;
//! `S_i = dt/dsigma_n`) and eliminates `dt_i` node by node, leaving a tridiagonal system:
//! ```text
//! (1 - D_i) A_i.dw - l_i S_i kappa_i B_i.dw - l_i D_i r_i dw_i = -(1 - D_i) E_i + l_i F_i
//! ```
//! (`A_i = dE_i/dw`, `B_i = dT_i/dw`): stick rows hold `w_i` at `w_old_i`, slip rows are the
//! capstan balance `dT/ds = +-mu kappa T`. Then `dt` follows from the equilibrium rows. The
//! augmentation `r_i` defaults to `k / (d J_i)^2`; any `r > 0` has the same solution.
//! Convergence: `max(|E_i|, |l_i F_i|) <= tolerance * scale` (or the round-off floor of
//! [`crate::membrane_displacement::MembraneNewton`]), within `max_iterations` steps
//! ([`FrictionError::SemismoothNotConverged`]); a backtracking search on that norm.
//!
//! A load path ([`SemismoothMembrane::solve_path`]) starts from the membrane wrapped at the
//! uniform tension `T0` of its start (`w = T0 (s - s0)/k`, `t = 0`: an equilibrium without
//! friction) and solves each end tension in turn from the previous state. Two tension ends
//! whose ratio friction cannot hold slide as a whole: [`FrictionError::RigidSliding`].
//! Belt creep on a circle has a closed form ([`creep::BeltCreep`]).
//!
//! # References
//! Alart and Curnier (1991); Johnson, *Contact Mechanics* (1985), 8.5 (belt creep); paper
//! section 2 (the capstan equation is the slip-zone balance).

pub mod creep;
mod semismooth;
mod step;

use capstan_geometry::ProfileCurve;

use crate::error::{FrictionError, check};
use crate::membrane_displacement::{EndCondition, MembraneDisplacementProblem, MembraneGrid};
use crate::nonsmooth_law::NonsmoothFrictionLaw;

use semismooth::StepSolver;
pub use step::{MembraneState, MembraneStep, SemismoothIteration, SemismoothSettings};

/// A load path solved step by step.
#[derive(Debug, Clone, PartialEq)]
pub struct MembranePath {
    /// The state the path starts from (wrapped at the start tension).
    pub initial: MembraneState,
    /// The end tensions at `theta1`, one per step.
    pub end_tensions: Vec<f64>,
    /// The solved steps.
    pub steps: Vec<MembraneStep>,
}

impl MembranePath {
    /// The displacement of the end `theta1` in each step, from the initial state.
    ///
    /// # Panics
    /// Never for paths built here.
    pub fn end_displacements(&self) -> Vec<f64> {
        let w0 = *self.initial.displacement.last().expect("nodes");
        self.steps
            .iter()
            .map(|s| s.displacement.last().expect("nodes") - w0)
            .collect()
    }

    /// The energy dissipated by friction over the path.
    pub fn dissipation(&self) -> f64 {
        self.steps.iter().map(|s| s.dissipation).sum()
    }
}

/// The membrane on a prism profile with a nonsmooth friction law (exact Coulomb), solved by
/// semismooth Newton step by step along a load path (see the module docs).
///
/// # Example
/// Belt creep: a belt wrapped on half a circle at `T0 = 1`, the far end pulled to 2; a slip
/// zone of angle `ln(2)/mu` grows from the pulled end.
/// ```
/// use capstan_friction::membrane_displacement::{EndCondition, MembraneDisplacementProblem};
/// use capstan_friction::membrane_path::{SemismoothMembrane, creep::BeltCreep};
/// use capstan_friction::{ExactCoulomb, ExactCoulombParams};
/// use capstan_geometry::CircularCylinder;
/// let circle = CircularCylinder::new(1.0).unwrap();
/// let problem = MembraneDisplacementProblem {
///     theta0: 0.0, theta1: std::f64::consts::PI, nodes: 801, stiffness: 100.0,
///     start: EndCondition::Tension(1.0), end: EndCondition::Tension(1.0),
/// };
/// let m = SemismoothMembrane::new(&circle, ExactCoulomb, ExactCoulombParams::new(0.3).unwrap());
/// let path = m.solve_path(&problem, &[2.0], Default::default(), &mut |_, _| {}).unwrap();
/// let exact = BeltCreep { radius: 1.0, mu: 0.3, stiffness: 100.0, t0: 1.0, theta0: 0.0, theta1: std::f64::consts::PI };
/// let w = path.end_displacements()[0];
/// assert!((w / exact.loading_displacement(2.0).unwrap() - 1.0).abs() < 1e-4);
/// ```
#[derive(Debug, Clone)]
pub struct SemismoothMembrane<'a, C: ?Sized, L: NonsmoothFrictionLaw<f64>> {
    profile: &'a C,
    law: L,
    params: L::Params,
}

impl<'a, C: ProfileCurve<f64> + ?Sized, L: NonsmoothFrictionLaw<f64>> SemismoothMembrane<'a, C, L> {
    /// The membrane on `profile` with the nonsmooth `law` and its parameters.
    pub fn new(profile: &'a C, law: L, params: L::Params) -> Self {
        Self {
            profile,
            law,
            params,
        }
    }

    /// The membrane wrapped at the uniform tension `tension` with `w(theta0) = 0` and no
    /// friction: `w_{i+1} - w_i = tension / c_{i+1/2}` (the discrete `w = T (s - s0)/k`).
    ///
    /// # Errors
    /// As [`crate::membrane_displacement::MembraneDisplacement::solve`] for the problem's
    /// values; [`FrictionError::InvalidParameter`] naming `membrane.t0` for a non-finite
    /// tension.
    pub fn wrapped(
        &self,
        problem: &MembraneDisplacementProblem,
        tension: f64,
    ) -> Result<MembraneState, FrictionError> {
        check("membrane.t0", tension, "finite values", |_| true)?;
        let grid = MembraneGrid::new(self.profile, problem)?;
        let mut w = vec![0.0; problem.nodes];
        for i in 1..problem.nodes {
            w[i] = w[i - 1] + tension / grid.c[i - 1];
        }
        Ok(MembraneState {
            displacement: w,
            friction: vec![0.0; problem.nodes],
        })
    }

    /// Solves one load step (the end conditions of `problem`) from `previous`.
    ///
    /// # Errors
    /// [`FrictionError::InvalidParameter`] for bad problem values, settings or a `previous`
    /// state of the wrong length; [`FrictionError::NonPositiveCurvature`] on a non-convex
    /// interval; [`FrictionError::RigidSliding`] when two end tensions cannot be held;
    /// [`FrictionError::SemismoothNotConverged`] when the budget is spent.
    pub fn solve_step(
        &self,
        problem: &MembraneDisplacementProblem,
        previous: &MembraneState,
        settings: SemismoothSettings,
        progress: &mut dyn FnMut(&SemismoothIteration),
    ) -> Result<MembraneStep, FrictionError> {
        let solver = StepSolver {
            law: &self.law,
            params: &self.params,
            grid: StepSolver::<L>::grid(self.profile, problem)?,
            problem: *problem,
        };
        solver.solve(previous, &settings, progress)
    }

    /// Solves the load path `end_tensions` (the tension at `theta1`, one value per step) from
    /// the membrane wrapped at the start tension `T0` of `problem` (whose end condition at
    /// `theta1` must be a tension; its value is replaced by each path value). `progress(step,
    /// iteration)` sees every iteration of every step (steps counted from 0).
    ///
    /// # Errors
    /// [`FrictionError::Unsupported`] naming `loads.path` unless both ends carry tensions;
    /// [`FrictionError::InvalidParameter`] naming `loads.path` for an empty path or a value
    /// that is not finite and positive; as [`SemismoothMembrane::solve_step`].
    pub fn solve_path(
        &self,
        problem: &MembraneDisplacementProblem,
        end_tensions: &[f64],
        settings: SemismoothSettings,
        progress: &mut dyn FnMut(usize, &SemismoothIteration),
    ) -> Result<MembranePath, FrictionError> {
        let (EndCondition::Tension(t0), EndCondition::Tension(_)) = (problem.start, problem.end)
        else {
            return Err(FrictionError::Unsupported {
                field: "loads.path",
                why: "a load path needs tensions at both ends of the membrane",
            });
        };
        check("membrane.t0", t0, "(0, inf)", |v| v > 0.0)?;
        check(
            "loads.path",
            end_tensions.len() as f64,
            "at least one value",
            |v| v >= 1.0,
        )?;
        for &v in end_tensions {
            check("loads.path", v, "(0, inf) for every value", |v| v > 0.0)?;
        }
        let initial = self.wrapped(problem, t0)?;
        let mut state = initial.clone();
        let mut steps = Vec::with_capacity(end_tensions.len());
        for (k, &te) in end_tensions.iter().enumerate() {
            let step_problem = MembraneDisplacementProblem {
                end: EndCondition::Tension(te),
                ..*problem
            };
            let step =
                self.solve_step(&step_problem, &state, settings, &mut |it| progress(k, it))?;
            state = step.state();
            steps.push(step);
        }
        Ok(MembranePath {
            initial,
            end_tensions: end_tensions.to_vec(),
            steps,
        })
    }
}
