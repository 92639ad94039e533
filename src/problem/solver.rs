//! The contact solver of a [`super::Problem`] and its work budgets.

use capstan_elasticity::contact::{Body, ContactSettings, Dimension, FullSystemSettings};
use capstan_elasticity::solvers::{LinearBackend, NonlinearMethod};

/// How the contact problem is solved (`solver.nonlinear`, `solver.linear` in scenes).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum SolveMethod {
    /// `auto` (default): the method [`SolveMethod::resolved`] picks for the body: condensed
    /// while the dense Newton on the contact unknowns is cheap, full-system Newton otherwise.
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

/// Contact unknowns up to which `auto` condenses: the condensed Newton factorises a dense
/// `m x m` matrix each iteration (`m^3 / 3` multiply-adds: 0.4 GFlop at 1,500), the condensation
/// itself costs about two sparse factorisations (the Schur complement, from one partial
/// factorisation) and `m^3` dense work.
pub const AUTO_CONDENSED_CONTACT_UNKNOWNS: usize = 1500;

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
    /// The concrete method for `body`: [`Solver::method`] unless [`SolveMethod::Auto`], which is
    /// ```text
    /// m = contact unknowns (n2 in plane strain, 2 n1 n2 on the 3-D box)
    /// m <= 1500:   condensed (Newton on m unknowns, bulk condensed once: also what a sweep or
    ///              a threshold re-uses)
    /// m >  1500:   full-system Newton, LU (the dense m x m Newton would dominate)
    /// ```
    /// and the [`SolverChoice`] reported with it.
    pub fn resolved<S>(&self, body: &Body<S>) -> (SolveMethod, SolverChoice) {
        let m = match body.dimension {
            Dimension::Plane => body.n2,
            Dimension::Solid { n1, .. } => 2 * n1 * body.n2,
        };
        let (method, reason) = match self.method {
            SolveMethod::Auto if m <= AUTO_CONDENSED_CONTACT_UNKNOWNS => (
                SolveMethod::Condensed,
                format!(
                    "{m} contact unknowns <= {AUTO_CONDENSED_CONTACT_UNKNOWNS}: condensed onto the contact face"
                ),
            ),
            SolveMethod::Auto => (
                SolveMethod::FullNewton(LinearBackend::LU),
                format!(
                    "{m} contact unknowns > {AUTO_CONDENSED_CONTACT_UNKNOWNS}: a dense condensed Newton would dominate; full-system Newton with the sparse LU"
                ),
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
