//! The full-system contact solver: Newton (any registered linear backend for the steps:
//! sparse LU refactorised each step by default, or GMRES with the discretisation's geometric
//! multigrid, `multigrid`) or the paper's Jacobi–Newton on the whole residual. The reference the boundary-only solver is checked
//! against, and the baseline of the benchmarks.

use std::sync::OnceLock;

use capstan_friction::FrictionLaw;
use capstan_solvers::{
    ActiveSet, BackendKind, BoxedLinearSolver, DistributedNewton, Jacobian, LinearBackend, Newton,
    NewtonParams, NonlinearMethod, NonlinearSolver, Observer, OwnedRowsProblem, Progress, Residual,
    SilentObserver, SolveStage, SolverError, SparsityPattern,
};

use crate::contact::body::ThickBody;
use crate::contact::boundary_solver::{BoundarySolver, ContactSettings};
use crate::contact::bulk_multigrid::{BackendCache, build_backend};
use crate::contact::error::{ContactError, ContactErrorKind};
use crate::contact::load_continuation::{LoadSteps, check_lift_off, solve_continued, tally};
use crate::contact::loads::EndLoads;
use crate::contact::model::ContactModel;
use crate::contact::operator::ContactOperator;
use crate::contact::owned_rows::OwnedContact;
use crate::contact::solution::{ContactSolution, SolveStats};
use crate::discretisation::interpolate_nodal;
use crate::error::ElasticityError;
use crate::registration::PlaneOperator;

/// Settings of [`FullSystemSolver`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FullSystemSettings {
    /// `newton` (linear backend `newton.linear`) or `jacobi-newton`.
    pub method: NonlinearMethod,
    /// Newton settings; the tolerances are replaced by `continuation.tolerance` relative to
    /// `max(1, |b|_2)`. `newton.linear` is any registered backend
    /// ([`capstan_solvers::linear_registry`]): `lu` (default) refactorised each step, or
    /// `multigrid` (`solver.linear = "multigrid"`, the 3-D body only): each step by GMRES
    /// preconditioned with the discretisation's geometric multigrid (settings
    /// `newton.krylov`, `newton.multigrid`), the stuck start by CG.
    pub newton: NewtonParams,
    /// Continuation settings (shared with the boundary-only solver).
    pub continuation: ContactSettings,
    /// [`solve_sequenced`] solves grids of at most this many nodes directly (its coarsest
    /// level); default [`SEQUENCING_COARSEST_NODES`].
    pub coarsest_nodes: usize,
}

impl Default for FullSystemSettings {
    fn default() -> Self {
        Self {
            method: NonlinearMethod::Newton,
            newton: NewtonParams::default(),
            continuation: ContactSettings::default(),
            coarsest_nodes: SEQUENCING_COARSEST_NODES,
        }
    }
}

/// The full residual `R(v)` and Jacobian of a contact model under fixed loads, as a
/// [`capstan_solvers`] problem.
///
/// # Math
/// ```text
/// R(v)  = A v - b - sum_k w_k e_row_k t_2,k(v)
/// dR/dv = A - sum_k w_k e_row_k (dt_2/dv^2 e_tdof_k^T + dt_2/dsigma N_k)
/// ```
/// on the pattern of `A` extended by the friction entries.
pub struct FullSystemProblem<'a, D, L: FrictionLaw<f64>> {
    model: &'a ContactModel<D, L>,
    rhs: Vec<f64>,
    /// The contact active set at the last residual evaluation (the accepted iterate when an
    /// observer hears of it).
    last_set: std::cell::Cell<Option<ActiveSet>>,
    /// Exact friction's penalty start ([`FullSystemProblem::penalty_start`]).
    penalty: Option<f64>,
}

impl<'a, D, L: FrictionLaw<f64>> FullSystemProblem<'a, D, L> {
    /// The problem for `loads`.
    pub fn new(model: &'a ContactModel<D, L>, loads: EndLoads) -> Self {
        Self {
            rhs: model.rhs(loads),
            model,
            last_set: std::cell::Cell::new(None),
            penalty: None,
        }
    }

    /// The problem for `loads` with exact friction replaced by its regularisation
    /// `t = P_C(-(|sigma_n| / width) u)` (regularised Coulomb of width `mu width`: a linear
    /// spring up to the friction limit, no traction in the trial), the start of the
    /// semismooth Newton method. Its Newton converges from the stuck start with load
    /// continuation, like every regularised law; the exact rows from the stuck start can step
    /// into full slip at every site, where their Jacobian is singular along the rigid sliding
    /// mode of a circular obstacle.
    pub fn penalty_start(model: &'a ContactModel<D, L>, loads: EndLoads, width: f64) -> Self {
        Self {
            penalty: Some(width),
            ..Self::new(model, loads)
        }
    }

    /// The contact active set at the last residual evaluation.
    pub fn last_active_set(&self) -> Option<ActiveSet> {
        self.last_set.get()
    }

    /// The right-hand side `b`.
    pub fn rhs(&self) -> &[f64] {
        &self.rhs
    }
}

impl<D, L: FrictionLaw<f64>> Residual<f64> for FullSystemProblem<'_, D, L> {
    type Error = SolverError;
    fn residual(&self, u: &[f64], r: &mut [f64]) -> Result<(), Self::Error> {
        self.model.residual_with(&self.rhs, u, r, self.penalty)?;
        // on a distributed model each process counts its sites (a collective sum)
        self.last_set
            .set(Some(self.model.active_set_reduced(&self.rhs, u)?));
        Ok(())
    }
}

impl<D, L: FrictionLaw<f64>> Jacobian<f64> for FullSystemProblem<'_, D, L> {
    fn pattern(&self) -> &SparsityPattern {
        &self.model.extended().pattern
    }
    fn jacobian(&self, u: &[f64], values: &mut [f64]) -> Result<(), Self::Error> {
        self.model.jacobian_with(&self.rhs, u, values, self.penalty);
        Ok(())
    }
}

/// Newton or Jacobi–Newton on the full residual, with load continuation.
///
/// The start is the stuck solution (a stiff spring on `v^2` at the contact: the body held by
/// friction everywhere), scaled with the load factor; or a given start
/// ([`FullSystemSolver::solve_from`], e.g. a coarser grid's solution: [`solve_sequenced`]).
pub struct FullSystemSolver<'a, D, L: FrictionLaw<f64>> {
    model: &'a ContactModel<D, L>,
    settings: FullSystemSettings,
    /// The stuck solution for unit `tau0` and unit `tau_max`, and for the gap alone (zero
    /// but under unilateral contact: the body closed onto the obstacle, `v^3 = -g`); one
    /// sparse LU, on first use.
    stuck: OnceLock<[Vec<f64>; 3]>,
    /// The discretisation's multigrid prolongations and near-null space (for backends that
    /// ask, on first use).
    cache: BackendCache,
}

impl<D, L: FrictionLaw<f64>> core::fmt::Debug for FullSystemSolver<'_, D, L> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("FullSystemSolver")
            .field("settings", &self.settings)
            .finish_non_exhaustive()
    }
}

impl<'a, D: ContactOperator, L: FrictionLaw<f64>> FullSystemSolver<'a, D, L> {
    /// Checks the settings by building the linear backend once (the stuck starting guesses
    /// are factorised on first use; a backend that asks for the multigrid hierarchy gets it
    /// now).
    ///
    /// # Errors
    /// Invalid settings; [`ElasticityError::InvalidParameter`] naming `solver.linear` for
    /// `multigrid` on a discretisation without a hierarchy.
    pub fn new(
        model: &'a ContactModel<D, L>,
        settings: FullSystemSettings,
    ) -> Result<Self, ContactError> {
        settings.continuation.validate()?;
        settings.newton.validate()?;
        model.require_assembled(
            "a matrix-free model is solved by the matrix-free Newton (capstan_elasticity::contact::MatrixFreeNewton)",
        )?;
        let solver = Self {
            model,
            settings,
            stuck: OnceLock::new(),
            cache: BackendCache::default(),
        };
        // validate by building: a discretisation without the hierarchy a backend needs is
        // refused here
        solver.backend(settings.newton.linear, false)?;
        Ok(solver)
    }

    /// `backend` with the Newton settings, for the model's matrices (`spd`: symmetric positive
    /// definite ones), the discretisation's ordering unless one is set.
    pub(crate) fn backend(
        &self,
        backend: LinearBackend,
        spd: bool,
    ) -> Result<BoxedLinearSolver, ContactError> {
        build_backend(
            backend,
            &self.settings.newton.linear_settings(),
            self.model.discretisation(),
            &self.cache,
            spd,
        )
    }

    /// The Newton linear backend (`newton.linear`) for the model's Jacobians.
    pub(crate) fn linear_backend(&self) -> Result<BoxedLinearSolver, ContactError> {
        self.backend(self.settings.newton.linear, false)
    }

    /// The settings.
    pub fn settings(&self) -> FullSystemSettings {
        self.settings
    }

    /// Whether the bulk operator `A` is symmetric (then the stuck start's matrix, `A` with a
    /// positive spring on diagonal entries, is symmetric positive definite).
    fn symmetric_bulk(&self) -> bool {
        let system = self.model.system();
        let p = &system.pattern;
        p.entries().zip(&system.values).all(|((i, j), v)| {
            p.slot(j, i)
                .is_some_and(|s| (system.values[s] - v).abs() <= 1e-12 * v.abs().max(1.0))
        })
    }

    /// The stuck solutions for unit loads: one factorisation of `A` with a stiff spring on the
    /// tangential contact rows, by the Newton backend (by `lu` if that is a stationary
    /// iteration: the stiff spring is what sweeps are slowest on), told the matrix is
    /// symmetric positive definite when `A` is symmetric (CG for `multigrid`).
    fn stuck_basis(&self) -> Result<&[Vec<f64>; 3], ContactError> {
        if let Some(s) = self.stuck.get() {
            return Ok(s);
        }
        let model = self.model;
        let ext = model.extended();
        let mut values = vec![0.0; ext.pattern.nnz()];
        for (k, &a) in model.system().values.iter().enumerate() {
            values[ext.a_slot[k]] += a;
        }
        for &slot in &ext.tangential_slot {
            values[slot] += 1e4 * values[slot].abs().max(1.0);
        }
        let linear = self.settings.newton.linear;
        let mut lu = match linear.kind() {
            BackendKind::Stationary => self.backend(LinearBackend::LU, false)?,
            BackendKind::Krylov => self.backend(linear, self.symmetric_bulk())?,
            _ => self.backend(linear, false)?,
        };
        lu.analyse(&ext.pattern)?;
        lu.factor(&values)?;
        if let Some((d, block)) = model.row_distribution().filter(|(d, _)| {
            model.unilateral().is_none()
                && d.newton_on_owned_rows()
                && linear.kind() == BackendKind::Krylov
        }) {
            // each process solves for its rows (no whole vector inside the backend), then
            // the rows are gathered: the continuation reads the start whole
            let rows = d.owned(model.dof_count(), block);
            let mut unit = |i: usize| -> Result<Vec<f64>, ContactError> {
                let mut v = vec![0.0; model.dof_count()];
                if i < 2 {
                    let mut owned = model.rhs_basis(i)[rows.clone()].to_vec();
                    lu.solve_owned_in_place_observed(rows.start, &mut owned, &mut SilentObserver)?;
                    v[rows.clone()].copy_from_slice(&owned);
                    d.gather(&mut v, block)?;
                }
                Ok(v)
            };
            let basis = [unit(0)?, unit(1)?, unit(2)?];
            return Ok(self.stuck.get_or_init(|| basis));
        }
        // unilateral contact: the closed start, v^3 = -g on the contact face
        let unilateral = model.unilateral();
        let mut unit = |i: usize| -> Result<Vec<f64>, ContactError> {
            let mut v = match i {
                2 => vec![0.0; model.dof_count()],
                _ => model.rhs_basis(i).to_vec(),
            };
            if let Some(u) = unilateral {
                u.closed_rows(&mut v, i == 2);
            } else if i == 2 {
                return Ok(v);
            }
            lu.solve_in_place(&mut v)?;
            Ok(v)
        };
        let basis = [unit(0)?, unit(1)?, unit(2)?];
        Ok(self.stuck.get_or_init(|| basis))
    }

    fn stuck(&self, loads: EndLoads) -> Result<Vec<f64>, ContactError> {
        let [a, b, c] = self.stuck_basis()?;
        Ok(a.iter()
            .zip(b)
            .zip(c)
            .map(|((a, b), c)| loads.tau0 * a + loads.tau_max * b + c)
            .collect())
    }

    /// Newton on `problem` from `v` (whole vectors).
    fn newton_on(
        &self,
        problem: &FullSystemProblem<'_, D, L>,
        v: &mut [f64],
        stats: &mut SolveStats,
        observer: &mut dyn Observer<f64>,
    ) -> Result<f64, SolverError> {
        let b = problem.rhs().iter().map(|x| x * x).sum::<f64>().sqrt();
        let params = NewtonParams {
            absolute_tolerance: self.settings.continuation.tolerance * b.max(1.0),
            relative_tolerance: 0.0,
            max_iterations: self.settings.continuation.max_iterations,
            ..self.settings.newton
        };
        // every Newton iterate reported with the active set it ended on
        let mut observer = WithActiveSet {
            inner: observer,
            last: &problem.last_set,
        };
        let observer: &mut dyn Observer<f64> = &mut observer;
        let result = match self.settings.method {
            NonlinearMethod::Newton => {
                let linear = self.backend(params.linear, false).map_err(|e| match e {
                    ContactError::Solver(s) => s,
                    other => SolverError::problem("jacobian", other),
                })?;
                Newton::with_linear_solver(params, linear)?.solve(problem, v, observer)
            }
            method => method.build(params)?.solve(problem, v, observer),
        };
        tally(result, stats)
    }

    /// Newton on this process's rows of the model ([`OwnedContact`]) from `v` (whole on
    /// entry; on return the last iterate, gathered whole on every process: the continuation
    /// and the outputs read it whole). Collective.
    fn newton_owned(
        &self,
        owned: &OwnedContact<'_, D, L>,
        v: &mut [f64],
        stats: &mut SolveStats,
        observer: &mut dyn Observer<f64>,
    ) -> Result<f64, SolverError> {
        let rows = owned.rows();
        let distribution = owned.distribution();
        let b = distribution
            .sum(owned.rhs().iter().map(|x| x * x).sum::<f64>())?
            .sqrt();
        let params = NewtonParams {
            absolute_tolerance: self.settings.continuation.tolerance * b.max(1.0),
            relative_tolerance: 0.0,
            max_iterations: self.settings.continuation.max_iterations,
            ..self.settings.newton
        };
        let linear = self.backend(params.linear, false).map_err(|e| match e {
            ContactError::Solver(s) => s,
            other => SolverError::problem("jacobian", other),
        })?;
        let mut observer = WithActiveSet {
            inner: observer,
            last: owned.last_set(),
        };
        let mut u = v[rows.clone()].to_vec();
        let result = DistributedNewton::new(params, linear)?.solve(owned, &mut u, &mut observer);
        v[rows].copy_from_slice(&u);
        drop(u);
        owned.gather(v)?;
        tally(result, stats)
    }

    /// Solves for the loads by Newton from `start` (one value per unknown, e.g. a coarser
    /// grid's solution interpolated: [`crate::interpolate_nodal`]); if that fails, by
    /// [`FullSystemSolver::solve`] (stuck start and load continuation), the iterations of the
    /// failed attempt counted in the statistics.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] for a start of the wrong length; see
    /// [`FullSystemSolver::solve`].
    pub fn solve_from(
        &self,
        loads: EndLoads,
        start: &[f64],
    ) -> Result<ContactSolution, ContactError> {
        self.solve_from_observed(loads, start, &mut SilentObserver)
    }

    /// [`FullSystemSolver::solve_from`] with an observer (see
    /// [`FullSystemSolver::solve_observed`]).
    ///
    /// # Errors
    /// See [`FullSystemSolver::solve_from`]; an interrupted solve.
    pub fn solve_from_observed(
        &self,
        loads: EndLoads,
        start: &[f64],
        observer: &mut dyn Observer<f64>,
    ) -> Result<ContactSolution, ContactError> {
        loads.check()?;
        if start.len() != self.model.dof_count() {
            return Err(ContactError::from(ElasticityError::InvalidParameter {
                field: "start",
                value: start.len() as f64,
                allowed: "one value per unknown",
            }));
        }
        let mut stats = self.fresh_stats(0);
        let mut v = start.to_vec();
        if start.iter().all(|x| x.is_finite()) {
            match LoadSteps::newton(self, loads, &mut v, &mut stats, observer) {
                Ok(_) => {
                    check_lift_off(self.model, loads, &v)?;
                    return Ok(ContactSolution::new(self.model, loads, v, stats)?);
                }
                Err(e @ (SolverError::Interrupted { .. } | SolverError::BudgetSpent { .. })) => {
                    return Err(e.into());
                }
                Err(_) => {}
            }
        }
        let mut sol = self.solve_observed(loads, observer)?;
        sol.stats.newton_iterations += stats.newton_iterations;
        sol.stats.factorisations += stats.factorisations;
        sol.stats.linear_iterations += stats.linear_iterations;
        Ok(sol)
    }

    /// Statistics before any iteration (`factorisations` already done).
    fn fresh_stats(&self, factorisations: usize) -> SolveStats {
        SolveStats {
            method: match self.settings.method {
                NonlinearMethod::JacobiNewton => "full-jacobi-newton",
                _ => "full-newton",
            },
            newton_iterations: 0,
            continuation_steps: 1,
            residual: 0.0,
            linear_iterations: 0,
            factorisations,
        }
    }

    /// Solves for the loads.
    ///
    /// # Errors
    /// [`ContactError::NotConverged`] (or [`ContactError::LoadStepFailed`], a step failing
    /// without a residual) when the continuation fails; invalid loads;
    /// [`SolverError::BudgetSpent`] (inside [`ContactError::Solver`], naming
    /// `krylov.max_iterations`) when an iterative bulk solve spends its budget (no
    /// continuation is tried: a smaller load step does not make the linear solves cheaper).
    pub fn solve(&self, loads: EndLoads) -> Result<ContactSolution, ContactError> {
        self.solve_observed(loads, &mut SilentObserver)
    }

    /// [`FullSystemSolver::solve`] reporting every Newton iterate
    /// ([`SolveStage::Newton`] or [`SolveStage::JacobiNewton`]: the residual norm of the full
    /// system, no stick/slip counts) and every converged load step
    /// ([`SolveStage::Continuation`]) to `observer`, which may stop the solve
    /// ([`SolverError::Interrupted`] inside [`ContactError::Solver`]).
    ///
    /// # Errors
    /// See [`FullSystemSolver::solve`].
    pub fn solve_observed(
        &self,
        loads: EndLoads,
        observer: &mut dyn Observer<f64>,
    ) -> Result<ContactSolution, ContactError> {
        loads.check()?;
        // the stuck start's sparse LU, unless an earlier solve made it
        let stats = self.fresh_stats(usize::from(self.stuck.get().is_none()));
        let v = self.stuck(loads)?;
        solve_continued(self, loads, v, stats, observer)
    }
}

impl<D: ContactOperator, L: FrictionLaw<f64>> LoadSteps<D, L> for FullSystemSolver<'_, D, L> {
    fn model(&self) -> &ContactModel<D, L> {
        self.model
    }

    fn continuation(&self) -> ContactSettings {
        self.settings.continuation
    }

    fn stuck_start(
        &self,
        loads: EndLoads,
        _stats: &mut SolveStats,
    ) -> Result<Vec<f64>, ContactError> {
        self.stuck(loads)
    }

    fn newton(
        &self,
        loads: EndLoads,
        v: &mut [f64],
        stats: &mut SolveStats,
        observer: &mut dyn Observer<f64>,
    ) -> Result<f64, SolverError> {
        if self.model.is_exact_friction() {
            let penalty =
                FullSystemProblem::penalty_start(self.model, loads, self.model.slip_threshold());
            self.newton_on(&penalty, v, stats, observer)?;
        }
        // on a model assembled over several processes (a regularised law, bilateral
        // contact): Newton on each process's rows
        if self.settings.method == NonlinearMethod::Newton
            && let Some(owned) = OwnedContact::new(self.model, loads)
        {
            return self.newton_owned(&owned, v, stats, observer);
        }
        self.newton_on(
            &FullSystemProblem::new(self.model, loads),
            v,
            stats,
            observer,
        )
    }
}

/// Passes every event on, the full-system Newton iterates with the contact active set of the
/// last residual evaluation (the accepted iterate).
struct WithActiveSet<'o, 'p> {
    inner: &'o mut dyn Observer<f64>,
    last: &'p std::cell::Cell<Option<ActiveSet>>,
}

impl Observer<f64> for WithActiveSet<'_, '_> {
    fn iteration(&mut self, progress: &Progress<f64>) {
        match (progress.stage, self.last.get()) {
            (SolveStage::Newton | SolveStage::JacobiNewton, Some(set))
                if progress.active.is_none() =>
            {
                self.inner.iteration(&progress.with_contact_set(set));
            }
            _ => self.inner.iteration(progress),
        }
    }

    fn interrupted(&mut self) -> bool {
        self.inner.interrupted()
    }
}

/// The default of [`FullSystemSettings::coarsest_nodes`]: grids with at most this many nodes
/// are solved directly, by the boundary-only solver, as the coarsest level of
/// [`solve_sequenced`] (the paper's 250 x 41 grid is one level).
pub const SEQUENCING_COARSEST_NODES: usize = 20_000;

/// The result of [`solve_sequenced`]: the finest level's model and solution, and the grids.
pub struct Sequenced<L: FrictionLaw<f64>> {
    /// The contact model on the body's own grid.
    pub model: ContactModel<PlaneOperator, L>,
    /// Its solution (statistics of the finest level; see `levels` for the others).
    pub solution: ContactSolution,
    /// `(n2, n3, newton iterations)` of every level, coarsest first.
    pub levels: Vec<(usize, usize, usize)>,
    /// The level before the finest (the body's [`ThickBody::coarser`] grid): its model and
    /// solution, a free solution one grid level coarser for error estimates; `None` with one
    /// level.
    pub coarser: Option<(ContactModel<PlaneOperator, L>, ContactSolution)>,
}

/// The full-system Newton on `body` with grid sequencing (nested iteration): the body on
/// ever coarser grids ([`ThickBody::coarser`]) down to [`FullSystemSettings::coarsest_nodes`],
/// the coarsest solved by the boundary-only solver, each finer level by Newton from the
/// coarser solution interpolated ([`crate::interpolate_nodal`]).
///
/// # Math
/// The interpolated start is within `O(dx^2)` of the fine solution, inside Newton's region of
/// quadratic convergence for all but the nodes whose stick/slip state changes, so each fine
/// level needs a few factorisations instead of the dozens a stuck start and load continuation
/// take on the large grids where a factorisation is the whole cost. A level whose Newton fails
/// from its start falls back to [`FullSystemSolver::solve`]; every level's answer is the
/// fine problem's (the sequence only chooses the start).
///
/// Every level reports to `observer` (a [`SilentObserver`] for none): the iterations of its
/// solver, then one [`SolveStage::GridLevel`] event (`iteration` the level, coarsest 0;
/// `residual_norm` the level's full-system residual; `step_length` its number of nodes).
///
/// # Errors
/// Model and solver errors of any level; [`ContactError::NoEquilibrium`] from the coarsest;
/// an interrupted solve.
pub fn solve_sequenced<L, S>(
    body: &ThickBody<S>,
    law: L,
    params: L::Params,
    slip_threshold: f64,
    loads: EndLoads,
    settings: FullSystemSettings,
    observer: &mut dyn Observer<f64>,
) -> Result<Sequenced<L>, ContactError>
where
    L: FrictionLaw<f64> + Clone,
    S: capstan_geometry::Surface<f64> + Clone + Send + Sync + 'static,
{
    let level_done = |level: usize, n2: usize, n3: usize, solution: &ContactSolution| {
        Progress::new(
            SolveStage::GridLevel,
            level,
            solution.stats.residual,
            (n2 * n3) as f64,
        )
    };
    let mut bodies = vec![body.clone()];
    while let Some(last) = bodies.last()
        && last.n2 * last.n3 > settings.coarsest_nodes
        && let Some(c) = last.coarser()
    {
        bodies.push(c);
    }
    bodies.reverse();
    let mut levels = Vec::with_capacity(bodies.len());
    let coarsest = &bodies[0];
    let model = coarsest.model(law.clone(), params.clone(), slip_threshold)?;
    let coarse = if bodies.len() == 1 {
        FullSystemSolver::new(&model, settings)?.solve_observed(loads, observer)
    } else {
        BoundarySolver::new(&model, settings.continuation)
            .and_then(|s| s.solve_observed(loads, observer))
    };
    let mut solution = match coarse {
        Ok(solution) => solution,
        Err(e)
            if bodies.len() == 1
                || matches!(
                    e.kind(),
                    ContactErrorKind::NoEquilibrium | ContactErrorKind::Interrupted
                ) =>
        {
            return Err(e);
        }
        Err(_) => {
            // no sequence without its coarsest level: the body's own grid directly
            let model = body.model(law, params, slip_threshold)?;
            let solution =
                FullSystemSolver::new(&model, settings)?.solve_observed(loads, observer)?;
            observer.iteration(&level_done(0, body.n2, body.n3, &solution));
            let levels = vec![(body.n2, body.n3, solution.stats.newton_iterations)];
            return Ok(Sequenced {
                model,
                solution,
                levels,
                coarser: None,
            });
        }
    };
    observer.iteration(&level_done(0, coarsest.n2, coarsest.n3, &solution));
    levels.push((coarsest.n2, coarsest.n3, solution.stats.newton_iterations));
    let mut model = model;
    let mut coarser = None;
    for fine in &bodies[1..] {
        let fine_model = fine.model(law.clone(), params.clone(), slip_threshold)?;
        let start = interpolate_nodal(
            model.discretisation(),
            &solution.displacement,
            fine_model.discretisation(),
        );
        let fine_solution = FullSystemSolver::new(&fine_model, settings)?
            .solve_from_observed(loads, &start, observer)?;
        observer.iteration(&level_done(levels.len(), fine.n2, fine.n3, &fine_solution));
        levels.push((fine.n2, fine.n3, fine_solution.stats.newton_iterations));
        coarser = Some((
            std::mem::replace(&mut model, fine_model),
            std::mem::replace(&mut solution, fine_solution),
        ));
    }
    Ok(Sequenced {
        model,
        solution,
        levels,
        coarser,
    })
}
