//! Progress reporting of the nonlinear solvers.

use crate::scalar::SolverScalar;

/// Receives the progress of a nonlinear solve; the solvers never print.
///
/// `iteration` is called once with `iteration = 0`, the initial residual norm and step length
/// `0`, then after every accepted step with the new residual norm `|r(u_k)|_2` and the step
/// length `alpha` taken along the Newton direction (1 for a full step).
///
/// Closures `FnMut(usize, F, F)` are observers.
///
/// # Example
/// ```
/// use capstan_solvers::Observer;
/// let mut seen = Vec::new();
/// let mut obs = |k: usize, r: f64, _alpha: f64| seen.push((k, r));
/// obs.iteration(0, 1.0, 0.0);
/// assert_eq!(seen, vec![(0, 1.0)]);
/// ```
pub trait Observer<F: SolverScalar> {
    /// One nonlinear iteration has been accepted.
    fn iteration(&mut self, iteration: usize, residual_norm: F, step_length: F);
}

/// An observer that ignores everything.
#[derive(Clone, Copy, Debug, Default)]
pub struct SilentObserver;

impl<F: SolverScalar> Observer<F> for SilentObserver {
    fn iteration(&mut self, _iteration: usize, _residual_norm: F, _step_length: F) {}
}

impl<F: SolverScalar, C: FnMut(usize, F, F)> Observer<F> for C {
    fn iteration(&mut self, iteration: usize, residual_norm: F, step_length: F) {
        self(iteration, residual_norm, step_length)
    }
}
