//! The start of the exact-friction (semismooth) Newton: the same problem under the law's
//! regularisation, solved by the condensed solver.

use capstan_elasticity::contact::BoundarySolver;
use capstan_elasticity::solvers::Observer;
use capstan_geometry::Surface;

use super::builder::Problem;
use super::friction::Friction;

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
