//! Solving a [`Problem`]: one path for 2-D and 3-D bodies.

use std::time::Instant;

use capstan_elasticity::PlaneOperator;
use capstan_elasticity::contact::{
    BodyOperator, BoundarySolver, ContactError, ContactErrorKind, ContactModel, ContactOperator,
    ContactSettings, ContactSolution, FullSystemSolver, LimitingRange, RunOffEnd, RunOffSettings,
    SEQUENCE_COARSEST_UNKNOWNS, ThresholdResult, ThresholdSettings, solve_sequenced,
    threshold_ratio,
};
use capstan_elasticity::friction::AnyFrictionLaw;
use capstan_elasticity::solid::{SolidMultigridParams, SolidOutput};
use capstan_elasticity::solvers::{LinearBackend, Observer, Progress, SetUpPhase, SilentObserver};
use capstan_elasticity::{Discretisation, ElasticityError};
use capstan_friction::FrictionError;
use capstan_geometry::Surface;

use capstan_elasticity::contact::Dimension;

use super::builder::Problem;
use super::plain_attempts::{PlainAttempts, run_off_may_explain};
use super::solver::{SolveMethod, Solver, SolverChoice};

/// The contact model of a [`Problem`] (either dimension, any registered friction law).
pub type Model = ContactModel<BodyOperator, AnyFrictionLaw>;

/// What a [`Problem`] failed with: its friction law, its body, or the contact solve (no
/// equilibrium, non-convergence within the budgets, an observer's stop).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ProblemError {
    /// The friction law: unknown name or bad parameters.
    #[error(transparent)]
    Friction(#[from] FrictionError),
    /// The body: bad material, grid, discretisation or geometry.
    #[error(transparent)]
    Elasticity(#[from] ElasticityError),
    /// The contact solve.
    #[error(transparent)]
    Contact(#[from] ContactError),
    /// `solver.nonlinear` names no registered nonlinear method.
    #[error(
        "`solver.nonlinear` = `{name}` is not a registered nonlinear method; registered: {known}"
    )]
    UnknownNonlinearMethod {
        /// The name asked for.
        name: String,
        /// The registered names, comma-separated.
        known: String,
    },
    /// A nonlinear method registered under a name (or alias) that is taken.
    #[error("a nonlinear method named `{name}` is registered already")]
    DuplicateNonlinearMethod {
        /// The name.
        name: &'static str,
    },
    /// An accuracy target's work budget ran out before every estimate met the tolerance.
    #[error(
        "accuracy target {tolerance:e} not reached: `{quantity}` still has a relative estimate of {estimate:.2e} ({trend}), and the next refinement has {unknowns} unknowns, over the budget `accuracy.max_unknowns` = {max_unknowns}; raise it or loosen `accuracy.tol`"
    )]
    AccuracyNotReached {
        /// The tolerance asked for.
        tolerance: f64,
        /// The quantity with the largest relative estimate on the last step.
        quantity: String,
        /// Its relative estimate.
        estimate: f64,
        /// Its relative differences `d_k / scale` along the ladder and whether they fall
        /// (converging, too slowly for the budget) or not (not converging on this ladder).
        trend: String,
        /// Unknowns of the step that would come next.
        unknowns: usize,
        /// The budget.
        max_unknowns: usize,
    },
}

/// The model a solve ended on: the problem's own ([`Problem::model`]), or, after grid
/// sequencing on the plane-strain body, the finest level's.
#[derive(Debug)]
pub enum SolvedModel {
    /// [`Problem::model`].
    Body(Model),
    /// The finest level of the full-system Newton's grid sequence (plane strain).
    Sequenced(ContactModel<PlaneOperator, AnyFrictionLaw>),
}

impl SolvedModel {
    /// The operator, whichever model it is.
    pub fn operator(&self) -> &dyn ContactOperator {
        match self {
            Self::Body(m) => m.discretisation(),
            Self::Sequenced(m) => m.discretisation(),
        }
    }

    /// The plane-strain discretisation (grid, numbering, nodal fields), `None` in 3-D.
    pub fn plane(&self) -> Option<&dyn Discretisation> {
        self.operator().plane()
    }

    /// The plane-strain mesh discretisation (`fem-qp-corner`: nodes, cells), `None` on a grid.
    pub fn mesh(&self) -> Option<&dyn capstan_elasticity::mesh_discretisation::MeshDiscretisation> {
        self.operator().mesh()
    }

    /// The 3-D body's box grid and nodal fields, `None` in plane strain.
    pub fn solid(&self) -> Option<&dyn SolidOutput> {
        self.operator().solid()
    }

    /// The short name of the discretisation (`fd`, `fem-q2`, `solid-q1`, ...).
    pub fn method(&self) -> &'static str {
        self.operator().method()
    }

    /// The number of contact unknowns (tangential entries on the contact face).
    pub fn contact_unknowns(&self) -> usize {
        match self {
            Self::Body(m) => m.active().len(),
            Self::Sequenced(m) => m.active().len(),
        }
    }
}

/// A solved [`Problem`].
#[derive(Debug)]
pub struct Solved {
    /// The model the solution belongs to.
    pub model: SolvedModel,
    /// The solution: displacement, contact profile, stick/slip, statistics.
    pub solution: ContactSolution,
    /// `[lower, upper]` tension ratios friction can hold, when the body can slide rigidly and
    /// the condensed solver ran (an entry is infinite when friction holds every ratio that
    /// way); `None` otherwise.
    pub limiting: Option<[f64; 2]>,
    /// Full-system Newton on the plane-strain body: `[n2, n3, newton iterations]` of each
    /// grid-sequencing level, coarsest first; `None` otherwise.
    pub grid_sequence: Option<Vec<[usize; 3]>>,
    /// The method that ran (what `auto` chose, or the one named).
    pub choice: SolverChoice,
    /// Wall times `[set-up, solve]` in seconds (set-up: assembly, factorisation and
    /// condensation of the condensed solver; for the full-system solvers only the body's
    /// description, their assembly being part of the solve).
    pub times: [f64; 2],
    /// After grid sequencing: the level before the finest, on [`Problem::coarser`]'s grid
    /// (the same problem one level coarser, solved on the way), which error estimates use
    /// instead of a solve of their own; `None` otherwise.
    pub coarser: Option<Box<Solved>>,
}

impl Solved {
    /// A body's solution with nothing more: no limiting ratios, no grid sequence, no coarser
    /// level.
    fn of_body(
        model: SolvedModel,
        solution: ContactSolution,
        choice: SolverChoice,
        times: [f64; 2],
    ) -> Self {
        Self {
            model,
            solution,
            limiting: None,
            grid_sequence: None,
            choice,
            times,
            coarser: None,
        }
    }
}

impl<S: Surface<f64> + Clone + Send + Sync + 'static> Problem<S> {
    /// The contact model: the body's operator of either dimension with the friction law.
    ///
    /// # Errors
    /// The friction law's and the body's errors.
    ///
    /// A nonsmooth law ([`super::Friction::nonsmooth`]: `exact-coulomb`, ...) gives the body
    /// without friction whose friction rows are then the law's projection rows
    /// ([`ContactModel::into_exact_friction`]; `friction.eps` is only the slip threshold of
    /// the reports and of the regularised start).
    pub fn model(&self) -> Result<Model, ProblemError> {
        if let Some(exact) = self.friction.nonsmooth()? {
            let frictionless =
                super::Friction::named("frictionless", self.friction.settings.clone());
            let (law, params, eps) = frictionless.build()?;
            return Ok(self
                .body
                .model(law, params, eps)?
                .into_exact_friction(exact)?);
        }
        let (law, params, eps) = self.friction.build()?;
        Ok(self.body.model(law, params, eps)?)
    }

    /// [`Problem::model`], reported to `observer` as the set-up phase
    /// [`SetUpPhase::Assembly`] (an event when it starts and one when it ends).
    fn model_observed(&self, observer: &mut dyn Observer<f64>) -> Result<Model, ProblemError> {
        observer.iteration(&Progress::set_up(SetUpPhase::Assembly, 0, 1));
        let model = self.model()?;
        observer.iteration(&Progress::set_up(SetUpPhase::Assembly, 1, 1));
        Ok(model)
    }

    /// Solves the problem ([`Problem::solve_observed`] with no observer).
    ///
    /// # Errors
    /// See [`Problem::solve_observed`].
    pub fn solve(&self) -> Result<Solved, ProblemError> {
        self.solve_observed(&mut SilentObserver)
    }

    /// Whether the body's discretisation is on a mesh rather than the grid's nodes
    /// (`fem-qp-corner`): no grid sequencing (its transfers interpolate on grid nodes).
    fn body_is_mesh(&self) -> bool {
        self.body.scheme().is_ok_and(|s| s.is_mesh())
    }

    /// Whether [`Problem::solve_observed`] solves the problem one grid level coarser on the way
    /// (grid sequencing of the plane full-system Newton with sparse backends and smooth
    /// friction, bilateral contact), so that [`Solved::coarser`] comes for free.
    pub fn sequences_grids(&self) -> bool {
        let plane = matches!(self.body.dimension, Dimension::Plane);
        let exact = self.friction.is_nonsmooth();
        let (method, _) = self.solver.resolved(&self.body);
        plane
            && !self.body.contact.is_unilateral()
            && !exact
            && !self.body_is_mesh()
            && matches!(method, SolveMethod::FullNewton(l) if l != LinearBackend::MATRIX_FREE_MG)
    }

    /// Solves the problem with its solver, reporting every iteration to `observer` (which may
    /// stop the solve).
    ///
    /// # Errors
    /// Bad input ([`ProblemError::Friction`], [`ProblemError::Elasticity`], or
    /// [`ContactError`] of kind `InvalidInput`); [`ContactError::NoEquilibrium`] when the loads
    /// are beyond what friction holds (the full-system solvers' non-convergence is checked
    /// against the condensed solver's limiting ratios and reported so); non-convergence within
    /// the budgets; [`ContactError::Interrupted`] when `observer` stops the solve.
    pub fn solve_observed(&self, observer: &mut dyn Observer<f64>) -> Result<Solved, ProblemError> {
        let t0 = Instant::now();
        let loads = self.loads;
        let plane = matches!(self.body.dimension, Dimension::Plane);
        // grid sequencing starts from the condensed solver, which keeps v^3 = 0 and knows no
        // exact friction
        let exact = self.friction.is_nonsmooth();
        let sequenced =
            plane && !self.body.contact.is_unilateral() && !exact && !self.body_is_mesh();
        let (mut method, mut choice) = self.solver.resolved(&self.body);
        if exact && method == SolveMethod::Condensed && !self.body.contact.is_unilateral() {
            // exact friction on the condensed solver: its regularisation, then semismooth
            // Newton on the contact face (exact_start.rs)
            let condensed = SolverChoice {
                reason: format!(
                    "exact friction (`{}`): its regularisation on the condensed solver, then semismooth Newton on the condensed contact face",
                    self.friction.law
                ),
                ..choice.clone()
            };
            match self.solve_exact_condensed(observer, condensed) {
                Ok(solved) => return Ok(solved),
                Err(e @ ProblemError::Contact(ContactError::Interrupted { .. })) => return Err(e),
                Err(e) if !choice.auto => return Err(e),
                // auto: the full-system semismooth Newton below
                Err(_) => {}
            }
        }
        if exact && method == SolveMethod::Condensed && choice.auto {
            // the condensed route failed (or the contact is unilateral): auto takes the full
            // system
            let linear = capstan_elasticity::solvers::LinearBackend::LU;
            method = SolveMethod::FullNewton(linear);
            choice.nonlinear = "full-newton";
            choice.linear = linear.name();
            choice.reason = format!(
                "exact friction (`{}`): the full-system semismooth Newton, sparse LU",
                self.friction.law
            );
        }
        // the full-system settings of the method that runs
        let full = Solver {
            method,
            ..self.solver
        }
        .full_settings();
        match method {
            SolveMethod::Condensed | SolveMethod::Auto => {
                let model = self.model_observed(observer)?;
                let solver = BoundarySolver::new_observed(&model, self.solver.budgets, observer)?;
                let setup = t0.elapsed().as_secs_f64();
                let t1 = Instant::now();
                let solution = solver.solve_observed(loads, observer)?;
                let limiting = solver
                    .sliding_at(solution.loads.tau0)?
                    .map(|m| [m.lower_ratio, m.upper_ratio]);
                let times = [setup, t1.elapsed().as_secs_f64()];
                drop(solver);
                Ok(Solved {
                    model: SolvedModel::Body(model),
                    solution,
                    limiting,
                    grid_sequence: None,
                    choice,
                    times,
                    coarser: None,
                })
            }
            SolveMethod::FullNewton(linear) if linear == LinearBackend::MATRIX_FREE_MG => {
                // grid sequencing: the body on its V-cycle's coarse grids first, each
                // solution prolonged as the next grid's start; the models of every level
                // are built inside the solve
                let (law, params, eps) = self.friction.build()?;
                let setup = t0.elapsed().as_secs_f64();
                let t1 = Instant::now();
                let seq = self.body.solve_matrix_free_sequenced(
                    law,
                    params,
                    eps,
                    SolidMultigridParams::default(),
                    self.solver.matrix_free_settings(),
                    SEQUENCE_COARSEST_UNKNOWNS,
                    loads,
                    observer,
                )?;
                let times = [setup, t1.elapsed().as_secs_f64()];
                Ok(Solved::of_body(
                    SolvedModel::Body(seq.model),
                    seq.solution,
                    choice,
                    times,
                ))
            }
            SolveMethod::FullNewton(_) if sequenced => {
                // Grid sequencing: the model is assembled level by level inside.
                let (law, params, eps) = self.friction.build()?;
                let body = self.body.plane();
                let setup = t0.elapsed().as_secs_f64();
                let t1 = Instant::now();
                match solve_sequenced(&body, law, params, eps, loads, full, observer) {
                    Ok(seq) => {
                        let coarser = seq.coarser.map(|(model, solution)| {
                            Box::new(Solved::of_body(
                                SolvedModel::Sequenced(model),
                                solution,
                                choice.clone(),
                                [0.0, 0.0],
                            ))
                        });
                        Ok(Solved {
                            grid_sequence: Some(
                                seq.levels.iter().map(|&(a, b, c)| [a, b, c]).collect(),
                            ),
                            model: SolvedModel::Sequenced(seq.model),
                            solution: seq.solution,
                            limiting: None,
                            choice,
                            times: [setup, t1.elapsed().as_secs_f64()],
                            coarser,
                        })
                    }
                    Err(e) if e.kind() == ContactErrorKind::NotConverged => {
                        Err(self.explain_not_converged(&self.model()?, e))
                    }
                    Err(e) => Err(e.into()),
                }
            }
            SolveMethod::FullNewton(_) | SolveMethod::JacobiNewton => {
                let model = self.model_observed(observer)?;
                let solver = FullSystemSolver::new(&model, full)?;
                let setup = t0.elapsed().as_secs_f64();
                let t1 = Instant::now();
                // exact friction starts from its regularisation's solution (exact_start.rs)
                let start = if exact {
                    self.regularised_start(observer)
                } else {
                    None
                };
                let solved = match &start {
                    Some(s) => solver
                        .solve_from_observed(loads, &s.displacement, observer)
                        .map(|mut solution| {
                            solution.stats.newton_iterations += s.iterations;
                            solution
                        }),
                    // a run-off follows a failure: the load continuation stops once it is
                    // futile (plain_attempts.rs, PLAIN_ATTEMPTS)
                    None if !plane && self.watches_plain_solve() => {
                        let mut watch = PlainAttempts::new(observer);
                        let solved = solver.solve_observed(loads, &mut watch);
                        match solved {
                            Err(_) if watch.stopped => Err(watch.failure()),
                            solved => solved,
                        }
                    }
                    None => solver.solve_observed(loads, observer),
                };
                // a 3-D body's Newton failed: the continuation in the ratio tells a fold of
                // the equilibrium path (no equilibrium) from a solver failure
                let solved = match solved {
                    Err(e) if !plane && run_off_may_explain(&e) => {
                        self.run_off(&model, &solver, method, e, observer)
                    }
                    solved => solved,
                };
                // a plane body under unilateral contact failed: a ratio outside its limiting
                // range (the full-slip balance along the rigid sliding mode) has no equilibrium
                let solved = match solved {
                    Err(e) if plane && e.kind() == ContactErrorKind::NotConverged => {
                        Err(self.outside_unilateral_range(&solver).unwrap_or(e))
                    }
                    solved => solved,
                };
                let times = [setup, t1.elapsed().as_secs_f64()];
                drop(solver);
                match solved {
                    Ok(solution) => Ok(Solved::of_body(
                        SolvedModel::Body(model),
                        solution,
                        choice,
                        times,
                    )),
                    Err(e) if plane && e.kind() == ContactErrorKind::NotConverged => {
                        Err(self.explain_not_converged(&model, e))
                    }
                    Err(e) => Err(e.into()),
                }
            }
        }
    }

    /// The tension ratio `tau_max / tau0` at which the whole contact surface slides (bisection
    /// on the condensed solver, [`threshold_ratio`]).
    ///
    /// # Errors
    /// The model's errors; non-convergence of a solve within the budgets.
    pub fn threshold(&self) -> Result<ThresholdResult, ProblemError> {
        self.threshold_with(ThresholdSettings::default())
    }

    /// [`Problem::threshold`] with the bisection's `settings` (its tolerance).
    ///
    /// # Errors
    /// See [`Problem::threshold`].
    pub fn threshold_with(
        &self,
        settings: ThresholdSettings,
    ) -> Result<ThresholdResult, ProblemError> {
        let model = self.model()?;
        if let Some(full) = self.unilateral_threshold_settings() {
            let solver = FullSystemSolver::new(&model, full)?;
            return Ok(match self.body.dimension {
                Dimension::Solid { .. } => self.threshold_run_off(&solver, settings)?,
                Dimension::Plane => threshold_at_limit(&solver)?,
            });
        }
        let solver = BoundarySolver::new(&model, self.solver.budgets)?;
        Ok(threshold_ratio(&solver, settings)?)
    }

    /// The threshold of a 3-D body under unilateral contact: the fold `r*` of its equilibrium
    /// path from ratio 1 ([`FullSystemSolver::run_off`] towards `settings.max_ratio`, `tau0 =
    /// 1`, the smallest ratio step `tolerance / 2`, so the bracket is at most `tolerance`
    /// wide): the result's `below` and `above` (= `ratio`) are the bracket, `fold` is `r*`.
    /// Under a growing ratio the body slides and peels off until friction on the shrinking
    /// contact can no longer hold the load along the sliding mode; past `r*` no equilibrium
    /// lies on the path (`above_is_no_equilibrium`).
    ///
    /// # Errors
    /// The solves' and the continuation's ([`ContactError::ContinuationBudgetSpent`]:
    /// `solver.max_continuation_steps` arclength steps); [`ContactError::NotConverged`] when
    /// the path reaches `settings.max_ratio` without a fold; the last error of a continuation
    /// that stalls.
    fn threshold_run_off(
        &self,
        solver: &FullSystemSolver<'_, BodyOperator, AnyFrictionLaw>,
        settings: ThresholdSettings,
    ) -> Result<ThresholdResult, ContactError> {
        let run_off = RunOffSettings {
            min_step: 0.5 * settings.tolerance,
            ..self.run_off_settings()
        };
        let run = solver.run_off(
            1.0,
            1.0,
            settings.max_ratio,
            run_off,
            &mut SilentObserver,
            &mut |_| {},
        )?;
        match run.end {
            RunOffEnd::Folded { fold, beyond } => Ok(ThresholdResult {
                ratio: beyond,
                below: run.reached,
                above: beyond,
                slip_fraction_below: run.last.slip_fraction,
                above_is_no_equilibrium: true,
                solves: run.ratio_steps + 1,
                limiting_ratio: None,
                fold: Some(fold),
            }),
            RunOffEnd::Reached => Err(ContactError::NotConverged {
                iterations: run.last.stats.newton_iterations,
                residual: f64::NAN,
                load_factor: 1.0,
            }),
            RunOffEnd::Stalled { error, .. } => Err(error),
        }
    }

    /// The run-off settings of the problem: the defaults with the budget
    /// `solver.max_continuation_steps` in arclength steps.
    pub(super) fn run_off_settings(&self) -> RunOffSettings {
        RunOffSettings {
            max_arclength_steps: self.solver.budgets.max_continuation_steps,
            ..Default::default()
        }
    }

    /// After the full-system Newton (`method`, with `solver` of `model`) failed (`failed`) at
    /// the problem's ratio `r != 1` (`tau0 > 0`): the equilibrium followed from ratio 1 up or
    /// down to `r` ([`FullSystemSolver::run_off`]) by `solver` when the plain solve did not
    /// converge: its solution at `r` when the path reaches it,
    /// [`ContactError::NoEquilibriumBeyond`] when the path folds back below `r > 1`,
    /// [`ContactError::NoEquilibriumBelow`] above `r < 1`. A unilateral body on another method
    /// than Newton with sparse LU, whose run-off stalled or whose plain solve spent its Krylov
    /// budget (next to a fold the Jacobian is near singular): the run-off on Newton with sparse
    /// LU, and only a fold it finds replaces `failed` (a spent budget of the scene stays the
    /// error otherwise). Else `failed`.
    ///
    /// # Errors
    /// As above; [`ContactError::ContinuationBudgetSpent`] (`solver.max_continuation_steps`
    /// arclength steps) of `solver`'s run-off; an interrupted solve.
    fn run_off(
        &self,
        model: &Model,
        solver: &FullSystemSolver<'_, BodyOperator, AnyFrictionLaw>,
        method: SolveMethod,
        failed: ContactError,
        observer: &mut dyn Observer<f64>,
    ) -> Result<ContactSolution, ContactError> {
        let (tau0, ratio) = (self.loads.tau0, self.loads.tension_ratio());
        if !self.runs_off() {
            return Err(failed);
        }
        let settings = self.run_off_settings();
        if failed.kind() == ContactErrorKind::NotConverged {
            match solver.run_off(tau0, 1.0, ratio, settings, observer, &mut |_| {}) {
                Ok(run) if !matches!(run.end, RunOffEnd::Stalled { .. }) => {
                    return run.into_solution(failed);
                }
                Ok(_) => {}
                Err(e @ ContactError::ContinuationBudgetSpent { .. }) => return Err(e),
                Err(e) if e.kind() == ContactErrorKind::Interrupted => return Err(e),
                Err(_) => {}
            }
        }
        match self.run_off_lu_settings(method) {
            Some(lu) if self.body.contact.is_unilateral() => {
                let lu = FullSystemSolver::new(model, lu)?;
                match lu.run_off(tau0, 1.0, ratio, settings, observer, &mut |_| {}) {
                    Ok(run) if matches!(run.end, RunOffEnd::Folded { .. }) => {
                        run.into_solution(failed)
                    }
                    Err(e) if e.kind() == ContactErrorKind::Interrupted => Err(e),
                    _ => Err(failed),
                }
            }
            _ => Err(failed),
        }
    }

    /// [`ContactError::NoEquilibrium`] when the problem is a plane body under unilateral
    /// contact whose ratio `r` (`tau0 > 0`) lies outside its limiting range: the end on `r`'s
    /// side first ([`FullSystemSolver::limiting_end`], upward for `r >= 1`), the other only to
    /// name the range when `r` lies beyond. `None` otherwise: inside, another body, no rigid
    /// sliding mode, or a full-slip solve that failed (the failure then stays the solver's).
    /// Asked only after the full-system Newton failed, as the bilateral body's condensed check
    /// ([`Problem::explain_not_converged`]): a converging run does no extra work, and an
    /// equilibrium the regularised law holds past the full-slip balance (docs/models.md) is
    /// returned rather than refused.
    fn outside_unilateral_range(
        &self,
        solver: &FullSystemSolver<'_, BodyOperator, AnyFrictionLaw>,
    ) -> Option<ContactError> {
        let plane = matches!(self.body.dimension, Dimension::Plane);
        let (tau0, ratio) = (self.loads.tau0, self.loads.tension_ratio());
        if !(plane && self.body.contact.is_unilateral() && tau0 > 0.0) {
            return None;
        }
        let direction = if ratio >= 1.0 { 1.0 } else { -1.0 };
        let near = solver.limiting_end(tau0, direction).ok().flatten()?;
        let tol = 1e-9 * ratio.abs().max(1.0);
        if direction * (ratio - near.ratio) <= tol {
            return None;
        }
        let far = solver.limiting_end(tau0, -direction).ok().flatten()?;
        let range = LimitingRange::from_ends(near, far);
        Some(ContactError::NoEquilibrium {
            ratio,
            lower: range.lower,
            upper: range.upper,
        })
    }

    /// A full-system non-convergence, told apart: no equilibrium (checked by the condensed
    /// solver's limiting ratios of `model`) rather than a solver failure. (A plane body under
    /// unilateral contact was checked against its own range first,
    /// [`Problem::outside_unilateral_range`]; the condensed solver refuses its model, so its
    /// error stays.)
    fn explain_not_converged(&self, model: &Model, e: ContactError) -> ProblemError {
        let check = || -> Result<(), ContactError> {
            BoundarySolver::new(model, ContactSettings::default())?.check_equilibrium(self.loads)
        };
        match check() {
            Err(no_equilibrium @ ContactError::NoEquilibrium { .. }) => no_equilibrium.into(),
            _ => e.into(),
        }
    }
}

/// The threshold of a plane body under unilateral contact: the upper end `r_L` of its limiting
/// range ([`FullSystemSolver::limiting_end`] upward, `tau0 = 1`), the ratio at which the whole
/// contact slides rigidly with friction on the nodes still in contact; no equilibrium beyond.
/// The full-slip balance is solved directly (to the Newton tolerance), so the result's
/// bracket is `[r_L, r_L]` (`below = above = ratio`, Slip 1 there) and `limiting_ratio` is
/// `r_L`; `solves` counts the one full-slip solve.
///
/// # Errors
/// The full-slip solve's ([`FullSystemSolver::full_slip_ratio`]);
/// [`ContactError::Unsupported`] naming `contact.kind` when the body has no rigid sliding
/// mode or friction holds every ratio upward (no full-slip threshold of this kind).
fn threshold_at_limit(
    solver: &FullSystemSolver<'_, BodyOperator, AnyFrictionLaw>,
) -> Result<ThresholdResult, ContactError> {
    let upper = solver
        .limiting_end(1.0, 1.0)?
        .map(|end| end.ratio)
        .filter(|r| r.is_finite())
        .ok_or(ContactError::Unsupported {
            field: "contact.kind",
            message: "the threshold of a plane body under unilateral contact is the full-slip limit along a rigid sliding mode (a circular obstacle); this body has none, or friction holds every ratio upward",
        })?;
    Ok(ThresholdResult {
        ratio: upper,
        below: upper,
        above: upper,
        slip_fraction_below: 1.0,
        above_is_no_equilibrium: true,
        solves: 1,
        limiting_ratio: Some(upper),
        fold: None,
    })
}
