//! The start of the exact-friction (semismooth) Newton: the same problem under the law's
//! regularisation, solved by the condensed solver.

use std::time::Instant;

use capstan_elasticity::contact::{BoundarySolver, ContactError};
use capstan_elasticity::solvers::{Observer, Progress, SetUpPhase};
use capstan_geometry::Surface;

use super::builder::Problem;
use super::friction::Friction;
use super::solve::{ProblemError, Solved, SolvedModel};
use super::solver::SolverChoice;

/// A start for exact friction and the condensed Newton iterations it took.
pub(super) struct RegularisedStart {
    /// The displacement (one value per unknown of the exact model: it is built on the same
    /// body, its friction rows replaced).
    pub displacement: Vec<f64>,
    /// Condensed Newton iterations of the regularised solve.
    pub iterations: usize,
}

impl<S: Surface<f64> + Clone + Send + Sync + 'static> Problem<S> {
    /// Exact friction `exact-X` on bilateral contact: the solution of the same problem with
    /// the regularised law `X` of width `friction.eps` (`exact-coulomb` -> `coulomb`,
    /// `exact-orthotropic-coulomb` -> `orthotropic-coulomb`) by the condensed solver, its
    /// slip-step control and continuations (10 iterations on the paper's default scene).
    /// The semismooth Newton on the Alart–Curnier rows then starts within its region of fast
    /// convergence (3 iterations there), where from the stuck state at full load its
    /// regularised start stagnates and the load continuation runs (29 iterations before).
    /// `None` (the stuck start) for unilateral contact (the condensed solver keeps
    /// `v^3 = 0`), a law without a registered regularisation, or any failure of the
    /// regularised solve (no equilibrium, non-convergence): the caller's own path reports
    /// those.
    pub(super) fn regularised_start(
        &self,
        observer: &mut dyn Observer<f64>,
    ) -> Option<RegularisedStart> {
        if self.body.contact.is_unilateral() {
            return None;
        }
        let name = self.friction.law.strip_prefix("exact-")?;
        if !capstan_friction::registry::is_registered(name) {
            return None;
        }
        let problem = Problem {
            friction: Friction::named(name, self.friction.settings.clone()),
            ..self.clone()
        };
        let model = problem.model().ok()?;
        let solver = BoundarySolver::new(&model, self.solver.budgets).ok()?;
        let solution = solver.solve_observed(self.loads, observer).ok()?;
        Some(RegularisedStart {
            iterations: solution.stats.newton_iterations,
            displacement: solution.displacement,
        })
    }
}

impl<S: Surface<f64> + Clone + Send + Sync + 'static> Problem<S> {
    /// Exact friction `exact-X` on bilateral contact, all on the condensed solver: the
    /// regularised law `X` of width `friction.eps` solved by the condensed Newton (as
    /// [`Problem::regularised_start`]), then the semismooth Newton on the condensed contact
    /// face ([`BoundarySolver::solve_exact_from_observed`]) from its contact unknowns, on the
    /// same factorisation and condensed matrices: each semismooth step is one dense `m x m`
    /// solve, the only sparse work the final solve for the field. The exact model is the
    /// regularised one with its friction rows replaced
    /// ([`capstan_elasticity::contact::ContactModel::into_exact_friction`]: the pointwise law
    /// is then not used), so there is one assembly. `newton_iterations` counts both stages.
    ///
    /// # Errors
    /// [`ContactError::Unsupported`] for unilateral contact or a law without a registered
    /// regularisation; the regularised solve's errors (no equilibrium, non-convergence); the
    /// semismooth Newton's ([`ContactError::NotConverged`] when its budget
    /// `solver.max_iterations` is spent).
    pub(super) fn solve_exact_condensed(
        &self,
        observer: &mut dyn Observer<f64>,
        choice: SolverChoice,
    ) -> Result<Solved, ProblemError> {
        let t0 = Instant::now();
        if self.body.contact.is_unilateral() {
            return Err(ContactError::Unsupported {
                field: "solver.nonlinear",
                message: "exact friction on the condensed solver keeps v^3 = 0; unilateral contact (`contact.kind = \"unilateral\"`) needs `full-newton`",
            }
            .into());
        }
        let unsupported = || ContactError::Unsupported {
            field: "friction.law",
            message: "the condensed semismooth Newton starts from the law's regularisation (`exact-coulomb` -> `coulomb`, `exact-orthotropic-coulomb` -> `orthotropic-coulomb`); use `solver.nonlinear = \"full-newton\"`",
        };
        let name = self
            .friction
            .law
            .strip_prefix("exact-")
            .filter(|name| capstan_friction::registry::is_registered(name))
            .ok_or_else(unsupported)?;
        let law = self.friction.nonsmooth()?.ok_or_else(unsupported)?;
        let regularised = Problem {
            friction: Friction::named(name, self.friction.settings.clone()),
            ..self.clone()
        };
        observer.iteration(&Progress::set_up(SetUpPhase::Assembly, 0, 1));
        let model = regularised.model()?;
        let rows = model.exact_rows(law)?;
        observer.iteration(&Progress::set_up(SetUpPhase::Assembly, 1, 1));
        let solver = BoundarySolver::new_observed(&model, self.solver.budgets, observer)?;
        let setup = t0.elapsed().as_secs_f64();
        let t1 = Instant::now();
        let started = solver.solve_exact_rows_started_observed(&rows, self.loads, observer)?;
        let limiting = solver
            .sliding_at(self.loads.tau0)?
            .map(|m| [m.lower_ratio, m.upper_ratio]);
        drop(solver);
        let exact = model.with_exact_rows(rows)?;
        let mut solution = started.face.into_solution(&exact)?;
        solution.stats.newton_iterations += started.start_iterations;
        solution.stats.continuation_steps = started.start_steps;
        let times = [setup, t1.elapsed().as_secs_f64()];
        Ok(Solved {
            model: SolvedModel::Body(exact),
            solution,
            limiting,
            grid_sequence: None,
            choice,
            times,
            coarser: None,
        })
    }
}
