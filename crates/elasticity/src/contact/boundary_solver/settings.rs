//! Settings of the contact Newton iterations and what the solver reports of its setup.

use capstan_solvers::LinearBackend;

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
