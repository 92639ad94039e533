//! Exact friction on the condensed face from its own regularised start: a loosely converged
//! regularised Newton, then the semismooth Newton, with no field solve in between.

use capstan_friction::FrictionLaw;
use capstan_solvers::Observer;

use super::BoundarySolver;
use super::semismooth::ExactFaceSolution;
use crate::contact::error::ContactError;
use crate::contact::loads::EndLoads;
use crate::contact::model::ExactRows;
use crate::contact::operator::ContactOperator;

/// Relative residual `max |G| / scale` at which the regularised plain Newton hands over to the
/// semismooth Newton in [`BoundarySolver::solve_exact_rows_started_observed`].
pub const EXACT_START_TOLERANCE: f64 = 1e-3;

/// [`EXACT_START_TOLERANCE`] for a body with a rigid sliding mode (the circle), whose
/// semismooth Newton starts at the balanced rigid amplitude: a looser hand-over.
///
/// On the paper's default scene the regularised plain Newton reaches 3.9e-2 after 8
/// iterations; from there the semismooth Newton at the balanced amplitude takes the same 2
/// full steps as from the residual 3.6e-5 after 9 (10 iterations in all, as many as the
/// regularised `eps = 1e-5` solve). Without a rigid mode (the ellipse 2 x 1.5, 61 x 13) the
/// looser hand-over cost 6 semismooth steps instead of 2, so it keeps [`EXACT_START_TOLERANCE`].
pub const EXACT_START_TOLERANCE_SLIDING: f64 = 1e-1;

/// [`BoundarySolver::solve_exact_rows_started_observed`]'s answer: the semismooth solution and
/// the work of its regularised start.
#[derive(Debug, Clone)]
pub struct StartedExactFace {
    /// The semismooth Newton's solution (its `iterations` are the semismooth steps only).
    pub face: ExactFaceSolution,
    /// Newton iterations of the regularised start (both attempts when the loose start did
    /// not do).
    pub start_iterations: usize,
    /// Continuation steps of the regularised start (1 without a continuation).
    pub start_steps: usize,
}

impl<D: ContactOperator, L: FrictionLaw<f64>> BoundarySolver<'_, D, L> {
    /// Exact friction `rows` ([`crate::contact::ContactModel::exact_rows`] of this solver's
    /// model, the law's regularisation) from this solver's own regularised solution, stopped
    /// early: the condensed Newton of [`BoundarySolver::solve_observed`] from the stuck state
    /// down to a relative residual [`EXACT_START_TOLERANCE`] only
    /// ([`EXACT_START_TOLERANCE_SLIDING`] with a rigid sliding mode, where the semismooth
    /// Newton starts at the balanced amplitude) (its slip homotopy and load
    /// continuation, when plain Newton fails, to `settings.tolerance` as always), no field
    /// solve, then [`BoundarySolver::solve_exact_rows_observed`] from its unknowns.
    ///
    /// # Math
    /// The regularised solution `s_eps` is itself only `O(eps)` from the exact one `s*`
    /// (max `|v2|` 2e-6 apart at `eps = 1e-5` on the paper's default scene, where the exact
    /// residual at `s_eps` is 3.5e-2 relative): converging the regularised residual below that
    /// distance does not bring the start nearer to `s*`, it only polishes what the semismooth
    /// steps redo. The answer is the semismooth Newton's, converged to `settings.tolerance` on
    /// the exact rows, from either start. Should the semismooth Newton fail from the loose
    /// start ([`ContactError::NotConverged`]), the regularised Newton continues from it to
    /// `settings.tolerance` and the semismooth Newton runs again from there (the route of
    /// [`BoundarySolver::solve_exact_rows_observed`] from [`BoundarySolver::solve_observed`]).
    ///
    /// # Errors
    /// The regularised solve's ([`ContactError::NoEquilibrium`], [`ContactError::NotConverged`])
    /// and those of [`BoundarySolver::solve_exact_rows_observed`].
    pub fn solve_exact_rows_started_observed(
        &self,
        rows: &ExactRows,
        loads: EndLoads,
        observer: &mut dyn Observer<f64>,
    ) -> Result<StartedExactFace, ContactError> {
        let loose = if self.rigid_mode.is_empty() {
            EXACT_START_TOLERANCE
        } else {
            EXACT_START_TOLERANCE_SLIDING
        };
        let tolerance = self.settings.tolerance.max(loose);
        let (start, iterations, steps) = self.unknowns_from(loads, None, tolerance, observer)?;
        match self.solve_exact_rows_observed(rows, loads, &start, observer) {
            Ok(face) => Ok(StartedExactFace {
                face,
                start_iterations: iterations,
                start_steps: steps,
            }),
            Err(ContactError::NotConverged { .. }) if tolerance > self.settings.tolerance => {
                let (start, more, steps) =
                    self.unknowns_from(loads, Some(&start), self.settings.tolerance, observer)?;
                let face = self.solve_exact_rows_observed(rows, loads, &start, observer)?;
                Ok(StartedExactFace {
                    face,
                    start_iterations: iterations + more,
                    start_steps: steps,
                })
            }
            Err(e) => Err(e),
        }
    }
}
