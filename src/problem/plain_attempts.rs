//! The plain solve of a 3-D body before a run-off ([`Problem::solve`]): when a failure is
//! followed by the run-off in the tension ratio, the watch that ends the plain Newton's futile
//! load continuation early ([`PlainAttempts`]), which failures the run-off may explain, and the
//! sparse-LU solver the run-off runs on after an iterative backend failed.

use capstan_elasticity::contact::{ContactError, ContactSettings, FullSystemSettings};
use capstan_elasticity::solvers::{LinearBackend, Observer, Progress, SolveStage, SolverError};
use capstan_geometry::Surface;

use super::builder::Problem;
use super::solver::{SolveMethod, Solver};

/// Newton solves the plain solve of a 3-D body may start, before a run-off follows, while no
/// load step has converged: the full load, then the load continuation's first steps at the
/// fractions `1/4, 1/8, ..., 1/4 2^-(PLAIN_ATTEMPTS - 2)` (`1/128` with 7).
///
/// Why: with no step converged every trial starts from the stuck start at its fraction `s`,
/// `v = s v_stuck(1)`, and elasticity, contact with zero gap and the loads are homogeneous of
/// degree 1 in `(v, loads)`; only the regularised friction law (its width `eps` against the
/// slips `s |u|`) and a gap are not, so the trial at `s` is the full problem with the width
/// `eps / s`: halving `s` only widens the regularisation. That helps where the small slips of
/// a stick zone are what Newton trips on, not past a fold. Measured (release, cone Q1): the
/// bilateral load continuations that converge (`3 x 20 x 3` at ratios 0.3 to 3.8, `6 x 40 x 5`
/// at 1.5) do so at the fractions 1/4 to 1/32 (the 2nd to 5th solve); on the unilateral cone
/// past its fold all 13 trials down to `1.2e-4` fail, each ending near half its starting
/// residual. The cut at `1/128` leaves two halvings below the latest converging trial
/// measured. It is a measured bound, not a proof: a continuation that would first converge
/// below `1/128` now goes to the run-off, which reaches the ratio if the path from 1 does.
pub(crate) const PLAIN_ATTEMPTS: usize = 7;

/// An observer around the plain solve before a run-off: it passes every event on, and stops
/// the solve (as an interrupt, which the load continuation returns at once) when a Newton
/// solve beyond the [`PLAIN_ATTEMPTS`]-th starts before any load step has converged. After a
/// converged load step it never stops the solve: the continuation is on its way.
pub(crate) struct PlainAttempts<'a> {
    /// The caller's observer (its interrupts are its own).
    inner: &'a mut dyn Observer<f64>,
    /// Newton solves started (iteration-0 events), `None` once a load step converged.
    attempts: Option<usize>,
    /// Newton iterations seen (events past iteration 0).
    pub iterations: usize,
    /// The residual of the last Newton event.
    pub residual: f64,
    /// Whether this watch stopped the solve.
    pub stopped: bool,
}

impl<'a> PlainAttempts<'a> {
    /// A watch around `inner`.
    pub fn new(inner: &'a mut dyn Observer<f64>) -> Self {
        Self {
            inner,
            attempts: Some(0),
            iterations: 0,
            residual: f64::INFINITY,
            stopped: false,
        }
    }

    /// The plain solve's failure when the watch stopped it: not converged at load factor 0,
    /// with the iterations and the last residual seen.
    pub fn failure(&self) -> ContactError {
        ContactError::NotConverged {
            iterations: self.iterations,
            residual: self.residual,
            load_factor: 0.0,
        }
    }
}

impl Observer<f64> for PlainAttempts<'_> {
    fn iteration(&mut self, progress: &Progress<f64>) {
        match progress.stage {
            SolveStage::Newton | SolveStage::JacobiNewton => {
                if progress.iteration == 0 {
                    self.attempts = self.attempts.map(|a| a + 1);
                } else {
                    self.iterations += 1;
                }
                self.residual = progress.residual_norm;
            }
            SolveStage::Continuation => self.attempts = None,
            _ => {}
        }
        self.inner.iteration(progress);
    }

    fn interrupted(&mut self) -> bool {
        if self.inner.interrupted() {
            return true;
        }
        if self.attempts.is_some_and(|a| a > PLAIN_ATTEMPTS) {
            self.stopped = true;
        }
        self.stopped
    }
}

impl<S: Surface<f64> + Clone + Send + Sync + 'static> Problem<S> {
    /// Whether a failed plain solve of this problem is followed by a run-off (3-D bodies on
    /// the full-system route): the loads pull at the near end (`tau0 > 0`) and the ratio is
    /// finite and not 1.
    pub(crate) fn runs_off(&self) -> bool {
        let ratio = self.loads.tension_ratio();
        self.loads.tau0 > 0.0 && ratio.is_finite() && ratio != 1.0
    }

    /// Whether the plain solve runs under [`PlainAttempts`]: a run-off follows a failure
    /// ([`Problem::runs_off`]) and `solver.min_load_step` is not below its default `1e-4` (a
    /// smaller one asks for the longer load continuation, which then runs in full).
    pub(crate) fn watches_plain_solve(&self) -> bool {
        self.runs_off()
            && self.solver.budgets.min_load_step >= ContactSettings::default().min_load_step
    }

    /// The settings of Newton with sparse LU for the run-off after `method`'s plain solve of a
    /// unilateral body failed: `None` when `method` is Newton with sparse LU (its own run-off
    /// is the run-off). The continuation's bordered solves sit next to a singular Jacobian
    /// (the fold), where Krylov and stationary iterations may fail or spend their budget
    /// (measured: the plain `multigrid` Newton on the unilateral cone `3 x 20 x 3` at ratio 2
    /// spends its 500 GMRES iterations), and a factorisation does not.
    pub(crate) fn run_off_lu_settings(&self, method: SolveMethod) -> Option<FullSystemSettings> {
        match method {
            SolveMethod::FullNewton(l) if l == LinearBackend::LU => None,
            _ => Some(
                Solver {
                    method: SolveMethod::FullNewton(LinearBackend::LU),
                    ..self.solver
                }
                .full_settings(),
            ),
        }
    }
}

/// Whether a plain solve's error is one a run-off may explain: not converged, or an iterative
/// backend's Krylov budget spent (next to a fold the Jacobian is near singular).
pub(crate) fn run_off_may_explain(e: &ContactError) -> bool {
    e.kind() == capstan_elasticity::contact::ContactErrorKind::NotConverged
        || matches!(e, ContactError::Solver(SolverError::BudgetSpent { .. }))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Records the events it hears and interrupts when told.
    #[derive(Default)]
    struct Inner {
        events: usize,
        stop: bool,
    }

    impl Observer<f64> for Inner {
        fn iteration(&mut self, _: &Progress<f64>) {
            self.events += 1;
        }
        fn interrupted(&mut self) -> bool {
            self.stop
        }
    }

    fn newton(iteration: usize) -> Progress<f64> {
        Progress::new(SolveStage::Newton, iteration, 0.5, 1.0)
    }

    /// `solves` Newton solves of 3 iterations each to `watch`; whether it stopped after each.
    fn run(watch: &mut PlainAttempts<'_>, solves: usize) -> Vec<bool> {
        (0..solves)
            .map(|_| {
                watch.iteration(&newton(0));
                (1..=3).any(|k| {
                    watch.iteration(&newton(k));
                    watch.interrupted()
                })
            })
            .collect()
    }

    #[test]
    fn the_watch_stops_the_solve_that_starts_after_the_seventh_and_passes_every_event_on() {
        let mut inner = Inner::default();
        let mut watch = PlainAttempts::new(&mut inner);
        let stopped = run(&mut watch, PLAIN_ATTEMPTS + 1);
        assert!(stopped[..PLAIN_ATTEMPTS].iter().all(|s| !s), "{stopped:?}");
        assert!(stopped[PLAIN_ATTEMPTS]);
        assert!(watch.stopped);
        // 3 iterations of each of the first 7, the 8th stopped at its first
        assert_eq!(watch.iterations, 3 * PLAIN_ATTEMPTS + 1);
        let ContactError::NotConverged { load_factor, .. } = watch.failure() else {
            panic!("{}", watch.failure())
        };
        assert_eq!(load_factor, 0.0);
        // the watch's borrow of `inner` ends here
        assert_eq!(inner.events, 4 * PLAIN_ATTEMPTS + 2);
    }

    #[test]
    fn after_a_converged_load_step_the_watch_never_stops_the_solve() {
        let mut inner = Inner::default();
        let mut watch = PlainAttempts::new(&mut inner);
        run(&mut watch, 3);
        watch.iteration(&Progress::new(SolveStage::Continuation, 3, 1e-12, 0.1));
        assert!(run(&mut watch, 3 * PLAIN_ATTEMPTS).iter().all(|s| !s));
        assert!(!watch.stopped);
    }

    #[test]
    fn the_callers_interrupt_is_its_own() {
        let mut inner = Inner {
            stop: true,
            ..Default::default()
        };
        let mut watch = PlainAttempts::new(&mut inner);
        watch.iteration(&newton(0));
        assert!(watch.interrupted());
        assert!(!watch.stopped);
    }
}
