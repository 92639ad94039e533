//! A [`Problem`] along a load path with memory: the states solved in order, each from the
//! previous one, friction on the slip increment ([`capstan_elasticity::contact::solve_path`]).

use std::time::Instant;

use capstan_elasticity::contact::{BoundarySolver, EndLoads, PathSolver, PathStep, solve_path};
use capstan_elasticity::solvers::{LinearBackend, Observer};
use capstan_geometry::Surface;

use super::builder::Problem;
use super::solve::{Model, ProblemError};
use super::solver::{SolveMethod, Solver, SolverChoice};

/// A solved load path.
#[derive(Debug)]
pub struct SolvedPath {
    /// The model of the path (without a slip reference: the body from rest).
    pub model: Model,
    /// The steps, in the order of the path.
    pub steps: Vec<PathStep>,
    /// The solver that ran every step, and why.
    pub choice: SolverChoice,
    /// Wall time of the set-up (assembly; the condensed solver's factorisation and
    /// condensation, done once for the whole path), seconds.
    pub setup_seconds: f64,
}

impl<S: Surface<f64> + Clone + Send + Sync + 'static> Problem<S> {
    /// Solves the load states `path` in order, the first from rest and each later one from
    /// the state before it, with friction on the slip increment of each step; every Newton
    /// iterate goes to `observer`. The problem's own [`Problem::loads`] are not used.
    ///
    /// The condensed solver runs the path when the problem's solver condenses (`newton`,
    /// `auto`) and the model allows it (bilateral contact, a regularised law): its
    /// factorisation and condensation serve every step. Otherwise the full-system Newton
    /// runs each step (exact friction, unilateral contact, `full-newton`, `jacobi-newton`),
    /// with no grid sequencing (a step starts from the previous state on the same grid).
    ///
    /// # Errors
    /// As [`Problem::solve_observed`]; [`capstan_elasticity::contact::ContactError::PathStep`]
    /// naming the step that failed; a matrix-free linear solver (`solver.linear =
    /// "matrix-free-mg"`) is refused.
    pub fn solve_path_observed(
        &self,
        path: &[EndLoads],
        observer: &mut dyn Observer<f64>,
    ) -> Result<SolvedPath, ProblemError> {
        let t0 = Instant::now();
        let (method, mut choice) = self.solver.resolved(&self.body);
        let condensable = !self.body.contact.is_unilateral() && !self.friction.is_nonsmooth();
        let model = self.model()?;
        let condensed = matches!(method, SolveMethod::Condensed | SolveMethod::Auto) && condensable;
        let steps = if condensed {
            let solver = BoundarySolver::new_observed(&model, self.solver.budgets, observer)?;
            let setup = t0.elapsed().as_secs_f64();
            let steps = solve_path(&model, PathSolver::Condensed(&solver), path, observer)?;
            drop(solver);
            (steps, setup)
        } else {
            let method = match method {
                SolveMethod::Condensed | SolveMethod::Auto => {
                    // the condensed solver refuses exact friction and unilateral contact
                    let linear = LinearBackend::LU;
                    choice.nonlinear = "full-newton";
                    choice.linear = linear.name();
                    choice.reason = "a load path with exact friction or unilateral contact: the full-system (semismooth) Newton, sparse LU".into();
                    SolveMethod::FullNewton(linear)
                }
                SolveMethod::FullNewton(linear) if linear == LinearBackend::MATRIX_FREE_MG => {
                    if !choice.auto {
                        return Err(capstan_elasticity::contact::ContactError::Unsupported {
                            field: "solver.linear",
                            message: "a load path needs the assembled bulk: `lu` or `multigrid` (the matrix-free Newton solves single load states)",
                        }
                        .into());
                    }
                    let linear = LinearBackend::LU;
                    choice.linear = linear.name();
                    choice.reason = "a load path: the full-system Newton on the assembled bulk, sparse LU (the matrix-free Newton solves single load states)".into();
                    SolveMethod::FullNewton(linear)
                }
                other => other,
            };
            let full = Solver {
                method,
                ..self.solver
            }
            .full_settings();
            let setup = t0.elapsed().as_secs_f64();
            let steps = solve_path(
                &model,
                PathSolver::FullSystem(Box::new(full)),
                path,
                observer,
            )?;
            (steps, setup)
        };
        Ok(SolvedPath {
            model,
            steps: steps.0,
            choice,
            setup_seconds: steps.1,
        })
    }
}
