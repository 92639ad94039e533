//! The contact solver of a [`super::Problem`] and its work budgets.

use capstan_elasticity::contact::{
    Body, ContactSettings, Dimension, FullSystemSettings, MatrixFreeSettings,
};
use capstan_elasticity::finite_element::VolumetricIntegration;
use capstan_elasticity::solvers::{LinearBackend, NonlinearMethod};

/// How the contact problem is solved (`solver.nonlinear`, `solver.linear` in scenes).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum SolveMethod {
    /// `auto` (default): the method [`Solver::resolved`] picks for the body (the condensed
    /// solver today, see there).
    #[default]
    Auto,
    /// `newton`: boundary-only Newton on the condensed contact tractions, the bulk
    /// factorised once; also gives the limiting tension ratios when the body can slide rigidly.
    Condensed,
    /// `full-newton`: Newton on the full residual with any registered linear backend
    /// (`capstan_solvers::linear_registry`): a factorisation or stationary iteration each
    /// step, `multigrid` (GMRES with the geometric multigrid of the 3-D body), `petsc` (feature
    /// `petsc`: PETSc's KSP over the MPI ranks, Newton replicated on every rank) or a user's
    /// (grid sequencing on the plane-strain body).
    FullNewton(LinearBackend),
    /// `jacobi-newton`: the paper's Jacobi–Newton (damped Jacobi, relaxation 1/2).
    JacobiNewton,
}

impl SolveMethod {
    /// Whether the method condenses the contact problem onto the contact face (`newton`, and
    /// `auto`, which condenses every bilateral body: [`Solver::resolved`]).
    pub fn condenses(&self) -> bool {
        matches!(self, Self::Condensed | Self::Auto)
    }
}

/// What `auto` chose and why (`solver_choice` in the JSON report).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SolverChoice {
    /// `newton` (condensed), `full-newton` or `jacobi-newton`: the scene name of the method run.
    pub nonlinear: &'static str,
    /// The linear backend's registered name (`lu`, `multigrid`, ...).
    pub linear: &'static str,
    /// Whether `auto` made the choice (`false`: the scene or the program named the method).
    pub auto: bool,
    /// Why, in a few words.
    pub reason: String,
}

impl Solver {
    /// The concrete method for `body`: [`Solver::method`] unless [`SolveMethod::Auto`], which
    /// is the condensed solver for every body today, and the [`SolverChoice`] reported with it.
    ///
    /// Measured (release, 2 shared cores): in plane strain the condensation from the Schur
    /// complement keeps `newton` within 20% of `full-newton` from FD 250 x 41 to Q2 1025 x 131
    /// (and 2x faster on the default scene); on the first 3-D try (Q1, 5 x 250 x 41, 2,500
    /// contact unknowns) `full-newton` with `lu` ran out of memory (killed at 22.6 GB) and
    /// `multigrid` does not converge on that grid (249 cells along `x2` do not coarsen), so
    /// `auto` condenses there too.
    pub fn resolved<S>(&self, body: &Body<S>) -> (SolveMethod, SolverChoice) {
        let m = match body.dimension {
            Dimension::Plane => body.n2,
            Dimension::Solid { n1, .. } => 2 * n1 * body.n2,
        };
        let solid = matches!(body.dimension, Dimension::Solid { .. });
        let mesh = body
            .method
            .scheme(&body.settings)
            .is_ok_and(|s| s.is_mesh());
        // a mesh (fem-qp-corner) is assembled on its own nodes: no matrix-free operator
        let matrix_free = !mesh
            && auto_matrix_free(
                solid,
                m,
                body.contact.is_unilateral(),
                body.body_force.is_some(),
                body.settings.volumetric == VolumetricIntegration::Full,
            );
        let (method, reason) = match self.method {
            SolveMethod::Auto if matrix_free => (
                SolveMethod::FullNewton(LinearBackend::MATRIX_FREE_MG),
                format!(
                    "3-D body with {m} contact unknowns: the matrix-free full-system Newton (inexact Newton-Krylov, p-multigrid)"
                ),
            ),
            // the condensed solver keeps v^3 = 0: unilateral contact needs the full system
            SolveMethod::Auto if body.contact.is_unilateral() => (
                SolveMethod::FullNewton(LinearBackend::LU),
                "unilateral contact: the full-system (semismooth) Newton, sparse LU".into(),
            ),
            // measured (docs/high-order.md): the condensed Newton stalls at its first iterate
            // once the corner layers' contact nodes are 1e-3 of a cell apart
            SolveMethod::Auto if mesh => (
                SolveMethod::FullNewton(LinearBackend::LU),
                format!(
                    "{m} grid contact nodes on a corner-refined mesh: the full-system Newton, sparse LU"
                ),
            ),
            SolveMethod::Auto => (
                SolveMethod::Condensed,
                format!("{m} contact unknowns: condensed onto the contact face (Schur complement)"),
            ),
            other => (other, "named by the solver settings".into()),
        };
        let (nonlinear, linear) = match method {
            SolveMethod::FullNewton(linear) => ("full-newton", linear.name()),
            SolveMethod::JacobiNewton => ("jacobi-newton", "jacobi"),
            _ => ("newton", self.budgets.linear.name()),
        };
        let choice = SolverChoice {
            nonlinear,
            linear,
            auto: self.method == SolveMethod::Auto,
            reason,
        };
        (method, choice)
    }
}

/// Contact unknowns of a 3-D body above which `auto` solves by the matrix-free full-system
/// Newton rather than condensing: measured on the first 3-D try (Q1, 5 x 250 x 41, 153,750
/// unknowns, 2,500 contact unknowns) the condensed solver took 254 s (207 s of set-up for the
/// dense condensation), the matrix-free Newton 74 CPU-s (docs/solid.md); small bodies keep
/// the condensed solver (it also gives the limiting ratios).
pub const AUTO_MATRIX_FREE_CONTACT_UNKNOWNS: usize = 2_000;

/// Whether `auto` picks the matrix-free full-system Newton (`matrix-free-mg`): a 3-D body
/// (`solid`) with more than [`AUTO_MATRIX_FREE_CONTACT_UNKNOWNS`] contact unknowns (`m`),
/// bilateral contact, no body force, full volumetric integration (what the matrix-free path
/// supports).
pub fn auto_matrix_free(
    solid: bool,
    m: usize,
    unilateral: bool,
    body_force: bool,
    full_integration: bool,
) -> bool {
    solid && m > AUTO_MATRIX_FREE_CONTACT_UNKNOWNS && !unilateral && !body_force && full_integration
}

/// The contact solver with its work budgets.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Solver {
    /// The method.
    pub method: SolveMethod,
    /// Newton iterations per load step, continuation steps, smallest load step
    /// (`solver.max_iterations`, `max_continuation_steps`, `min_load_step`).
    pub budgets: ContactSettings,
    /// Linear iterations per solve of the iterative backends (`solver.max_sweeps`); `None`:
    /// each backend's default.
    pub max_sweeps: Option<usize>,
    /// The relaxation weight `w` of the Jacobi / Gauss–Seidel iterations
    /// (`solver.relaxation`); `None`: 1, and 1/2 for `jacobi-newton` (the paper's own Jacobi is
    /// undamped, `w = 1`, and diverges on the paper's body).
    pub relaxation: Option<f64>,
}

impl Solver {
    /// `method` with the default budgets.
    pub fn new(method: SolveMethod) -> Self {
        Self {
            method,
            ..Default::default()
        }
    }

    /// The settings of the matrix-free Newton (`full-newton` with `matrix-free-mg`) with the
    /// budgets: Newton steps and continuation as [`Solver::budgets`], `solver.max_sweeps` the
    /// Krylov iterations summed over one Newton solve.
    pub fn matrix_free_settings(&self) -> MatrixFreeSettings {
        let mut s = MatrixFreeSettings::default();
        s.continuation = ContactSettings {
            tolerance: s.continuation.tolerance,
            ..self.budgets
        };
        if let Some(sweeps) = self.max_sweeps {
            s.max_linear_iterations = sweeps;
        }
        s
    }

    /// The settings of the full-system solvers (`full-newton`, `jacobi-newton`) with the
    /// budgets.
    pub fn full_settings(&self) -> FullSystemSettings {
        let mut s = FullSystemSettings::default();
        match self.method {
            SolveMethod::FullNewton(linear) => s.newton.linear = linear,
            SolveMethod::JacobiNewton => {
                s.method = NonlinearMethod::JacobiNewton;
                s.newton.iterative.relaxation = 0.5; // undamped Jacobi diverges here
                s.newton.iterative.max_iterations = 10_000_000;
                s.newton.iterative.tolerance = 1e-12;
                s.continuation.tolerance = 1e-9;
            }
            SolveMethod::Condensed | SolveMethod::Auto => {}
        }
        s.continuation = ContactSettings {
            tolerance: s.continuation.tolerance,
            ..self.budgets
        };
        if let Some(w) = self.relaxation {
            s.newton.iterative.relaxation = w;
        }
        if let Some(sweeps) = self.max_sweeps {
            // the budget of whichever family the backend is
            s.newton.iterative.max_iterations = sweeps;
            s.newton.krylov.max_iterations = sweeps;
        }
        s
    }
}
