//! The one damped Newton loop of capstan: generic over the problem (residual, Newton
//! direction, trial projection, progress) and over its policies (residual norm, merit and
//! line search, stall handling, iteration budget, divergence), so that every Newton method
//! of the workspace (here: sparse Newton and Jacobi–Newton, inexact Newton–Krylov; the crates
//! above run their own Newton methods through it, see docs/architecture.md) is this loop with
//! its own settings.

use crate::nonlinear_solver::SolveReport;
use crate::scalar::{first_non_finite, norm2};

/// How the driver measures a residual vector `r` (its convergence test, progress and
/// divergence test all use this value).
///
/// # Math
/// ```text
/// Two:  |r|_2   = sqrt(sum_i r_i^2)       (scaled against overflow and underflow)
/// Max:  |r|_inf = max_i |r_i|             (entries that are NaN are skipped; inf if not finite)
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ResidualNorm {
    /// The Euclidean norm.
    Two,
    /// The maximum norm.
    Max,
}

impl ResidualNorm {
    /// The norm of `r`.
    pub fn of(self, r: &[f64]) -> f64 {
        match self {
            Self::Two => norm2(r),
            Self::Max => {
                let m = r.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                if m.is_finite() { m } else { f64::INFINITY }
            }
        }
    }
}

/// The sufficient-decrease test of the backtracking line search: the trial point
/// `u + alpha d` is accepted when its merit has decreased enough against the current one.
/// `c = armijo * s`, `s` the step's scale ([`NewtonDirection::armijo_scale`], 1 for an exact
/// step).
///
/// # Math
/// ```text
/// SquaredNorm:   |r(u + alpha d)|^2 <= (1 - 2 c alpha) |r(u)|^2      (|.| the driver's norm)
/// SumOfSquares:  phi(alpha) <= (1 - c alpha) phi(0),  phi = sum_i r_i^2 finite
/// Norm:          |r(u + alpha d)|   <  (1 - c alpha) |r(u)|           (strict)
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Merit {
    /// Armijo on the squared residual norm (`phi'(0) = -2 phi(0)` for an exact Newton step).
    SquaredNorm {
        /// The sufficient-decrease constant `c` in `(0, 1/2)`.
        armijo: f64,
    },
    /// Armijo on the sum of squares of the residual, computed apart from the driver's norm.
    SumOfSquares {
        /// The sufficient-decrease constant `c` in `(0, 1)`.
        armijo: f64,
    },
    /// A strict decrease of the residual norm by `c alpha` relative.
    Norm {
        /// The sufficient-decrease constant `c` in `(0, 1)`.
        armijo: f64,
    },
}

/// What the line search does when the step fraction falls below its floor without a
/// sufficient decrease.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShortStep {
    /// Stop with [`NewtonFailure::LineSearch`] once halving takes `alpha` below the floor
    /// (the fraction below the floor is never evaluated).
    Fail,
    /// Take the trial point at the first fraction below the floor whatever its merit.
    Take,
}

/// Step-length control along the Newton direction `d`.
///
/// # Math
/// ```text
/// alpha = alpha0, alpha0/2, alpha0/4, ...  (alpha0 = NewtonDirection::max_step)
/// until the merit test holds; floor: alpha < min_step alpha0
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StepControl {
    /// Always the full step; a trial residual that is not finite is
    /// [`NewtonFailure::NonFinite`].
    Full,
    /// Backtracking by halving.
    Backtracking {
        /// The sufficient-decrease test.
        merit: Merit,
        /// The floor of `alpha / alpha0`, in `(0, 1)`.
        min_step: f64,
        /// What happens at the floor.
        short_step: ShortStep,
    },
}

/// The policies of [`newton_drive`].
///
/// # Math
/// ```text
/// target    = max(absolute_tolerance, relative_tolerance |r(u_0)|, floor(u_k))
/// converged when |r(u_k)| <= target                      (|.| = norm; floor: NewtonSystem::floor)
/// diverged  when |r(u_k)| >  divergence_limit max(|r(u_0)|, absolute_tolerance)
/// stagnated when |r(u_k)| >  target and alpha |d|_2 <= eps_mach |u_k|_2   (step_stagnation)
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonPolicy {
    /// Newton steps allowed (at least 1); [`NewtonFailure::NotConverged`] when spent.
    pub max_iterations: usize,
    /// Absolute residual tolerance (`>= 0`).
    pub absolute_tolerance: f64,
    /// Tolerance relative to the first residual (`>= 0`).
    pub relative_tolerance: f64,
    /// The residual norm.
    pub norm: ResidualNorm,
    /// The line search.
    pub step: StepControl,
    /// Residual growth factor that counts as divergence (`None`: never).
    pub divergence_limit: Option<f64>,
    /// Whether a step below the rounding of `u` is [`NewtonFailure::Stagnated`].
    pub step_stagnation: bool,
    /// Whether a non-finite initial guess or initial residual is [`NewtonFailure::NonFinite`]
    /// (otherwise the problem's own checks and the norm decide).
    pub check_finite: bool,
}

/// One point of the iteration, as the problem's hooks see it.
#[derive(Clone, Copy, Debug)]
pub struct NewtonIterate<'a> {
    /// Accepted steps so far (0 at the start).
    pub iteration: usize,
    /// The iterate `u_k`.
    pub u: &'a [f64],
    /// Its residual `r(u_k)`.
    pub r: &'a [f64],
    /// `|r(u_k)|` in the driver's norm.
    pub norm: f64,
    /// The step fraction `alpha` that led to it (0 at the start).
    pub step: f64,
}

/// What [`NewtonSystem::direction`] found besides the direction itself.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonDirection {
    /// The first step fraction tried, `alpha0` in `(0, 1]` (1: the full Newton step).
    pub max_step: f64,
    /// The factor on the line search's Armijo constant (1 for an exact step; `1 - eta^2` for
    /// an inexact one solved to relative residual `eta`).
    pub armijo_scale: f64,
    /// Factorisations (or preconditioner set-ups) the direction took.
    pub factorisations: usize,
    /// Inner linear iterations it took.
    pub linear_iterations: usize,
}

impl Default for NewtonDirection {
    fn default() -> Self {
        Self {
            max_step: 1.0,
            armijo_scale: 1.0,
            factorisations: 0,
            linear_iterations: 0,
        }
    }
}

/// Whether the solve goes on after an accepted iterate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flow {
    /// Go on.
    Continue,
    /// Stop with [`NewtonFailure::Interrupted`].
    Interrupt,
}

/// A problem `r(u) = 0` for [`newton_drive`].
pub trait NewtonSystem {
    /// The problem's own error.
    type Error;

    /// Overwrites `r` with `r(u)`.
    ///
    /// # Errors
    /// Any failure of the evaluation ([`NewtonFailure::Problem`]).
    fn residual(&mut self, u: &[f64], r: &mut [f64]) -> Result<(), Self::Error>;

    /// Overwrites `d` with the Newton direction at `at` (`J(u) d = -r`, exactly or not).
    ///
    /// # Errors
    /// Any failure of the Jacobian or the linear solve ([`NewtonFailure::Problem`]).
    fn direction(
        &mut self,
        at: &NewtonIterate<'_>,
        d: &mut [f64],
    ) -> Result<NewtonDirection, Self::Error>;

    /// Moves a trial point before its residual is evaluated (e.g. onto a constraint);
    /// nothing by default.
    fn project(&mut self, _trial: &mut [f64]) {}

    /// A residual level below which no step can go (the rounding floor of the evaluation)
    /// that counts as converged; 0 by default.
    fn floor(&self, _u: &[f64]) -> f64 {
        0.0
    }

    /// Called with the start (`iteration` 0) and every accepted iterate, before its
    /// convergence test: reports progress, may stop the solve, and may refuse to go on with
    /// the problem's own error (e.g. a stall it detects).
    ///
    /// # Errors
    /// The problem's own error ([`NewtonFailure::Problem`]).
    fn accepted(&mut self, _at: &NewtonIterate<'_>) -> Result<Flow, Self::Error> {
        Ok(Flow::Continue)
    }

    /// The global index of this process's first row when `u`, `r` and the direction are one
    /// process's rows of vectors distributed over several processes (a distributed Newton:
    /// [`crate::DistributedNewton`]); `None` (the default) for whole vectors. When set, the
    /// driver takes every norm, sum and non-finite test over all processes through
    /// [`NewtonSystem::reduce`], so that every process takes the same decisions (line search,
    /// convergence, failure) and reports the same global index of a non-finite entry.
    fn row_offset(&self) -> Option<usize> {
        None
    }

    /// `local` combined over all processes: their sum or maximum (a NaN on any process gives
    /// NaN). Called only when [`NewtonSystem::row_offset`] is set; collective (every process
    /// calls it in the same order). The default is `local` itself (one process).
    ///
    /// # Errors
    /// The communication's failure.
    fn reduce(&mut self, local: f64, _op: Reduction) -> Result<f64, Self::Error> {
        Ok(local)
    }
}

/// How [`NewtonSystem::reduce`] combines one value per process.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reduction {
    /// The sum over the processes.
    Sum,
    /// The maximum over the processes (NaN if any is NaN).
    Max,
}

/// `|x|` in `norm` over all processes: the driver's own norm for whole vectors; for one
/// process's rows (`distributed`), the same norm of the whole vector by reductions.
///
/// # Math
/// ```text
/// Two:  s = max_p max_i |x_i|,  |x|_2 = s sqrt(sum_p sum_i (x_i / s)^2)   (NaN if any is; s if 0 or inf)
/// Max:  max_p max_i |x_i|                                                 (inf if not finite)
/// ```
fn norm_over<P: NewtonSystem + ?Sized>(
    problem: &mut P,
    norm: ResidualNorm,
    x: &[f64],
    distributed: bool,
) -> Result<f64, P::Error> {
    if !distributed {
        return Ok(norm.of(x));
    }
    let local_max = if x.iter().any(|v| v.is_nan()) {
        f64::NAN
    } else {
        x.iter().fold(0.0f64, |m, v| m.max(v.abs()))
    };
    let scale = problem.reduce(local_max, Reduction::Max)?;
    match norm {
        ResidualNorm::Max => Ok(if scale.is_finite() {
            scale
        } else {
            f64::INFINITY
        }),
        ResidualNorm::Two => {
            if scale == 0.0 || !scale.is_finite() {
                return Ok(scale);
            }
            let inv = 1.0 / scale;
            let local = x.iter().fold(0.0, |s, v| s + (v * inv) * (v * inv));
            Ok(scale * problem.reduce(local, Reduction::Sum)?.sqrt())
        }
    }
}

/// The global index of the first non-finite entry of `x` over all processes (`offset`: this
/// process's first row when `x` is its rows; `None`: `x` is whole).
fn first_non_finite_over<P: NewtonSystem + ?Sized>(
    problem: &mut P,
    x: &[f64],
    offset: Option<usize>,
) -> Result<Option<usize>, P::Error> {
    let Some(first) = offset else {
        return Ok(first_non_finite(x));
    };
    // the smallest global index as the maximum of its negative (exact below 2^53)
    let local = first_non_finite(x).map_or(f64::NEG_INFINITY, |i| -((first + i) as f64));
    let global = problem.reduce(local, Reduction::Max)?;
    Ok((global > f64::NEG_INFINITY).then(|| (-global) as usize))
}

/// `sum_i x_i^2` over all processes.
fn sum_of_squares_over<P: NewtonSystem + ?Sized>(
    problem: &mut P,
    x: &[f64],
    distributed: bool,
) -> Result<f64, P::Error> {
    let local = x.iter().map(|v| v * v).sum::<f64>();
    if distributed {
        problem.reduce(local, Reduction::Sum)
    } else {
        Ok(local)
    }
}

/// Why [`newton_drive`] stopped without converging; `u` holds the last accepted iterate.
#[derive(Clone, Debug, PartialEq)]
pub enum NewtonFailure<E> {
    /// The problem's own error (evaluation, direction, or a hook's refusal).
    Problem(E),
    /// The iteration budget is spent.
    NotConverged {
        /// Steps taken.
        iterations: usize,
        /// The last residual norm.
        residual: f64,
    },
    /// The line search found no sufficient decrease above its floor ([`ShortStep::Fail`]).
    LineSearch {
        /// Steps taken before the failed one.
        iterations: usize,
        /// The residual norm at the last accepted iterate.
        residual: f64,
        /// The first non-finite entry of the last trial residual, if any.
        non_finite: Option<usize>,
    },
    /// The accepted step is below the rounding of `u` ([`NewtonPolicy::step_stagnation`]).
    Stagnated {
        /// Steps taken.
        iterations: usize,
        /// The last residual norm.
        residual: f64,
    },
    /// The residual grew beyond [`NewtonPolicy::divergence_limit`].
    Diverged {
        /// The step at which it did.
        iteration: usize,
        /// Its residual norm.
        residual: f64,
    },
    /// [`NewtonSystem::accepted`] asked to stop.
    Interrupted {
        /// The iterate at which it did.
        iteration: usize,
    },
    /// A non-finite initial guess, residual or step.
    NonFinite {
        /// `"initial guess"`, `"residual"` or `"step"`.
        quantity: &'static str,
        /// Its first non-finite entry.
        index: usize,
        /// The step it belongs to.
        iteration: usize,
    },
}

/// What a converged [`newton_drive`] did.
#[derive(Clone, Debug, PartialEq)]
pub struct NewtonDriven {
    /// Steps taken.
    pub iterations: usize,
    /// `|r(u_k)|` for `k = 0 ..= iterations`.
    pub residuals: Vec<f64>,
    /// Factorisations summed over the directions.
    pub factorisations: usize,
    /// Inner linear iterations summed over the directions.
    pub linear_iterations: usize,
}

impl From<NewtonDriven> for SolveReport<f64> {
    fn from(done: NewtonDriven) -> Self {
        SolveReport::new(
            done.iterations,
            done.residuals,
            done.factorisations,
            done.linear_iterations,
        )
    }
}

/// Damped Newton on `problem` from `u` (which holds the solution on success and the last
/// accepted iterate on failure) with the policies of `policy`.
///
/// # Math
/// ```text
/// k = 0, 1, ...:  accepted(u_k); stop if |r(u_k)| <= target; fail if k = max_iterations
///                 d_k = direction(u_k)                        (J(u_k) d_k = -r(u_k))
///                 u_{k+1} = project(u_k + alpha_k d_k)        (alpha_k: StepControl)
/// ```
/// Near a root with a nonsingular Jacobian and exact directions the full step is accepted
/// and convergence is quadratic.
///
/// # Errors
/// See [`NewtonFailure`].
pub fn newton_drive<P: NewtonSystem + ?Sized>(
    problem: &mut P,
    u: &mut [f64],
    policy: &NewtonPolicy,
) -> Result<NewtonDriven, NewtonFailure<P::Error>> {
    use NewtonFailure as F;
    let n = u.len();
    let offset = problem.row_offset();
    let distributed = offset.is_some();
    if policy.check_finite
        && let Some(index) = first_non_finite_over(problem, u, offset).map_err(F::Problem)?
    {
        return Err(F::NonFinite {
            quantity: "initial guess",
            index,
            iteration: 0,
        });
    }
    let mut r = vec![0.0; n];
    problem.residual(u, &mut r).map_err(F::Problem)?;
    if policy.check_finite
        && let Some(index) = first_non_finite_over(problem, &r, offset).map_err(F::Problem)?
    {
        return Err(F::NonFinite {
            quantity: "residual",
            index,
            iteration: 0,
        });
    }
    let mut norm = norm_over(problem, policy.norm, &r, distributed).map_err(F::Problem)?;
    let target = policy
        .absolute_tolerance
        .max(policy.relative_tolerance * norm);
    let divergence = policy
        .divergence_limit
        .map(|limit| limit * norm.max(policy.absolute_tolerance));
    let mut done = NewtonDriven {
        iterations: 0,
        residuals: vec![norm],
        factorisations: 0,
        linear_iterations: 0,
    };
    let mut d = vec![0.0; n];
    let mut trial = vec![0.0; n];
    let mut r_trial = vec![0.0; n];
    let mut alpha = 0.0;
    let mut step_norm = 0.0;
    loop {
        let k = done.iterations;
        let at = NewtonIterate {
            iteration: k,
            u,
            r: &r,
            norm,
            step: alpha,
        };
        if problem.accepted(&at).map_err(F::Problem)? == Flow::Interrupt {
            return Err(F::Interrupted { iteration: k });
        }
        if k > 0 {
            if divergence.is_some_and(|limit| norm > limit) {
                return Err(F::Diverged {
                    iteration: k,
                    residual: norm,
                });
            }
            if policy.step_stagnation
                && norm > target
                && step_norm
                    <= f64::EPSILON
                        * norm_over(problem, ResidualNorm::Two, u, distributed)
                            .map_err(F::Problem)?
            {
                return Err(F::Stagnated {
                    iterations: k,
                    residual: norm,
                });
            }
        }
        if norm <= target.max(problem.floor(u)) {
            return Ok(done);
        }
        if k == policy.max_iterations {
            return Err(F::NotConverged {
                iterations: k,
                residual: norm,
            });
        }
        let at = NewtonIterate {
            iteration: k,
            u,
            r: &r,
            norm,
            step: alpha,
        };
        let found = problem.direction(&at, &mut d).map_err(F::Problem)?;
        done.factorisations += found.factorisations;
        done.linear_iterations += found.linear_iterations;
        if let Some(index) = first_non_finite_over(problem, &d, offset).map_err(F::Problem)? {
            return Err(F::NonFinite {
                quantity: "step",
                index,
                iteration: k + 1,
            });
        }
        let alpha0 = found.max_step;
        alpha = alpha0;
        let phi0 = match policy.step {
            StepControl::Backtracking {
                merit: Merit::SumOfSquares { .. },
                ..
            } => sum_of_squares_over(problem, &r, distributed).map_err(F::Problem)?,
            _ => 0.0,
        };
        let trial_norm = loop {
            for ((t, ui), di) in trial.iter_mut().zip(u.iter()).zip(&d) {
                *t = ui + alpha * di;
            }
            problem.project(&mut trial);
            problem.residual(&trial, &mut r_trial).map_err(F::Problem)?;
            let value =
                norm_over(problem, policy.norm, &r_trial, distributed).map_err(F::Problem)?;
            let StepControl::Backtracking {
                merit,
                min_step,
                short_step,
            } = policy.step
            else {
                if let Some(index) =
                    first_non_finite_over(problem, &r_trial, offset).map_err(F::Problem)?
                {
                    return Err(F::NonFinite {
                        quantity: "residual",
                        index,
                        iteration: k + 1,
                    });
                }
                break value;
            };
            let sufficient = match merit {
                Merit::SquaredNorm { armijo } => {
                    let c = armijo * found.armijo_scale;
                    value * value <= (1.0 - 2.0 * c * alpha) * norm * norm
                }
                Merit::SumOfSquares { armijo } => {
                    let phi =
                        sum_of_squares_over(problem, &r_trial, distributed).map_err(F::Problem)?;
                    phi.is_finite() && phi <= (1.0 - armijo * found.armijo_scale * alpha) * phi0
                }
                Merit::Norm { armijo } => {
                    value < (1.0 - armijo * found.armijo_scale * alpha) * norm
                }
            };
            let floor = min_step * alpha0;
            if sufficient || (short_step == ShortStep::Take && alpha < floor) {
                break value;
            }
            alpha *= 0.5;
            if short_step == ShortStep::Fail && alpha < floor {
                return Err(F::LineSearch {
                    iterations: k,
                    residual: norm,
                    non_finite: first_non_finite_over(problem, &r_trial, offset)
                        .map_err(F::Problem)?,
                });
            }
        };
        if policy.step_stagnation {
            step_norm = alpha
                * norm_over(problem, ResidualNorm::Two, &d, distributed).map_err(F::Problem)?;
        }
        u.copy_from_slice(&trial);
        core::mem::swap(&mut r, &mut r_trial);
        norm = trial_norm;
        done.iterations = k + 1;
        done.residuals.push(norm);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `r_i(u) = u_i^3 + u_i - b_i` (diagonal, root `u_i = 1 + i/10` for `b_i` of that root),
    /// the exact Newton direction, every accepted iterate recorded; `stop_at` interrupts.
    struct Cubic {
        b: Vec<f64>,
        seen: Vec<(usize, f64, f64)>,
        stop_at: Option<usize>,
        floor: f64,
    }

    impl Cubic {
        fn new(n: usize) -> Self {
            let b = (0..n)
                .map(|i| {
                    let x = 1.0 + i as f64 / 10.0;
                    x * x * x + x
                })
                .collect();
            Self {
                b,
                seen: vec![],
                stop_at: None,
                floor: 0.0,
            }
        }
    }

    impl NewtonSystem for Cubic {
        type Error = &'static str;
        fn residual(&mut self, u: &[f64], r: &mut [f64]) -> Result<(), &'static str> {
            for ((ri, ui), bi) in r.iter_mut().zip(u).zip(&self.b) {
                *ri = ui * ui * ui + ui - bi;
            }
            Ok(())
        }
        fn direction(
            &mut self,
            at: &NewtonIterate<'_>,
            d: &mut [f64],
        ) -> Result<NewtonDirection, &'static str> {
            for ((di, ui), ri) in d.iter_mut().zip(at.u).zip(at.r) {
                *di = -ri / (3.0 * ui * ui + 1.0);
            }
            Ok(NewtonDirection {
                factorisations: 1,
                ..NewtonDirection::default()
            })
        }
        fn floor(&self, _u: &[f64]) -> f64 {
            self.floor
        }
        fn accepted(&mut self, at: &NewtonIterate<'_>) -> Result<Flow, &'static str> {
            self.seen.push((at.iteration, at.norm, at.step));
            Ok(if self.stop_at == Some(at.iteration) {
                Flow::Interrupt
            } else {
                Flow::Continue
            })
        }
    }

    fn policy(norm: ResidualNorm, merit: Merit, short_step: ShortStep) -> NewtonPolicy {
        NewtonPolicy {
            max_iterations: 50,
            absolute_tolerance: 1e-13,
            relative_tolerance: 0.0,
            norm,
            step: StepControl::Backtracking {
                merit,
                min_step: 1e-10,
                short_step,
            },
            divergence_limit: Some(1e8),
            step_stagnation: true,
            check_finite: true,
        }
    }

    #[test]
    fn every_merit_and_norm_reaches_the_exact_root_at_quadratic_order() {
        for (norm, merit) in [
            (ResidualNorm::Two, Merit::SquaredNorm { armijo: 1e-4 }),
            (ResidualNorm::Max, Merit::SumOfSquares { armijo: 1e-4 }),
            (ResidualNorm::Max, Merit::Norm { armijo: 1e-4 }),
        ] {
            let mut problem = Cubic::new(8);
            let mut u = vec![3.0; 8];
            let done =
                newton_drive(&mut problem, &mut u, &policy(norm, merit, ShortStep::Fail)).unwrap();
            for (i, ui) in u.iter().enumerate() {
                assert!(
                    (ui - (1.0 + i as f64 / 10.0)).abs() < 1e-13,
                    "{merit:?} {ui}"
                );
            }
            assert_eq!(done.factorisations, done.iterations);
            assert_eq!(problem.seen.len(), done.iterations + 1);
            // observed order log(r_{k+1}/r_k) / log(r_k/r_{k-1}) over the last full steps
            let r = &done.residuals;
            let k = r.len() - 2;
            let order = (r[k + 1] / r[k]).ln() / (r[k] / r[k - 1]).ln();
            assert!(
                order > 1.8 || r[k + 1] < 1e-15,
                "{merit:?} order {order}: {r:?}"
            );
            assert!(
                (r[k] / r[k - 1]).ln() / (r[k - 1] / r[k - 2]).ln() > 1.8,
                "{r:?}"
            );
        }
    }

    #[test]
    fn budget_floor_interrupt_and_full_steps_follow_the_policy() {
        let mut problem = Cubic::new(4);
        let mut u = vec![3.0; 4];
        let tight = NewtonPolicy {
            max_iterations: 2,
            ..policy(
                ResidualNorm::Two,
                Merit::SquaredNorm { armijo: 1e-4 },
                ShortStep::Fail,
            )
        };
        assert!(matches!(
            newton_drive(&mut problem, &mut u, &tight),
            Err(NewtonFailure::NotConverged { iterations: 2, .. })
        ));
        // a floor above the start's residual: converged at once
        let mut floored = Cubic::new(4);
        floored.floor = 1e3;
        let mut u = vec![3.0; 4];
        assert_eq!(
            newton_drive(&mut floored, &mut u, &tight)
                .unwrap()
                .iterations,
            0
        );
        // an interrupt after the first step leaves u at that step
        let mut stopped = Cubic::new(4);
        stopped.stop_at = Some(1);
        let mut u = vec![3.0; 4];
        assert!(matches!(
            newton_drive(&mut stopped, &mut u, &tight),
            Err(NewtonFailure::Interrupted { iteration: 1 })
        ));
        assert!(u[0] < 3.0);
        // pure Newton takes every full step (step length 1 reported)
        let mut full = Cubic::new(4);
        let mut u = vec![3.0; 4];
        let pure = NewtonPolicy {
            step: StepControl::Full,
            ..tight
        };
        let pure = NewtonPolicy {
            max_iterations: 50,
            ..pure
        };
        newton_drive(&mut full, &mut u, &pure).unwrap();
        assert!(full.seen[1..].iter().all(|s| s.2 == 1.0));
        // a non-finite start is refused
        let mut u = vec![f64::NAN; 4];
        assert!(matches!(
            newton_drive(&mut Cubic::new(4), &mut u, &pure),
            Err(NewtonFailure::NonFinite {
                quantity: "initial guess",
                ..
            })
        ));
    }

    /// `r(u) = u^2 + 1`: no root; the direction `-r / 2u` overshoots the minimum of `|r|` at 0.
    struct NoRoot;

    impl NewtonSystem for NoRoot {
        type Error = ();
        fn residual(&mut self, u: &[f64], r: &mut [f64]) -> Result<(), ()> {
            r[0] = u[0] * u[0] + 1.0;
            Ok(())
        }
        fn direction(
            &mut self,
            at: &NewtonIterate<'_>,
            d: &mut [f64],
        ) -> Result<NewtonDirection, ()> {
            d[0] = -at.r[0] / (2.0 * at.u[0]);
            Ok(NewtonDirection::default())
        }
    }

    #[test]
    fn a_failed_line_search_fails_or_takes_the_short_step_as_told() {
        let fail = policy(
            ResidualNorm::Max,
            Merit::Norm { armijo: 1e-4 },
            ShortStep::Fail,
        );
        let mut u = vec![1e-3];
        match newton_drive(&mut NoRoot, &mut u, &fail) {
            Err(NewtonFailure::LineSearch {
                non_finite: None, ..
            }) => {}
            other => panic!("{other:?}"),
        }
        // taking short steps ends at the budget instead
        let take = NewtonPolicy {
            max_iterations: 5,
            step_stagnation: false,
            ..policy(
                ResidualNorm::Max,
                Merit::Norm { armijo: 1e-4 },
                ShortStep::Take,
            )
        };
        let mut u = vec![1e-3];
        assert!(matches!(
            newton_drive(&mut NoRoot, &mut u, &take),
            Err(NewtonFailure::NotConverged { iterations: 5, .. })
        ));
    }
}
