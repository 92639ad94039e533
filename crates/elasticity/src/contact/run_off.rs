//! The run-off of a body under a growing tension ratio: the equilibrium followed from a low
//! ratio up to the one asked for by pseudo-arclength continuation
//! ([`FullSystemSolver::continue_ratio`]), in ratio steps halved on a failure, until the path
//! reaches the ratio asked for or folds back before it (no equilibrium beyond the fold `r*`,
//! bracketed). From ratio 1 the run-off climbs to a ratio above 1 and goes down to one below
//! (the far end pulled less than the near one, or pushed): a fold there, `r_*`, bounds the
//! equilibria from below. The driver of `examples/solid_runoff.rs`, of `capstan contact` when the plain
//! Newton fails on a 3-D body, and of `capstan threshold` on a 3-D unilateral body.

use capstan_friction::FrictionLaw;
use capstan_solvers::Observer;

use crate::contact::error::ContactError;
use crate::contact::full_system::FullSystemSolver;
use crate::contact::loads::EndLoads;
use crate::contact::operator::ContactOperator;
use crate::contact::ratio_arclength::ArclengthBudget;
use crate::contact::solution::ContactSolution;
use crate::error::ElasticityError;

/// Settings of [`FullSystemSolver::run_off`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunOffSettings {
    /// The first ratio step (and the largest): default `0.05`.
    pub first_step: f64,
    /// The step is halved after a failed one until it is below this (then the bracket
    /// `[lower, upper]` of the stop is at most `2 min_step` wide): default `1e-3`.
    pub min_step: f64,
    /// The work budget: arclength steps (converged or not) over every continuation of the
    /// run-off, default 400 (`solver.max_continuation_steps` in scenes).
    pub max_arclength_steps: usize,
}

impl Default for RunOffSettings {
    fn default() -> Self {
        Self {
            first_step: 0.05,
            min_step: 1e-3,
            max_arclength_steps: 400,
        }
    }
}

impl RunOffSettings {
    /// Checks the steps: `0 < min_step <= first_step`, finite.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming the step.
    pub fn validate(&self) -> Result<(), ElasticityError> {
        if !(self.first_step.is_finite() && self.first_step > 0.0) {
            return Err(ElasticityError::InvalidParameter {
                field: "first_step",
                value: self.first_step,
                allowed: "finite and > 0",
            });
        }
        if !(self.min_step > 0.0 && self.min_step <= self.first_step) {
            return Err(ElasticityError::InvalidParameter {
                field: "min_step",
                value: self.min_step,
                allowed: "in (0, first_step]",
            });
        }
        Ok(())
    }
}

/// How a run-off ended ([`RunOff::end`]).
#[derive(Debug)]
pub enum RunOffEnd {
    /// The path reached the ratio asked for ([`RunOff::last`] is the equilibrium there).
    Reached,
    /// The equilibrium path folds back before the ratio asked for: no equilibrium beyond
    /// `fold` on the path (above it when the run-off climbs, below it when it goes down),
    /// which lies between [`RunOff::reached`] and `beyond` ([`RunOff::bracket`]).
    Folded {
        /// `r*` (or `r_*` going down): the ratio furthest from the start that the path reached
        /// (an equilibrium there), at or beyond [`RunOff::reached`].
        fold: f64,
        /// The ratio nearest the start that the path folded back before (above
        /// [`RunOff::reached`] when climbing, below it going down).
        beyond: f64,
    },
    /// The continuation failed before `beyond` for another reason than a fold (steps too
    /// small, a singular corrector): `error` is the last such failure.
    Stalled {
        /// The ratio nearest the start that the continuation failed to reach.
        beyond: f64,
        /// Why the last step failed.
        error: ContactError,
    },
}

/// The result of [`FullSystemSolver::run_off`].
#[derive(Debug)]
pub struct RunOff {
    /// How it ended.
    pub end: RunOffEnd,
    /// The tension ratio asked for.
    pub target: f64,
    /// The converged ratio nearest the target (the target when [`RunOffEnd::Reached`]): the
    /// largest converged ratio when the run-off climbs, the smallest when it goes down.
    pub reached: f64,
    /// The equilibrium at `reached`. Its statistics count the Newton iterations of every
    /// converged step of the run-off (the start's and each continuation's corrector and final
    /// Newton) and, as `continuation_steps`, its arclength steps.
    pub last: ContactSolution,
    /// Arclength steps taken in total (the budget's measure).
    pub arclength_steps: usize,
    /// Ratio steps tried (continuations, converged or not).
    pub ratio_steps: usize,
}

impl RunOff {
    /// The bracket of the stop, `[lower, upper]` in increasing order: the converged
    /// [`RunOff::reached`] and the first ratio not reached (`beyond`); `None` when the run-off
    /// reached its target.
    pub fn bracket(&self) -> Option<[f64; 2]> {
        match self.end {
            RunOffEnd::Reached => None,
            RunOffEnd::Folded { beyond, .. } | RunOffEnd::Stalled { beyond, .. } => {
                Some([self.reached.min(beyond), self.reached.max(beyond)])
            }
        }
    }

    /// The run-off as a solve at [`RunOff::target`]: the equilibrium if reached;
    /// [`ContactError::NoEquilibriumBeyond`] if the path folded on its way up,
    /// [`ContactError::NoEquilibriumBelow`] on its way down; else `stalled` (the error of the
    /// solve the run-off was to replace).
    ///
    /// # Errors
    /// As above.
    pub fn into_solution(self, stalled: ContactError) -> Result<ContactSolution, ContactError> {
        match self.end {
            RunOffEnd::Reached => Ok(self.last),
            RunOffEnd::Folded { fold, beyond } if beyond < self.reached => {
                Err(ContactError::NoEquilibriumBelow {
                    ratio: self.target,
                    fold,
                    lower: beyond,
                    upper: self.reached,
                })
            }
            RunOffEnd::Folded { fold, beyond } => Err(ContactError::NoEquilibriumBeyond {
                ratio: self.target,
                fold,
                lower: self.reached,
                upper: beyond,
            }),
            RunOffEnd::Stalled { .. } => Err(stalled),
        }
    }
}

/// One ratio step of a run-off as [`FullSystemSolver::run_off`] reports it to its trace:
/// the ratio tried and the continuation's answer.
pub type RunOffTrial<'a> = (f64, Result<&'a ContactSolution, &'a ContactError>);

impl<D: ContactOperator, L: FrictionLaw<f64>> FullSystemSolver<'_, D, L> {
    /// Follows the equilibrium from the ratio `from` (solved here from the stuck start) to
    /// `to` with `tau0` held, up (`to > from`) or down (`to < from`: the far end pulled less,
    /// or pushed): each ratio `r + d step` (`d = sign(to - from)`) continued from the last
    /// converged one `r` by [`FullSystemSolver::continue_ratio`], `step` from
    /// `settings.first_step`, halved after a failed step (whether the path folded back or the
    /// continuation failed otherwise) until it falls below `settings.min_step`. The start and
    /// every ratio step are reported to `trace`; `observer` hears the start's solve and may
    /// stop the run-off between steps.
    ///
    /// # Math
    /// ```text
    /// r_0 = from,   d = sign(to - from),   trial = r + d step  (not past `to`)
    /// trial reached:        r = trial                          (the next step from there)
    /// trial not reached:    beyond = the one of (beyond, trial) nearer `from`,  step = step / 2
    /// stop: r = to (reached), or step < min_step:
    ///   folded  when the path folded back before `beyond`, at its ratio r* furthest along d
    ///           (an equilibrium), so r* lies between r and beyond: no equilibrium beyond r*
    ///           on the path (above it for d = +1, below it for d = -1)
    ///   stalled otherwise
    /// ```
    /// A later step that converges at or past `beyond` (from a start further along) clears it:
    /// the path has small local folds where its contact set changes, and a fold seen from one
    /// start may be passed from the next.
    ///
    /// # Errors
    /// Invalid settings or loads (`to = from`, or not finite); the solve at `from`;
    /// [`ContactError::ContinuationBudgetSpent`] when the arclength steps run out;
    /// [`ContactError::Interrupted`] when `observer` stops it.
    pub fn run_off(
        &self,
        tau0: f64,
        from: f64,
        to: f64,
        settings: RunOffSettings,
        observer: &mut dyn Observer<f64>,
        trace: &mut dyn FnMut(RunOffTrial<'_>),
    ) -> Result<RunOff, ContactError> {
        settings.validate()?;
        EndLoads::new(tau0, tau0 * to).check()?;
        EndLoads::new(tau0, tau0 * from).check()?;
        if to == from {
            return Err(ElasticityError::InvalidParameter {
                field: "to",
                value: to,
                allowed: "a ratio other than the start ratio `from`",
            }
            .into());
        }
        // d = +1 climbing, -1 going down; `further(a, b)`: a lies past b along d
        let d = if to > from { 1.0 } else { -1.0 };
        let further = |a: f64, b: f64| d * a > d * b;
        let mut last = self.solve_observed(EndLoads::new(tau0, tau0 * from), observer)?;
        trace((from, Ok(&last)));
        let mut budget = ArclengthBudget {
            spent: 0,
            max: settings.max_arclength_steps,
        };
        let mut iterations = last.stats.newton_iterations;
        let (mut ratio, mut step) = (from, settings.first_step);
        // the ratio nearest `from` not reached, and the fold seen there (the ratio furthest
        // along d on the path before it turned back)
        let (mut failed, mut fold): (f64, Option<f64>) = (d * f64::INFINITY, None);
        let mut error = None;
        let mut ratio_steps = 0;
        while step >= settings.min_step {
            if observer.interrupted() {
                return Err(ContactError::Interrupted { iterations });
            }
            let trial = if further(ratio + d * step, to) {
                to
            } else {
                ratio + d * step
            };
            ratio_steps += 1;
            let result =
                self.continue_ratio_counted(tau0, ratio, &last.displacement, trial, &mut budget);
            trace((trial, result.as_ref()));
            match result {
                Ok(solution) => {
                    ratio = trial;
                    iterations += solution.stats.newton_iterations;
                    last = solution;
                    if !further(failed, ratio) {
                        // an earlier step from another start failed here: not the stop
                        (failed, fold) = (d * f64::INFINITY, None);
                    }
                    if ratio == to {
                        return Ok(self.finish(
                            RunOffEnd::Reached,
                            to,
                            ratio,
                            last,
                            iterations,
                            budget,
                            ratio_steps,
                        ));
                    }
                }
                Err(ContactError::ContinuationBudgetSpent { steps, .. }) => {
                    return Err(ContactError::ContinuationBudgetSpent {
                        steps,
                        reached: ratio,
                        ratio: to,
                    });
                }
                Err(e @ (ContactError::Interrupted { .. } | ContactError::Elasticity(_))) => {
                    return Err(e);
                }
                Err(e) => {
                    // the path's end along d: `upper` climbing, `lower` going down
                    let folded = match e {
                        ContactError::NoEquilibrium { lower, upper, .. } => {
                            Some(if d > 0.0 { upper } else { lower })
                        }
                        _ => None,
                    };
                    if further(failed, trial) {
                        (failed, fold) = (trial, folded);
                    } else if trial == failed {
                        fold = match (fold, folded) {
                            (Some(a), Some(b)) => Some(if further(b, a) { b } else { a }),
                            (a, b) => a.or(b),
                        };
                    }
                    error = Some(e);
                    step /= 2.0;
                }
            }
        }
        let end = match (fold, error) {
            (Some(fold), _) => RunOffEnd::Folded {
                fold: if further(ratio, fold) { ratio } else { fold },
                beyond: failed,
            },
            (None, Some(error)) => RunOffEnd::Stalled {
                beyond: failed,
                error,
            },
            // not met: the step falls below `min_step` only after a failed continuation
            (None, None) => RunOffEnd::Stalled {
                beyond: failed,
                error: ContactError::NotConverged {
                    iterations,
                    residual: f64::NAN,
                    load_factor: (ratio - from) / (to - from),
                },
            },
        };
        Ok(self.finish(end, to, ratio, last, iterations, budget, ratio_steps))
    }

    /// The run-off's result with the work of every converged step in `last`'s statistics.
    #[allow(clippy::too_many_arguments)]
    fn finish(
        &self,
        end: RunOffEnd,
        target: f64,
        reached: f64,
        mut last: ContactSolution,
        iterations: usize,
        budget: ArclengthBudget,
        ratio_steps: usize,
    ) -> RunOff {
        last.stats.newton_iterations = iterations;
        last.stats.continuation_steps = budget.spent;
        RunOff {
            end,
            target,
            reached,
            last,
            arclength_steps: budget.spent,
            ratio_steps,
        }
    }
}
