//! The contact problem's error type.

use capstan_friction::FrictionError;
use capstan_solvers::SolverError;

use crate::error::ElasticityError;

/// Everything that can go wrong while building or solving a frictional contact problem.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ContactError {
    /// The discretisations built for different end loads do not share one bulk operator.
    #[error(
        "the bulk operator depends on the loads ({what}); contact condensation needs it linear"
    )]
    InconsistentLoads {
        /// What differs.
        what: &'static str,
    },
    /// A factorised bulk was offered to a model of another body
    /// ([`crate::contact::BoundarySolver::with_model`]).
    #[error("the model is not the body this solver factorised ({what} differ); build a new solver")]
    DifferentBody {
        /// What differs.
        what: &'static str,
    },
    /// No contact node has a free tangential row (nothing for friction to act on).
    #[error("the contact surface has no node with a free tangential displacement")]
    NoContactNodes,
    /// No static equilibrium exists: the tension ratio exceeds what friction can hold (the body
    /// slides off as a rigid body).
    #[error(
        "no static equilibrium: tension ratio {ratio:.6} is outside the limiting range [{lower:.6}, {upper:.6}] that friction can hold"
    )]
    NoEquilibrium {
        /// `tau_max / tau0` asked for.
        ratio: f64,
        /// Smallest ratio friction can hold.
        lower: f64,
        /// Largest ratio friction can hold.
        upper: f64,
    },
    /// No static equilibrium beyond a limit point of the equilibrium path: the continuation in
    /// the tension ratio ([`crate::contact::FullSystemSolver::run_off`]) found the path to turn
    /// back at `fold` (the largest ratio it reached), between the last ratio it converged at
    /// (`lower`) and the first it could not reach (`upper`), below the ratio asked for.
    #[error(
        "no static equilibrium at tension ratio {ratio:.6}: the equilibrium path folds back at r* = {fold:.6}; no equilibrium beyond r* in [{lower:.6}, {upper:.6}]"
    )]
    NoEquilibriumBeyond {
        /// `tau_max / tau0` asked for.
        ratio: f64,
        /// The fold ratio `r*`: the largest ratio reached on the path (an equilibrium there).
        fold: f64,
        /// The largest ratio of the continuation's steps that converged.
        lower: f64,
        /// The smallest ratio of its steps that the path folded back before.
        upper: f64,
    },
    /// No static equilibrium below a limit point of the equilibrium path: the continuation in
    /// the tension ratio down from 1 ([`crate::contact::FullSystemSolver::run_off`]) found the
    /// path to turn back at `fold` (`r_*`, the smallest ratio it reached), between the first
    /// ratio it could not reach (`lower`) and the last it converged at (`upper`), above the
    /// ratio asked for.
    #[error(
        "no static equilibrium at tension ratio {ratio:.6}: the equilibrium path folds back at r_* = {fold:.6}; no equilibrium below r_* in [{lower:.6}, {upper:.6}]"
    )]
    NoEquilibriumBelow {
        /// `tau_max / tau0` asked for.
        ratio: f64,
        /// The fold ratio `r_*`: the smallest ratio reached on the path (an equilibrium there).
        fold: f64,
        /// The largest ratio of the continuation's steps that the path folded back before.
        lower: f64,
        /// The smallest ratio of its steps that converged.
        upper: f64,
    },
    /// The continuation in the tension ratio ([`crate::contact::FullSystemSolver::run_off`])
    /// spent its budget of arclength steps
    /// ([`crate::contact::ContactSettings::max_continuation_steps`]).
    #[error(
        "the continuation in the tension ratio spent its budget of {steps} arclength steps (`max_continuation_steps`) at ratio {reached:.6} on the way to {ratio:.6}"
    )]
    ContinuationBudgetSpent {
        /// The budget (steps taken).
        steps: usize,
        /// The largest ratio converged at.
        reached: f64,
        /// `tau_max / tau0` asked for.
        ratio: f64,
    },
    /// Unilateral contact: the solution has every contact node separated from the obstacle.
    /// The body is then free, and a free body has rigid motions: its static equilibrium under
    /// the loads is not unique (balanced loads) or does not exist (unbalanced ones; Newton then
    /// fails with every node separated). Either way no equilibrium on the obstacle exists.
    #[error(
        "no static equilibrium: the body lifts off the obstacle entirely (all {nodes} contact nodes separated) at tension ratio {ratio:.6}"
    )]
    LiftedOff {
        /// `tau_max / tau0` asked for.
        ratio: f64,
        /// Contact nodes (every one separated).
        nodes: usize,
    },
    /// The nonlinear solve failed even with load continuation.
    #[error(
        "contact Newton did not converge: residual {residual:.3e} after {iterations} iterations (load factor reached {load_factor:.4})"
    )]
    NotConverged {
        /// Newton iterations spent in total.
        iterations: usize,
        /// Last residual (max norm, relative).
        residual: f64,
        /// The last load factor in `[0, 1]` that converged.
        load_factor: f64,
    },
    /// The load continuation stopped at a step whose Newton solve failed without a residual to
    /// report (a singular Jacobian, a failed linear solve): `source` is that failure, the
    /// solver's own, rather than a residual of `inf`.
    #[error(
        "contact Newton did not converge: the Newton solve of the load step to load factor {attempted:.4} failed: {source} (after {iterations} iterations in total; load factor reached {load_factor:.4})"
    )]
    LoadStepFailed {
        /// Newton iterations spent in total.
        iterations: usize,
        /// The last load factor in `[0, 1]` that converged.
        load_factor: f64,
        /// The load factor of the failed step.
        attempted: f64,
        /// Why its Newton solve failed.
        source: SolverError,
    },
    /// The chosen solver does not handle this contact model (e.g. the condensed solver and
    /// unilateral contact); `field` names the key that picks another.
    #[error("`{field}`: {message}")]
    Unsupported {
        /// The scene key (API parameter) to change.
        field: &'static str,
        /// What is not supported and what to use instead.
        message: &'static str,
    },
    /// The observer asked the solve to stop ([`capstan_solvers::Observer::interrupted`]).
    #[error("interrupted after {iterations} contact Newton iterations")]
    Interrupted {
        /// Newton iterations spent before the stop.
        iterations: usize,
    },
    /// A step of a load path failed ([`crate::contact::solve_path`]); its kind is the kind of
    /// `source`.
    #[error("load path step {step}: {source}")]
    PathStep {
        /// The step, from 1 (the first load state of the path).
        step: usize,
        /// Why the step failed.
        source: Box<ContactError>,
    },
    /// The elasticity layer failed (assembly, geometry), or a parameter of the contact problem
    /// (loads, settings) is outside its allowed range: [`ElasticityError::InvalidParameter`],
    /// the field named as in a scene file where there is one.
    #[error(transparent)]
    Elasticity(#[from] ElasticityError),
    /// A linear or nonlinear solver failed.
    #[error(transparent)]
    Solver(#[from] SolverError),
    /// Invalid friction-law parameters.
    #[error(transparent)]
    Friction(#[from] FrictionError),
}

/// The kind of a [`ContactError`], for exit codes and statuses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ContactErrorKind {
    /// Bad input (exit code 2).
    InvalidInput,
    /// No static equilibrium exists (exit code 3, status `no-equilibrium`).
    NoEquilibrium,
    /// The solver did not converge (exit code 4, status `not-converged`).
    NotConverged,
    /// The solve was stopped by its observer (status `interrupted`).
    Interrupted,
}

capstan_solvers::named_variants!(ContactErrorKind {
    InvalidInput => "invalid-input",
    NoEquilibrium => "no-equilibrium",
    NotConverged => "not-converged",
    Interrupted => "interrupted",
});

impl ContactError {
    /// Which kind of failure this is.
    pub fn kind(&self) -> ContactErrorKind {
        match self {
            Self::PathStep { source, .. } => source.kind(),
            Self::NoEquilibrium { .. }
            | Self::NoEquilibriumBeyond { .. }
            | Self::NoEquilibriumBelow { .. }
            | Self::LiftedOff { .. } => ContactErrorKind::NoEquilibrium,
            Self::NotConverged { .. }
            | Self::LoadStepFailed { .. }
            | Self::ContinuationBudgetSpent { .. } => ContactErrorKind::NotConverged,
            Self::Interrupted { .. } | Self::Solver(SolverError::Interrupted { .. }) => {
                ContactErrorKind::Interrupted
            }
            Self::Solver(
                SolverError::Diverged { .. }
                | SolverError::Stagnated { .. }
                | SolverError::NotConverged { .. }
                | SolverError::Singular { .. },
            ) => ContactErrorKind::NotConverged,
            _ => ContactErrorKind::InvalidInput,
        }
    }

    /// The status string of a failed run: `no-equilibrium`, `not-converged`, `interrupted` or
    /// `invalid-input`.
    pub fn status(&self) -> &'static str {
        self.kind().name()
    }
}
