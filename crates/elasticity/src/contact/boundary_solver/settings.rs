//! Settings of the contact Newton iterations and what the solver reports of its setup.

use capstan_solvers::{LinearBackend, Merit, NewtonPolicy, ResidualNorm, ShortStep, StepControl};

use crate::contact::error::ContactError;
use crate::error::ElasticityError;

/// Settings of the contact Newton iterations (both solvers) and of the load continuation.
///
/// # Math
/// ```text
/// converged when max_k |G_k| <= tolerance * max(|tau0|, |tau_max|) * max_k sqrt(g_22)
/// continuation: lambda = 0 -> 1 on the loads, step x1.5 after success, /2 after failure
/// ```
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ContactSettings {
    /// Newton iterations per continuation step.
    pub max_iterations: usize,
    /// Relative tolerance on the condensed residual (see above).
    pub tolerance: f64,
    /// First load step of the continuation (used only when plain Newton fails).
    pub initial_load_step: f64,
    /// Smallest load step before giving up.
    pub min_load_step: f64,
    /// Cap on continuation steps.
    pub max_continuation_steps: usize,
    /// The linear backend that factorises the stabilised bulk (any registered one:
    /// [`capstan_solvers::linear_registry`]; default `lu`).
    pub linear: LinearBackend,
}

impl Default for ContactSettings {
    fn default() -> Self {
        Self {
            max_iterations: 60,
            tolerance: 1e-10,
            initial_load_step: 0.25,
            min_load_step: 1e-4,
            max_continuation_steps: 400,
            linear: LinearBackend::LU,
        }
    }
}

impl ContactSettings {
    /// The Newton policy of the condensed face systems (the regularised condensed Newton and
    /// the semismooth exact-friction step): converged when `max_k |F_k| <= tol` (absolute),
    /// at most `max_iterations` steps, backtracking on `|F|^2` with Armijo `1e-4` down to a
    /// step of `1e-8`, a shorter step a failure.
    pub(crate) fn face_policy(&self, tol: f64) -> NewtonPolicy {
        NewtonPolicy {
            max_iterations: self.max_iterations,
            absolute_tolerance: tol,
            relative_tolerance: 0.0,
            norm: ResidualNorm::Max,
            step: StepControl::Backtracking {
                merit: Merit::SumOfSquares { armijo: 1e-4 },
                min_step: 1e-8,
                short_step: ShortStep::Fail,
            },
            divergence_limit: None,
            step_stagnation: false,
            check_finite: false,
        }
    }

    /// Checks every field.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming the first bad field.
    pub fn validate(&self) -> Result<(), ContactError> {
        let bad = |field, value, allowed| {
            Err(ContactError::from(ElasticityError::InvalidParameter {
                field,
                value,
                allowed,
            }))
        };
        if self.max_iterations == 0 {
            return bad("max_iterations", 0.0, "[1, inf)");
        }
        if !(self.tolerance > 0.0 && self.tolerance < 1.0) {
            return bad("tolerance", self.tolerance, "(0, 1)");
        }
        if !(self.initial_load_step > 0.0 && self.initial_load_step <= 1.0) {
            return bad("initial_load_step", self.initial_load_step, "(0, 1]");
        }
        if !(self.min_load_step > 0.0 && self.min_load_step <= self.initial_load_step) {
            return bad(
                "min_load_step",
                self.min_load_step,
                "(0, initial_load_step]",
            );
        }
        Ok(())
    }
}

/// The rigid sliding mode of the bilaterally constrained body (a circular obstacle) and the
/// range of tension ratios friction can hold against it.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SlidingMode {
    /// Smallest singular value over the largest of the frictionless condensed operator.
    pub relative_singular_value: f64,
    /// `tau_max / tau0` at which the whole contact slides in the negative direction.
    pub lower_ratio: f64,
    /// `tau_max / tau0` at which the whole contact slides in the positive direction.
    pub upper_ratio: f64,
    /// The `tau0` of these ratios (they depend on it unless the law is homogeneous in the
    /// normal stress, as Coulomb's is; [`BoundarySolver::sliding`](super::BoundarySolver::sliding) reports `tau0 = 1`).
    pub tau0: f64,
    /// 3-D bodies only: the ratios `[lower, upper]` at which full slip along the rigid mode
    /// balances the loads where `lower_ratio` / `upper_ratio` is unbounded because some of
    /// that full slip's friction pushes *along* the slip (bilateral contact in tension, more
    /// than the wrong-way share the 2-D bound allows) while the friction as a whole resists
    /// it (`-sum_k w_k t_k . u_k > 0`); `None` in 2-D, or when the bound itself is finite
    /// each way, or when neither way has such a balance. A 3-D body whose full slip is not
    /// rigid (a band on a cone also slides towards the apex) runs off along the rigid mode as
    /// the ratio approaches this balance: its displacements grow like `c / (r_L - r)`
    /// (measured on the default cone, see docs/solid.md), so no equilibrium is reached past
    /// it along the load path. [`BoundarySolver`](super::BoundarySolver) does not refuse
    /// these ratios up front (friction may still hold them in another state); it reports
    /// [`ContactError::NoEquilibrium`](crate::contact::ContactError::NoEquilibrium) with
    /// this range when plain Newton fails past them, instead of running the load
    /// continuation, whose path would cross the run-off.
    pub runaway_ratios: Option<[f64; 2]>,
}

/// Work done once by [`BoundarySolver::new`](super::BoundarySolver::new).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SetupStats {
    /// Contact unknowns `m`.
    pub contact_unknowns: usize,
    /// Bulk unknowns `n`.
    pub bulk_unknowns: usize,
    /// Sparse LU factorisations of the bulk (1; 2 when the spring was softened, see
    /// [`BoundarySolver`](super::BoundarySolver); 0 for a solver from [`BoundarySolver::with_model`](super::BoundarySolver::with_model)).
    pub factorisations: usize,
    /// Sparse solves with the bulk factors: 2 (the unit loads) after a condensation from the
    /// Schur complements (the `lu` default), `m` per factorisation `+ 2` by solves.
    pub bulk_solves: usize,
}

/// The method name (`stats.method`) of a solution by
/// [`super::BoundarySolver::solve_exact_from_observed`].
pub const CONDENSED_SEMISMOOTH: &str = "condensed-semismooth";
