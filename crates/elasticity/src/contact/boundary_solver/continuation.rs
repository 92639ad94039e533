//! Continuations for hard loads: in the slip scale (the law sees `beta u`) and in the loads.

use capstan_friction::FrictionLaw;
use capstan_solvers::{Observer, Progress, SolveStage};

use super::{BoundarySolver, Failure};
use crate::contact::error::ContactError;
use crate::contact::loads::EndLoads;
use crate::contact::operator::ContactOperator;

impl<D: ContactOperator, L: FrictionLaw<f64>> BoundarySolver<'_, D, L> {
    /// Continuation in the slip scale `beta` (the law sees `beta u`; for regularised Coulomb
    /// this is `eps / beta`) from the stuck state: `beta_0 = min(1e-3, eps / (10 U))`, where `U`
    /// is the largest physical tangential displacement of the spring-held linear solution
    /// (`s = 0`), so that every contact point starts on the smooth branch of the law
    /// (`|beta u| < eps`: all stick) however small `eps` is; then decade steps (halved on
    /// failure) up to `beta = 1`, each from the previous solution.
    /// `Ok((iterations, steps, s))` or the failure with the iterations spent in all. Every
    /// converged step is reported to `observer` ([`SolveStage::Continuation`], the step in
    /// `log10 beta` as its step length).
    pub(super) fn slip_homotopy(
        &self,
        loads: EndLoads,
        observer: &mut dyn Observer<f64>,
    ) -> Result<(usize, usize, Vec<f64>), Failure> {
        let mut s = self.stuck_unknowns(loads);
        let (x0, _) = self.loaded_base(loads);
        let scale = x0.iter().enumerate().fold(0.0f64, |a, (k, x)| {
            a.max((self.model.active_node(k).sqrt_g22 * x).abs())
        });
        let start = if scale > 0.0 {
            (0.1 * self.model.slip_threshold() / scale).min(1e-3)
        } else {
            1e-3
        };
        let mut log_beta = start.log10();
        let mut step = 1.0f64;
        let mut iterations = 0;
        let mut steps = 0;
        let mut first = true;
        loop {
            steps += 1;
            if steps > self.settings.max_continuation_steps {
                return Err(Failure::NotConverged(iterations, f64::INFINITY));
            }
            let target = if first {
                log_beta
            } else {
                (log_beta + step).min(0.0)
            };
            let mut trial = s.clone();
            match self.newton(10f64.powf(target), loads, &mut trial, observer) {
                Ok((it, residual)) => {
                    iterations += it;
                    let taken = if first { 0.0 } else { target - log_beta };
                    observer.iteration(&Progress::new(
                        SolveStage::Continuation,
                        steps,
                        residual,
                        taken,
                    ));
                    s = trial;
                    log_beta = target;
                    first = false;
                    if log_beta >= 0.0 {
                        return Ok((iterations, steps, s));
                    }
                    step = (step * 1.5).min(1.0);
                }
                Err(Failure::Interrupted(it)) => {
                    return Err(Failure::Interrupted(iterations + it));
                }
                Err(Failure::NotConverged(it, r)) => {
                    iterations += it;
                    if first || step * 0.5 < 1e-3 {
                        return Err(Failure::NotConverged(iterations, r));
                    }
                    step *= 0.5;
                }
            }
        }
    }

    /// Continuation in the loads, `lambda = 0 -> 1` (step x1.5 after success, /2 after
    /// failure), each step from the previous solution scaled; every converged step is
    /// reported to `observer` ([`SolveStage::Continuation`], the load step as step length).
    ///
    /// # Errors
    /// [`ContactError::NotConverged`] below the smallest load step or past the step budget;
    /// [`ContactError::Interrupted`] when the observer stops it.
    pub(super) fn continuation(
        &self,
        loads: EndLoads,
        s: &mut [f64],
        observer: &mut dyn Observer<f64>,
    ) -> Result<(usize, usize), ContactError> {
        let m = s.len();
        let mut lambda = 0.0;
        let mut current = vec![0.0; m];
        let mut step = self.settings.initial_load_step;
        let mut iterations = 0;
        let mut steps = 0;
        let mut last_residual = f64::INFINITY;
        while lambda < 1.0 {
            if steps >= self.settings.max_continuation_steps {
                break;
            }
            steps += 1;
            let next = (lambda + step).min(1.0);
            let mut trial: Vec<f64> = if lambda > 0.0 {
                current.iter().map(|x| x * next / lambda).collect()
            } else {
                self.stuck_unknowns(loads.scaled(next))
            };
            match self.newton(1.0, loads.scaled(next), &mut trial, observer) {
                Ok((it, residual)) => {
                    iterations += it;
                    observer.iteration(&Progress::new(
                        SolveStage::Continuation,
                        steps,
                        residual,
                        next - lambda,
                    ));
                    lambda = next;
                    current = trial;
                    step = (step * 1.5).min(1.0);
                }
                Err(Failure::Interrupted(it)) => {
                    return Err(ContactError::Interrupted {
                        iterations: iterations + it,
                    });
                }
                Err(Failure::NotConverged(it, r)) => {
                    iterations += it;
                    last_residual = r;
                    step *= 0.5;
                    if step < self.settings.min_load_step {
                        break;
                    }
                }
            }
        }
        if lambda < 1.0 {
            return Err(ContactError::NotConverged {
                iterations,
                residual: last_residual,
                load_factor: lambda,
            });
        }
        s.copy_from_slice(&current);
        Ok((iterations, steps))
    }
}
