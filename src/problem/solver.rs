//! The contact solver of a [`super::Problem`] and its work budgets.

use capstan_elasticity::contact::{BulkMultigrid, ContactSettings, FullSystemSettings};
use capstan_elasticity::solvers::{LinearBackend, NonlinearMethod};

/// How the contact problem is solved (`solver.nonlinear`, `solver.linear` in scenes).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum SolveMethod {
    /// `newton` (default): boundary-only Newton on the condensed contact tractions, the bulk
    /// factorised once; also gives the limiting tension ratios when the body can slide rigidly.
    #[default]
    Condensed,
    /// `full-newton`: Newton on the full residual with the linear backend, refactorised each
    /// step (grid sequencing on the plane-strain body).
    FullNewton(LinearBackend),
    /// `jacobi-newton`: the paper's Jacobi–Newton (damped Jacobi, relaxation 1/2).
    JacobiNewton,
    /// `full-newton` with `solver.linear = "multigrid"`: each Newton step by GMRES with the
    /// geometric multigrid of the 3-D body ([`BulkMultigrid`]).
    FullNewtonMultigrid,
    /// `full-newton` with `solver.linear = "petsc"` (feature `petsc`): each Newton step by
    /// PETSc's KSP over the MPI ranks, Newton replicated on every rank
    /// ([`FullSystemSettings::external`]).
    FullNewtonPetsc,
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
            SolveMethod::FullNewtonMultigrid => s.multigrid = Some(BulkMultigrid::default()),
            SolveMethod::FullNewtonPetsc => s.external = crate::scale::petsc_backend(),
            SolveMethod::JacobiNewton => {
                s.method = NonlinearMethod::JacobiNewton;
                s.newton.iterative.relaxation = 0.5; // undamped Jacobi diverges here
                s.newton.iterative.max_iterations = 10_000_000;
                s.newton.iterative.tolerance = 1e-12;
                s.continuation.tolerance = 1e-9;
            }
            SolveMethod::Condensed => {}
        }
        s.continuation = ContactSettings {
            tolerance: s.continuation.tolerance,
            ..self.budgets
        };
        if let Some(w) = self.relaxation {
            s.newton.iterative.relaxation = w;
        }
        if let Some(sweeps) = self.max_sweeps {
            s.newton.iterative.max_iterations = sweeps;
            if let Some(m) = s.multigrid.as_mut() {
                m.krylov.max_iterations = sweeps;
            }
        }
        s
    }
}
