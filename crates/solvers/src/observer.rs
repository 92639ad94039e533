//! Progress reporting of every iterative solve; the solvers never print.
//!
//! One [`Observer`] receives a [`Progress`] event per accepted iteration from every loop that
//! iterates: Newton on a sparse system, Jacobi–Newton, Newton on the condensed contact
//! boundary, continuation steps, grid-sequencing levels, the membrane models, and from the
//! set-up phases that run before them (assembly, factorisation, the condensation onto the
//! contact boundary, [`SolveStage::SetUp`] with [`SetUpWork`]). The event names
//! its [`SolveStage`], so one observer can print, draw a progress bar, record residual
//! histories or forward them to Python. An observer can also stop a solve: solvers poll
//! [`Observer::interrupted`] after each iteration and return a typed `Interrupted` error.

use crate::scalar::SolverScalar;

/// Which iterative loop a [`Progress`] event comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum SolveStage {
    /// Newton's method on a sparse system (the full contact system, a sample problem).
    Newton,
    /// The paper's Jacobi–Newton iteration.
    JacobiNewton,
    /// Newton on the condensed contact boundary (`2m` or `m` unknowns for `m` contact nodes).
    CondensedNewton,
    /// A continuation (homotopy) step in a parameter; `iteration` counts the steps taken and
    /// `step_length` is the parameter step.
    Continuation,
    /// A grid-sequencing level has been solved; `iteration` is the level (0 the coarsest).
    GridLevel,
    /// Newton of a membrane model (tension or implied friction coefficient).
    Membrane,
    /// A Krylov iteration (CG, GMRES) of a linear solve; `residual_norm` is the relative
    /// residual `|b - A x_k| / |b|` (GMRES: its estimate from the least-squares problem).
    Krylov,
    /// A set-up phase before the iterations (assembly, factorisation, condensation):
    /// [`Progress::work`] says which phase and how much of it is done; `iteration` is the
    /// work done and `residual_norm`, `step_length` are 0.
    SetUp,
}

// `name()`: the lower-case name used in logs and in the Python package
// (`"condensed-newton"`, ...).
named_variants!(SolveStage {
    Newton => "newton",
    JacobiNewton => "jacobi-newton",
    CondensedNewton => "condensed-newton",
    Continuation => "continuation",
    GridLevel => "grid-level",
    Membrane => "membrane",
    Krylov => "krylov",
    SetUp => "set-up",
});

/// The phase of a [`SolveStage::SetUp`] event.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum SetUpPhase {
    /// Assembling the discrete operator (element integrals, the contact rows).
    Assembly,
    /// Ordering and factorising a sparse matrix (or building a preconditioner).
    Factorisation,
    /// Condensing the bulk onto the contact unknowns: `total` right-hand sides solved with
    /// the factorised bulk (or one Schur complement).
    Condensation,
}

named_variants!(SetUpPhase {
    Assembly => "assembly",
    Factorisation => "factorisation",
    Condensation => "condensation",
});

/// How far a set-up phase has come: `done` of `total` units of work (solves, elements;
/// `0 of 1` when it starts and `1 of 1` when it ends for phases that cannot count).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SetUpWork {
    /// The phase.
    pub phase: SetUpPhase,
    /// Units of work done.
    pub done: usize,
    /// Units of work in the phase.
    pub total: usize,
}

/// Sizes of the contact active set after an iteration: nodes that stick and nodes that slip.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct ActiveSet {
    /// Contact nodes whose slip is below the law's regularisation width.
    pub stick: usize,
    /// Contact nodes that slip.
    pub slip: usize,
    /// Contact nodes that have lifted off the obstacle (unilateral contact; 0 otherwise).
    pub separated: usize,
}

/// One accepted iteration of an iterative solve.
///
/// `iteration = 0` carries the initial residual norm and `step_length = 0`; every later event
/// the residual norm `|r(u_k)|_2` after step `k` and the step length `alpha` taken along the
/// search direction (1 for a full Newton step; the parameter step for
/// [`SolveStage::Continuation`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct Progress<F> {
    /// The loop the event comes from.
    pub stage: SolveStage,
    /// Iteration (or step, or level) counter of that loop.
    pub iteration: usize,
    /// Residual norm after the iteration.
    pub residual_norm: F,
    /// Step length of the iteration.
    pub step_length: F,
    /// Stick/slip counts, where the solve has a contact boundary.
    pub active: Option<ActiveSet>,
    /// The phase and its work done, for [`SolveStage::SetUp`] events (`None` otherwise).
    pub work: Option<SetUpWork>,
}

impl<F> Progress<F> {
    /// An event without active-set counts.
    pub fn new(stage: SolveStage, iteration: usize, residual_norm: F, step_length: F) -> Self {
        Self {
            stage,
            iteration,
            residual_norm,
            step_length,
            active: None,
            work: None,
        }
    }

    /// A [`SolveStage::SetUp`] event: `done` of `total` units of `phase` (`iteration = done`,
    /// residual and step 0).
    pub fn set_up(phase: SetUpPhase, done: usize, total: usize) -> Self
    where
        F: SolverScalar,
    {
        Self {
            work: Some(SetUpWork { phase, done, total }),
            ..Self::new(SolveStage::SetUp, done, F::zero(), F::zero())
        }
    }

    /// The same event with the contact active-set counts.
    #[must_use]
    pub fn with_active(mut self, stick: usize, slip: usize) -> Self {
        self.active = Some(ActiveSet {
            stick,
            slip,
            separated: 0,
        });
        self
    }

    /// The same event with the contact active set: nodes that stick, slip and have lifted off.
    #[must_use]
    pub fn with_contact_set(mut self, active: ActiveSet) -> Self {
        self.active = Some(active);
        self
    }
}

/// Receives the progress of iterative solves.
///
/// Closures `FnMut(&Progress<F>)` are observers (they never interrupt).
///
/// # Example
/// ```
/// use capstan_solvers::{Observer, Progress, SolveStage};
/// let mut seen = Vec::new();
/// let mut obs = |p: &Progress<f64>| seen.push((p.iteration, p.residual_norm));
/// obs.iteration(&Progress::new(SolveStage::Newton, 0, 1.0, 0.0));
/// assert!(!obs.interrupted());
/// assert_eq!(seen, vec![(0, 1.0)]);
/// ```
pub trait Observer<F: SolverScalar> {
    /// One iteration has been accepted.
    fn iteration(&mut self, progress: &Progress<F>);

    /// Polled after every iteration: `true` stops the solve, which returns its crate's
    /// `Interrupted` error (e.g. Ctrl-C in an embedding interpreter, a wall-clock limit).
    fn interrupted(&mut self) -> bool {
        false
    }
}

/// An observer that ignores everything.
#[derive(Clone, Copy, Debug, Default)]
pub struct SilentObserver;

impl<F: SolverScalar> Observer<F> for SilentObserver {
    fn iteration(&mut self, _progress: &Progress<F>) {}
}

impl<F: SolverScalar, C: FnMut(&Progress<F>)> Observer<F> for C {
    fn iteration(&mut self, progress: &Progress<F>) {
        self(progress)
    }
}
