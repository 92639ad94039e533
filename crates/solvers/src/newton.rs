//! Newton's method with a backtracking line search (the driver's loop, [`crate::newton_drive`],
//! over a sparse Jacobian and a linear backend).

use core::fmt;

use crate::direct_params::DirectParams;
use crate::error::SolverError;
use crate::iterative_params::IterativeParams;
use crate::krylov::KrylovParams;
use crate::linear_backend::LinearBackend;
use crate::linear_registration::LinearSettings;
use crate::linear_solver::LinearSolver;
use crate::multigrid::MultigridParams;
use crate::newton_driver::{
    Flow, Merit, NewtonDirection, NewtonFailure, NewtonIterate, NewtonPolicy, NewtonSystem,
    ResidualNorm, ShortStep, StepControl, newton_drive,
};
use crate::nonlinear_solver::{NonlinearSolver, SolveReport};
use crate::observer::{Observer, Progress, SolveStage};
use crate::problem::Jacobian;
use crate::scalar::first_non_finite;
use crate::sparsity_pattern::SparsityPattern;

/// Step-length control along the Newton direction.
///
/// # Math
/// ```text
/// phi(alpha) = |r(u + alpha du)|^2,   J du = -r  =>  phi'(0) = -2 phi(0)
/// accept alpha  iff  phi(alpha) <= (1 - 2 armijo alpha) phi(0)      (Armijo)
/// alpha = 1, 1/2, 1/4, ...  while alpha >= min_step
/// ```
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub enum LineSearch {
    /// Always take the full step (pure Newton).
    None,
    /// Backtracking by halving until the Armijo condition on `|r|^2` holds.
    Backtracking {
        /// Sufficient-decrease constant `c` in `(0, 1/2)`; `1e-4` is customary.
        armijo: f64,
        /// Smallest step tried, in `(0, 1)`; below it the solve has stagnated.
        min_step: f64,
    },
}

impl Default for LineSearch {
    fn default() -> Self {
        Self::Backtracking {
            armijo: 1e-4,
            min_step: 1e-10,
        }
    }
}

/// Settings of [`Newton`] (and of [`crate::JacobiNewton`], which ignores `linear`).
///
/// # Math
/// ```text
/// converged      when |r(u_k)|_2 <= max(absolute_tolerance, relative_tolerance |r(u_0)|_2)
/// diverged       when |r(u_k)|_2 >  divergence_limit * max(|r(u_0)|_2, absolute_tolerance)
/// ```
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct NewtonParams {
    /// Iteration cap (at least 1); reaching it is [`SolverError::NotConverged`].
    pub max_iterations: usize,
    /// Absolute residual tolerance, `>= 0`.
    pub absolute_tolerance: f64,
    /// Tolerance relative to the initial residual, in `[0, 1)`; at least one of the two
    /// tolerances must be positive.
    pub relative_tolerance: f64,
    /// Step-length control.
    pub line_search: LineSearch,
    /// Linear backend for the Newton systems `J du = -r` (any registered one:
    /// [`crate::linear_registry`]).
    pub linear: LinearBackend,
    /// Settings of the iterative linear backends (inner tolerance for Jacobi–Newton).
    pub iterative: IterativeParams,
    /// Settings of the direct linear backends (fill-reducing ordering, solution check).
    pub direct: DirectParams,
    /// Settings of the Krylov backends (`multigrid`).
    pub krylov: KrylovParams,
    /// Settings of the multigrid preconditioner (`multigrid`).
    pub multigrid: MultigridParams,
    /// Residual growth factor (> 1) that counts as divergence.
    pub divergence_limit: f64,
}

impl Default for NewtonParams {
    fn default() -> Self {
        Self {
            max_iterations: 50,
            absolute_tolerance: 1e-10,
            relative_tolerance: 1e-10,
            line_search: LineSearch::default(),
            linear: LinearBackend::LU,
            iterative: IterativeParams::default(),
            direct: DirectParams::default(),
            krylov: KrylovParams::default(),
            multigrid: MultigridParams::default(),
            divergence_limit: 1e8,
        }
    }
}

impl NewtonParams {
    /// The driver's policy of the sparse Newtons ([`Newton`], [`crate::DistributedNewton`]):
    /// these tolerances, cap and line search, the two-norm of the residual, divergence at
    /// `divergence_limit`, step stagnation and non-finite values as failures.
    pub(crate) fn policy(&self) -> NewtonPolicy {
        NewtonPolicy {
            max_iterations: self.max_iterations,
            absolute_tolerance: self.absolute_tolerance,
            relative_tolerance: self.relative_tolerance,
            norm: ResidualNorm::Two,
            step: self.line_search.step_control(),
            divergence_limit: Some(self.divergence_limit),
            step_stagnation: true,
            check_finite: true,
        }
    }

    /// The settings of the linear backends, as [`LinearBackend::build`] reads them.
    pub fn linear_settings(&self) -> LinearSettings {
        LinearSettings {
            direct: self.direct,
            iterative: self.iterative,
            krylov: self.krylov,
            multigrid: self.multigrid,
        }
    }

    /// Checks every field (the linear settings are checked when the backend is built).
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), SolverError> {
        let invalid = |field, value, allowed| Err(SolverError::invalid(field, value, allowed));
        SolverError::check_count("max_iterations", self.max_iterations)?;
        if !(self.absolute_tolerance >= 0.0 && self.absolute_tolerance.is_finite()) {
            return invalid("absolute_tolerance", self.absolute_tolerance, "[0, inf)");
        }
        if !(self.relative_tolerance >= 0.0 && self.relative_tolerance < 1.0) {
            return invalid("relative_tolerance", self.relative_tolerance, "[0, 1)");
        }
        if self.absolute_tolerance == 0.0 && self.relative_tolerance == 0.0 {
            return invalid(
                "absolute_tolerance",
                0.0,
                "(0, inf) when relative_tolerance is 0",
            );
        }
        if self.divergence_limit.is_nan() || self.divergence_limit <= 1.0 {
            return invalid("divergence_limit", self.divergence_limit, "(1, inf]");
        }
        if let LineSearch::Backtracking { armijo, min_step } = self.line_search {
            if !(armijo > 0.0 && armijo < 0.5) {
                return invalid("line_search.armijo", armijo, "(0, 0.5)");
            }
            SolverError::check_fraction("line_search.min_step", min_step)?;
        }
        Ok(())
    }
}

/// Newton's method for `r(u) = 0` with a sparse Jacobian and an interchangeable linear
/// backend.
///
/// The pattern is analysed once (and again only if a later problem brings a different
/// pattern); each iteration refills the Jacobian values, refactors and solves.
///
/// # Math
/// ```text
/// J(u_k) du_k = -r(u_k)                 (linear backend)
/// u_{k+1}     = u_k + alpha_k du_k      (alpha_k from the line search)
/// ```
/// Near a root with a nonsingular Jacobian the full step is accepted and convergence is
/// quadratic: `|r_{k+1}| <= C |r_k|^2`.
///
/// # Errors
/// See [`NonlinearSolver::solve`].
///
/// # Example
/// ```
/// use capstan_solvers::{Newton, NonlinearSolver, SilentObserver, samples::CubicReaction};
/// let problem = CubicReaction::new(20); // u^3 + A u = b with a known root
/// let mut u = vec![0.0; 20];
/// let report = Newton::new(Default::default()).unwrap()
///     .solve(&problem, &mut u, &mut SilentObserver).unwrap();
/// assert!(report.iterations <= 8);
/// let exact = problem.exact_solution();
/// assert!(u.iter().zip(&exact).all(|(a, b)| (a - b).abs() < 1e-9));
/// ```
pub struct Newton {
    params: NewtonParams,
    linear: Box<dyn LinearSolver<f64> + Send>,
    analysed: Option<SparsityPattern>,
    /// The stage its [`Progress`] events carry.
    pub(crate) stage: SolveStage,
}

impl fmt::Debug for Newton {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Newton")
            .field("params", &self.params)
            .field("analysed", &self.analysed.as_ref().map(|p| p.nrows()))
            .finish_non_exhaustive()
    }
}

impl Newton {
    /// Newton with the backend named in `params.linear`.
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] if a setting is out of range.
    pub fn new(params: NewtonParams) -> Result<Self, SolverError> {
        params.validate()?;
        let linear = params.linear.build(&params.linear_settings(), &())?;
        Ok(Self {
            params,
            linear,
            analysed: None,
            stage: SolveStage::Newton,
        })
    }

    /// Newton with a caller-supplied linear solver (e.g. one built with a [`crate::LinearContext`]);
    /// `params.linear` is ignored.
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] if a setting is out of range.
    pub fn with_linear_solver(
        params: NewtonParams,
        linear: Box<dyn LinearSolver<f64> + Send>,
    ) -> Result<Self, SolverError> {
        params.validate()?;
        Ok(Self {
            params,
            linear,
            analysed: None,
            stage: SolveStage::Newton,
        })
    }

    /// The settings in use.
    pub fn params(&self) -> &NewtonParams {
        &self.params
    }
}

/// `NonlinearSolver<f64>` for a solver whose solves are those of the [`Newton`] that the
/// expression `$newton` picks out of `$solver` (the solver, by `&mut`).
macro_rules! solve_with_newton {
    ($type:ty, |$solver:ident| $newton:expr) => {
        impl $crate::nonlinear_solver::NonlinearSolver<f64> for $type {
            fn solve<P: $crate::problem::Jacobian<f64> + ?Sized>(
                &mut self,
                problem: &P,
                u: &mut [f64],
                observer: &mut dyn $crate::observer::Observer<f64>,
            ) -> Result<$crate::nonlinear_solver::SolveReport<f64>, $crate::error::SolverError>
            {
                let $solver = self;
                let newton: &mut $crate::newton::Newton = $newton;
                newton.solve(problem, u, observer)
            }
        }
    };
}
pub(crate) use solve_with_newton;

/// [`Newton`]'s problem for the driver: the Jacobian refilled, refactorised and solved by the
/// linear backend at every step, every iterate reported to the observer.
struct SparseSystem<'a, P: ?Sized> {
    problem: &'a P,
    linear: &'a mut (dyn LinearSolver<f64> + Send),
    values: Vec<f64>,
    observer: &'a mut dyn Observer<f64>,
    stage: SolveStage,
}

impl<P: Jacobian<f64> + ?Sized> NewtonSystem for SparseSystem<'_, P> {
    type Error = SolverError;

    fn residual(&mut self, u: &[f64], r: &mut [f64]) -> Result<(), SolverError> {
        self.problem
            .residual(u, r)
            .map_err(|e| SolverError::problem("residual", e))
    }

    fn direction(
        &mut self,
        at: &NewtonIterate<'_>,
        du: &mut [f64],
    ) -> Result<NewtonDirection, SolverError> {
        self.values.fill(0.0);
        self.problem
            .jacobian(at.u, &mut self.values)
            .map_err(|e| SolverError::problem("jacobian", e))?;
        if let Some(index) = first_non_finite(&self.values) {
            return Err(SolverError::NonFinite {
                quantity: "jacobian",
                index,
                iteration: Some(at.iteration + 1),
            });
        }
        self.linear.factor(&self.values)?;
        for (d, ri) in du.iter_mut().zip(at.r) {
            *d = -ri;
        }
        self.linear.solve_in_place_observed(du, self.observer)?;
        Ok(NewtonDirection {
            factorisations: 1,
            linear_iterations: self.linear.last_iterations().unwrap_or(0),
            ..NewtonDirection::default()
        })
    }

    fn accepted(&mut self, at: &NewtonIterate<'_>) -> Result<Flow, SolverError> {
        self.observer
            .iteration(&Progress::new(self.stage, at.iteration, at.norm, at.step));
        Ok(if at.iteration > 0 && self.observer.interrupted() {
            Flow::Interrupt
        } else {
            Flow::Continue
        })
    }
}

impl LineSearch {
    /// The driver's step control for this line search: Armijo on `|r|_2^2`, failing below
    /// `min_step`.
    pub(crate) fn step_control(self) -> StepControl {
        match self {
            Self::None => StepControl::Full,
            Self::Backtracking { armijo, min_step } => StepControl::Backtracking {
                merit: Merit::SquaredNorm { armijo },
                min_step,
                short_step: ShortStep::Fail,
            },
        }
    }
}

impl From<NewtonFailure<SolverError>> for SolverError {
    /// The driver's failure as a solver error: a failed line search is
    /// [`SolverError::Stagnated`] (or [`SolverError::NonFinite`] when its last trial residual
    /// was not finite).
    fn from(failure: NewtonFailure<SolverError>) -> Self {
        match failure {
            NewtonFailure::Problem(e) => e,
            NewtonFailure::NotConverged {
                iterations,
                residual,
            } => SolverError::NotConverged {
                iterations,
                residual,
            },
            NewtonFailure::LineSearch {
                iterations,
                residual,
                non_finite,
            } => match non_finite {
                Some(index) => SolverError::NonFinite {
                    quantity: "residual",
                    index,
                    iteration: Some(iterations + 1),
                },
                None => SolverError::Stagnated {
                    iterations,
                    residual,
                },
            },
            NewtonFailure::Stagnated {
                iterations,
                residual,
            } => SolverError::Stagnated {
                iterations,
                residual,
            },
            NewtonFailure::Diverged {
                iteration,
                residual,
            } => SolverError::Diverged {
                iteration,
                residual,
            },
            NewtonFailure::Interrupted { iteration } => SolverError::Interrupted { iteration },
            NewtonFailure::NonFinite {
                quantity,
                index,
                iteration,
            } => SolverError::NonFinite {
                quantity,
                index,
                iteration: Some(iteration),
            },
        }
    }
}

impl NonlinearSolver<f64> for Newton {
    fn solve<P: Jacobian<f64> + ?Sized>(
        &mut self,
        problem: &P,
        u: &mut [f64],
        observer: &mut dyn Observer<f64>,
    ) -> Result<SolveReport<f64>, SolverError> {
        let params = self.params;
        let pattern = problem.pattern();
        let n = u.len();
        if !pattern.is_square() {
            return Err(SolverError::NotSquare {
                nrows: pattern.nrows(),
                ncols: pattern.ncols(),
            });
        }
        if pattern.ncols() != n {
            return Err(SolverError::DimensionMismatch {
                quantity: "u",
                expected: pattern.ncols(),
                found: n,
            });
        }
        if let Some(index) = first_non_finite(u) {
            return Err(SolverError::NonFinite {
                quantity: "initial guess",
                index,
                iteration: Some(0),
            });
        }
        if self.analysed.as_ref() != Some(pattern) {
            self.analysed = None;
            self.linear.analyse(pattern)?;
            self.analysed = Some(pattern.clone());
        }
        let policy = params.policy();
        let mut system = SparseSystem {
            problem,
            linear: self.linear.as_mut(),
            values: vec![0.0; pattern.nnz()],
            observer,
            stage: self.stage,
        };
        Ok(newton_drive(&mut system, u, &policy)?.into())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validate_rejects_each_bad_field() {
        NewtonParams::default().validate().unwrap();
        let d = NewtonParams::default();
        let field = |p: NewtonParams| match p.validate() {
            Err(SolverError::InvalidParameter { field, .. }) => field,
            other => panic!("expected InvalidParameter, got {other:?}"),
        };
        assert_eq!(
            field(NewtonParams {
                max_iterations: 0,
                ..d
            }),
            "max_iterations"
        );
        assert_eq!(
            field(NewtonParams {
                relative_tolerance: 1.0,
                ..d
            }),
            "relative_tolerance"
        );
        assert_eq!(
            field(NewtonParams {
                absolute_tolerance: 0.0,
                relative_tolerance: 0.0,
                ..d
            }),
            "absolute_tolerance"
        );
        assert_eq!(
            field(NewtonParams {
                divergence_limit: 0.5,
                ..d
            }),
            "divergence_limit"
        );
        assert_eq!(
            field(NewtonParams {
                line_search: LineSearch::Backtracking {
                    armijo: 0.7,
                    min_step: 1e-3
                },
                ..d
            }),
            "line_search.armijo"
        );
    }

    #[test]
    fn params_round_trip_through_json_with_defaults() {
        let p: NewtonParams =
            serde_json::from_str(r#"{"max_iterations": 7, "linear": "gauss-seidel"}"#).unwrap();
        assert_eq!(p.max_iterations, 7);
        assert_eq!(p.linear, LinearBackend::GAUSS_SEIDEL);
        assert_eq!(p.line_search, LineSearch::default());
        let json = serde_json::to_string(&p).unwrap();
        assert_eq!(serde_json::from_str::<NewtonParams>(&json).unwrap(), p);
        let none: LineSearch = serde_json::from_str(r#""none""#).unwrap();
        assert_eq!(none, LineSearch::None);
    }
}
