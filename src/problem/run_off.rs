//! The lower end of a 3-D unilateral body's equilibrium range for `capstan threshold`: the
//! run-off from ratio 1 down to its fold `r_*` ([`Problem::threshold_lower_end`]).

use capstan_elasticity::contact::{
    BodyOperator, FullSystemSettings, FullSystemSolver, RunOffEnd, RunOffSettings,
    ThresholdSettings,
};
use capstan_elasticity::friction::AnyFrictionLaw;
use capstan_elasticity::solvers::SilentObserver;
use capstan_geometry::Surface;

use super::builder::Problem;
use super::solve::{Model, ProblemError};
use super::solver::{SolveMethod, Solver};

/// The lower end of a 3-D unilateral body's equilibrium range from ratio 1
/// ([`Problem::threshold_lower_end`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LowerEnd {
    /// `r_*`: the smallest ratio the path reached before it turned back (an equilibrium
    /// there); `None` when the path reached the smallest ratio searched without a fold.
    pub fold: Option<f64>,
    /// `[lower, upper]`: the largest ratio the path folded back before and the smallest it
    /// converged at (`lower <= r_* <= upper`); with no fold, the smallest ratio searched twice.
    pub bracket: [f64; 2],
    /// Ratio steps of the run-off down.
    pub solves: usize,
}

impl<S: Surface<f64> + Clone + Send + Sync + 'static> Problem<S> {
    /// The lower end of a 3-D unilateral body's equilibrium range: the run-off from ratio 1
    /// down towards `1 / settings.max_ratio` (`tau0 = 1`, the smallest ratio step
    /// `tolerance / 2`, as [`Problem::threshold`] climbs), with its fold `r_*` and bracket;
    /// `None` for every other body (its threshold is not a run-off). The far end pulled less
    /// than the near one: the body slides the other way and peels off until friction can no
    /// longer hold it below `r_*`.
    ///
    /// # Errors
    /// The model's; the solves' and the continuation's
    /// ([`ContinuationBudgetSpent`]); the last error of a continuation that stalls.
    ///
    /// [`ContinuationBudgetSpent`]: capstan_elasticity::contact::ContactError::ContinuationBudgetSpent
    pub fn threshold_lower_end(
        &self,
        settings: ThresholdSettings,
    ) -> Result<Option<LowerEnd>, ProblemError> {
        let solid = !matches!(
            self.body.dimension,
            capstan_elasticity::contact::Dimension::Plane
        );
        let Some(full) = self.unilateral_threshold_settings().filter(|_| solid) else {
            return Ok(None);
        };
        let model: Model = self.model()?;
        let solver: FullSystemSolver<'_, BodyOperator, AnyFrictionLaw> =
            FullSystemSolver::new(&model, full)?;
        let run_off = RunOffSettings {
            min_step: 0.5 * settings.tolerance,
            ..self.run_off_settings()
        };
        let bottom = 1.0 / settings.max_ratio;
        let run = solver.run_off(1.0, 1.0, bottom, run_off, &mut SilentObserver, &mut |_| {})?;
        let (solves, bracket) = (run.ratio_steps + 1, run.bracket());
        match (run.end, bracket) {
            (RunOffEnd::Folded { fold, .. }, Some(bracket)) => Ok(Some(LowerEnd {
                fold: Some(fold),
                bracket,
                solves,
            })),
            (RunOffEnd::Stalled { error, .. }, _) => Err(error.into()),
            _ => Ok(Some(LowerEnd {
                fold: None,
                bracket: [bottom, bottom],
                solves,
            })),
        }
    }

    /// The full-system settings of the threshold of a body under unilateral contact on the
    /// full-system route (Newton or Jacobi-Newton after `auto`), `None` for every other body
    /// (the condensed solver's bisection): the scene's, and on a 3-D body sparse LU where the
    /// method's backend is iterative ([`Problem::run_off_lu_settings`]: the run-off's bordered
    /// solves sit next to the fold's singular Jacobian).
    pub(crate) fn unilateral_threshold_settings(&self) -> Option<FullSystemSettings> {
        let (method, _) = self.solver.resolved(&self.body);
        if !(self.body.contact.is_unilateral()
            && matches!(
                method,
                SolveMethod::FullNewton(_) | SolveMethod::JacobiNewton
            ))
        {
            return None;
        }
        let lu = match self.body.dimension {
            capstan_elasticity::contact::Dimension::Plane => None,
            _ => self.run_off_lu_settings(method),
        };
        Some(lu.unwrap_or_else(|| {
            Solver {
                method,
                ..self.solver
            }
            .full_settings()
        }))
    }
}
