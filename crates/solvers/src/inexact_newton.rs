//! Inexact Newton–Krylov: each Newton step solved by a Krylov method only as accurately as
//! the Eisenstat–Walker forcing term asks, with a backtracking line search and work budgets.

use crate::error::SolverError;
use crate::krylov::{KrylovParams, KrylovReport};
use crate::newton::LineSearch;
use crate::newton_driver::{
    Flow, NewtonDirection, NewtonIterate, NewtonPolicy, NewtonSystem, ResidualNorm, newton_drive,
};
use crate::nonlinear_solver::SolveReport;
use crate::observer::{Observer, Progress, SolveStage};

/// The setting that bounds the Krylov iterations summed over one inexact Newton solve.
pub const INEXACT_NEWTON_BUDGET_FIELD: &str = "solver.max_sweeps";

/// The Eisenstat–Walker forcing terms ("choice 2") with the usual safeguards.
///
/// # Math
/// With `|r_k|` the residual norm at Newton step `k`, the linear solve of step `k` is asked for
/// `|J_k d + r_k| <= eta_k |r_k|`:
/// ```text
/// eta_0 = eta_max
/// eta_k = gamma (|r_k| / |r_{k-1}|)^alpha                               (choice 2)
/// safeguard 1:  if gamma eta_{k-1}^alpha > 0.1:  eta_k = max(eta_k, gamma eta_{k-1}^alpha)
/// safeguard 2:  eta_k = min(eta_k, eta_max)
/// safeguard 3:  eta_k = max(eta_k, eta_min, 0.5 tol / |r_k|)    (no oversolving the last step)
/// ```
/// (Eisenstat and Walker, SIAM J. Sci. Comput. 17 (1996) 16-32; Kelley, Iterative methods
/// for linear and nonlinear equations, 1995, sec. 6.3). With `alpha = 2` the outer iteration
/// keeps Newton's quadratic convergence once `eta_k = O(|r_k|)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EisenstatWalker {
    /// `gamma` in `(0, 1]` (default 0.9).
    pub gamma: f64,
    /// `alpha` in `(1, 2]` (default 2).
    pub alpha: f64,
    /// `eta_max` in `(0, 1)` (default 0.9): the first and the loosest forcing term.
    pub eta_max: f64,
    /// `eta_min` in `[0, eta_max]` (default 1e-10): the tightest forcing term.
    pub eta_min: f64,
}

impl Default for EisenstatWalker {
    fn default() -> Self {
        Self {
            gamma: 0.9,
            alpha: 2.0,
            eta_max: 0.9,
            eta_min: 1e-10,
        }
    }
}

impl EisenstatWalker {
    /// Checks the ranges.
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] naming `forcing.gamma`, `forcing.alpha`,
    /// `forcing.eta_max` or `forcing.eta_min`.
    pub fn validate(&self) -> Result<(), SolverError> {
        let bad = |field, value, allowed| Err(SolverError::invalid(field, value, allowed));
        if !(self.gamma > 0.0 && self.gamma <= 1.0) {
            return bad("forcing.gamma", self.gamma, "(0, 1]");
        }
        if !(self.alpha > 1.0 && self.alpha <= 2.0) {
            return bad("forcing.alpha", self.alpha, "(1, 2]");
        }
        if !(self.eta_max > 0.0 && self.eta_max < 1.0) {
            return bad("forcing.eta_max", self.eta_max, "(0, 1)");
        }
        if !(self.eta_min >= 0.0 && self.eta_min <= self.eta_max) {
            return bad("forcing.eta_min", self.eta_min, "[0, forcing.eta_max]");
        }
        Ok(())
    }

    /// The forcing term of the step at residual norm `rn`, after a step whose residual norm
    /// was `previous` and forcing term `eta_previous` (`None` for the first step), for the
    /// absolute target `tolerance` of the outer iteration.
    pub fn next(&self, rn: f64, previous: Option<(f64, f64)>, tolerance: f64) -> f64 {
        let eta = match previous {
            None => self.eta_max,
            Some((r_prev, eta_prev)) => {
                let mut eta = self.gamma * (rn / r_prev).powf(self.alpha);
                let guard = self.gamma * eta_prev.powf(self.alpha);
                if guard > 0.1 {
                    eta = eta.max(guard);
                }
                eta.min(self.eta_max)
            }
        };
        let floor = if rn > 0.0 { 0.5 * tolerance / rn } else { 0.0 };
        eta.max(self.eta_min).max(floor.min(self.eta_max))
    }
}

/// Settings of [`inexact_newton`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InexactNewtonParams {
    /// Newton steps allowed (the outer budget).
    pub max_iterations: usize,
    /// Stop when `|r|_2 <= absolute_tolerance`.
    pub absolute_tolerance: f64,
    /// Krylov iterations summed over all steps (the inner budget; [`SolverError::BudgetSpent`]
    /// naming [`INEXACT_NEWTON_BUDGET_FIELD`] when spent).
    pub max_linear_iterations: usize,
    /// The Krylov settings of every step (`tolerance` is replaced by the forcing term,
    /// `max_iterations` by what is left of `max_linear_iterations` when smaller).
    pub krylov: KrylovParams,
    /// The forcing terms.
    pub forcing: EisenstatWalker,
    /// The line search on `|r|^2`.
    pub line_search: LineSearch,
    /// [`SolverError::Diverged`] when `|r|` exceeds this multiple of the first residual.
    pub divergence_limit: f64,
}

impl Default for InexactNewtonParams {
    fn default() -> Self {
        Self {
            max_iterations: 50,
            absolute_tolerance: 1e-10,
            max_linear_iterations: 20_000,
            krylov: KrylovParams::default(),
            forcing: EisenstatWalker::default(),
            line_search: LineSearch::default(),
            divergence_limit: 1e8,
        }
    }
}

/// The problem of [`inexact_newton`]: a residual and a Krylov solve with its Jacobian.
pub trait NewtonKrylovProblem {
    /// Overwrites `r` with `r(u)`.
    ///
    /// # Errors
    /// Any failure of the evaluation.
    fn residual(&mut self, u: &[f64], r: &mut [f64]) -> Result<(), SolverError>;

    /// Solves `J(u) d = b` from `d = 0` by a (preconditioned) Krylov method with `params`
    /// (`params.tolerance` the relative residual asked for), reporting its iterations to
    /// `observer`.
    ///
    /// # Errors
    /// The Krylov method's errors (a spent budget, a breakdown, a failed preconditioner).
    fn solve_step(
        &mut self,
        u: &[f64],
        b: &[f64],
        d: &mut [f64],
        params: &KrylovParams,
        observer: &mut dyn Observer<f64>,
    ) -> Result<KrylovReport, SolverError>;
}

/// Inexact Newton–Krylov from `u` (which holds the last accepted iterate on return).
///
/// # Math
/// ```text
/// step k:   solve J(u_k) d = -r(u_k)  to  |J d + r| <= eta_k |r|     (eta_k: EisenstatWalker)
///           u_{k+1} = u_k + a d,  a = 1, 1/2, ... until |r(u_{k+1})|^2 <= (1 - 2 c a) |r_k|^2
/// stop:     |r_k| <= absolute_tolerance
/// ```
/// Every accepted step goes to `observer` as a [`SolveStage::Newton`] event; the report's
/// `linear_iterations` is the Krylov total and `factorisations` the number of steps (one
/// preconditioner set-up each).
///
/// # Errors
/// [`SolverError::NotConverged`] after `max_iterations` steps; [`SolverError::BudgetSpent`]
/// naming [`INEXACT_NEWTON_BUDGET_FIELD`] when the Krylov total reaches
/// `max_linear_iterations`; [`SolverError::Stagnated`] when the line search fails;
/// [`SolverError::Diverged`]; [`SolverError::NonFinite`] for a non-finite residual or step;
/// [`SolverError::Interrupted`]; invalid settings ([`SolverError::InvalidParameter`]).
pub fn inexact_newton(
    problem: &mut dyn NewtonKrylovProblem,
    u: &mut [f64],
    params: &InexactNewtonParams,
    observer: &mut dyn Observer<f64>,
) -> Result<SolveReport<f64>, SolverError> {
    params.forcing.validate()?;
    params.krylov.validate()?;
    if params.max_iterations == 0 {
        return Err(SolverError::invalid("max_iterations", 0.0, "[1, inf)"));
    }
    if !(params.absolute_tolerance.is_finite() && params.absolute_tolerance > 0.0) {
        return Err(SolverError::invalid(
            "absolute_tolerance",
            params.absolute_tolerance,
            "(0, inf)",
        ));
    }
    let policy = NewtonPolicy {
        max_iterations: params.max_iterations,
        absolute_tolerance: params.absolute_tolerance,
        relative_tolerance: 0.0,
        norm: ResidualNorm::Two,
        step: params.line_search.step_control(),
        divergence_limit: Some(params.divergence_limit),
        step_stagnation: false,
        check_finite: true,
    };
    let mut system = KrylovSystem {
        problem,
        params,
        observer,
        b: vec![0.0; u.len()],
        previous: None,
        linear_iterations: 0,
    };
    Ok(newton_drive(&mut system, u, &policy)?.into())
}

/// [`inexact_newton`]'s problem for the driver: each direction a Krylov solve to the forcing
/// term's tolerance, the Krylov total kept within its budget.
struct KrylovSystem<'a> {
    problem: &'a mut dyn NewtonKrylovProblem,
    params: &'a InexactNewtonParams,
    observer: &'a mut dyn Observer<f64>,
    /// The right-hand side `-r` of the step.
    b: Vec<f64>,
    /// `(|r|, eta)` of the last step.
    previous: Option<(f64, f64)>,
    /// Krylov iterations so far.
    linear_iterations: usize,
}

impl NewtonSystem for KrylovSystem<'_> {
    type Error = SolverError;

    fn residual(&mut self, u: &[f64], r: &mut [f64]) -> Result<(), SolverError> {
        self.problem.residual(u, r)
    }

    fn direction(
        &mut self,
        at: &NewtonIterate<'_>,
        d: &mut [f64],
    ) -> Result<NewtonDirection, SolverError> {
        let params = self.params;
        let left = params.max_linear_iterations - self.linear_iterations;
        let eta = params
            .forcing
            .next(at.norm, self.previous, params.absolute_tolerance);
        let krylov = KrylovParams {
            tolerance: eta,
            max_iterations: params.krylov.max_iterations.min(left),
            ..params.krylov
        };
        self.b.iter_mut().zip(at.r).for_each(|(bi, ri)| *bi = -ri);
        d.fill(0.0);
        let iterations = match self
            .problem
            .solve_step(at.u, &self.b, d, &krylov, self.observer)
        {
            Ok(step) => step.iterations,
            Err(SolverError::BudgetSpent {
                iterations,
                residual,
                ..
            }) => {
                let total = self.linear_iterations + iterations;
                // a spent inner budget: the outer total, or a step that would not get below 1
                if total >= params.max_linear_iterations || residual >= 1.0 {
                    return Err(SolverError::BudgetSpent {
                        field: INEXACT_NEWTON_BUDGET_FIELD,
                        iterations: total,
                        residual,
                        tolerance: eta,
                    });
                }
                // the step is inexact but still a descent direction for |r|^2
                iterations
            }
            Err(e) => return Err(e),
        };
        self.linear_iterations += iterations;
        self.previous = Some((at.norm, eta));
        Ok(NewtonDirection {
            // the inexact step decreases |r|^2 by at least (1 - eta^2) of the exact one
            armijo_scale: (1.0 - eta * eta).max(0.0),
            factorisations: 1,
            linear_iterations: iterations,
            ..NewtonDirection::default()
        })
    }

    fn accepted(&mut self, at: &NewtonIterate<'_>) -> Result<Flow, SolverError> {
        self.observer.iteration(&Progress::new(
            SolveStage::Newton,
            at.iteration,
            at.norm,
            at.step,
        ));
        if at.iteration == 0 {
            return Ok(Flow::Continue);
        }
        if self.observer.interrupted() {
            return Ok(Flow::Interrupt);
        }
        if self.linear_iterations >= self.params.max_linear_iterations
            && at.norm > self.params.absolute_tolerance
        {
            return Err(SolverError::BudgetSpent {
                field: INEXACT_NEWTON_BUDGET_FIELD,
                iterations: self.linear_iterations,
                residual: at.norm,
                tolerance: self.params.absolute_tolerance,
            });
        }
        Ok(Flow::Continue)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::csr_matrix::CsrMatrix;
    use crate::krylov::{IdentityPreconditioner, KrylovMethod, krylov_solve_operator};
    use crate::observer::SilentObserver;
    use crate::scalar::norm2;

    /// `r(u) = A u + u^3 - f` with `A` the 1-D Laplacian `tridiag(-1, 2, -1) (n + 1)^2`
    /// (Bratu-like, monotone: a unique root), its Jacobian `A + 3 diag(u^2)` assembled each
    /// step and solved by unpreconditioned GMRES.
    struct Cubic {
        n: usize,
        f: Vec<f64>,
        krylov_steps: Vec<(f64, usize)>,
    }

    impl Cubic {
        fn new(n: usize) -> Self {
            let f = (0..n)
                .map(|i| 50.0 * (core::f64::consts::PI * (i + 1) as f64 / (n + 1) as f64).sin())
                .collect();
            Self {
                n,
                f,
                krylov_steps: vec![],
            }
        }

        #[allow(clippy::needless_range_loop)] // the rows of a tridiagonal matrix
        fn matrix(&self, u: &[f64]) -> CsrMatrix {
            let n = self.n;
            let s = ((n + 1) * (n + 1)) as f64;
            let (mut ptr, mut cols, mut vals) = (vec![0], vec![], vec![]);
            for i in 0..n {
                if i > 0 {
                    cols.push((i - 1) as u32);
                    vals.push(-s);
                }
                cols.push(i as u32);
                vals.push(2.0 * s + 3.0 * u[i] * u[i]);
                if i + 1 < n {
                    cols.push((i + 1) as u32);
                    vals.push(-s);
                }
                ptr.push(cols.len());
            }
            CsrMatrix::new(n, n, ptr, cols, vals).unwrap()
        }
    }

    impl NewtonKrylovProblem for Cubic {
        fn residual(&mut self, u: &[f64], r: &mut [f64]) -> Result<(), SolverError> {
            let zero = vec![0.0; self.n];
            // A u = (A + 3 diag(0)) u
            self.matrix(&zero).mul_vec(u, r);
            for i in 0..self.n {
                r[i] += u[i].powi(3) - self.f[i];
            }
            Ok(())
        }

        fn solve_step(
            &mut self,
            u: &[f64],
            b: &[f64],
            d: &mut [f64],
            params: &KrylovParams,
            observer: &mut dyn Observer<f64>,
        ) -> Result<KrylovReport, SolverError> {
            let a = self.matrix(u);
            let report =
                krylov_solve_operator(&a, b, d, &mut IdentityPreconditioner, params, observer)?;
            self.krylov_steps
                .push((params.tolerance, report.iterations));
            Ok(report)
        }
    }

    fn params() -> InexactNewtonParams {
        InexactNewtonParams {
            absolute_tolerance: 1e-9,
            krylov: KrylovParams {
                method: KrylovMethod::Gmres,
                restart: 200,
                max_iterations: 1000,
                ..Default::default()
            },
            ..Default::default()
        }
    }

    #[test]
    fn forcing_terms_follow_choice_two_with_safeguards() {
        let ew = EisenstatWalker::default();
        assert_eq!(ew.next(1.0, None, 1e-12), 0.9);
        // fast decrease: eta = 0.9 (0.01)^2 = 9e-5, but safeguard 1 (0.9 * 0.9^2 = 0.729)
        let eta = ew.next(0.01, Some((1.0, 0.9)), 1e-12);
        assert!((eta - 0.729).abs() < 1e-15, "{eta}");
        // after a small eta the safeguard is off: choice 2 itself
        let eta = ew.next(1e-4, Some((1e-2, 1e-3)), 1e-12);
        assert!((eta - 0.9e-4).abs() < 1e-18, "{eta}");
        // no oversolving: 0.5 tol / |r|
        let eta = ew.next(1e-8, Some((1e-4, 1e-6)), 1e-9);
        assert!((eta - 0.05).abs() < 1e-15, "{eta}");
        assert!(EisenstatWalker { alpha: 3.0, ..ew }.validate().is_err());
    }

    #[test]
    fn inexact_newton_reaches_the_root_with_fewer_krylov_iterations_than_exact_steps() {
        let n = 200;
        let mut problem = Cubic::new(n);
        let mut u = vec![0.0; n];
        let report = inexact_newton(&mut problem, &mut u, &params(), &mut SilentObserver).unwrap();
        let mut r = vec![0.0; n];
        problem.residual(&u, &mut r).unwrap();
        assert!(norm2(&r) <= 1e-9, "{}", norm2(&r));
        // the forcing terms tighten as the residual falls (superlinear outer convergence)
        let etas: Vec<f64> = problem.krylov_steps.iter().map(|s| s.0).collect();
        assert!(etas[0] == 0.9 && etas.last().unwrap() < &1e-2, "{etas:?}");
        let rs = &report.residuals;
        let k = rs.len() - 1;
        assert!(rs[k] / rs[k - 1] < 0.1 * rs[k - 1] / rs[k - 2], "{rs:?}");
        // exact steps (eta = 1e-12 throughout) cost more Krylov iterations for the same root
        let mut exact = Cubic::new(n);
        let mut v = vec![0.0; n];
        let strict = InexactNewtonParams {
            forcing: EisenstatWalker {
                eta_max: 1e-12,
                eta_min: 1e-12,
                ..Default::default()
            },
            ..params()
        };
        let exact_report =
            inexact_newton(&mut exact, &mut v, &strict, &mut SilentObserver).unwrap();
        let diff = u
            .iter()
            .zip(&v)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        let scale = v.iter().map(|x| x.abs()).fold(0.0, f64::max);
        assert!(diff <= 1e-9 * scale, "{diff:e}");
        assert!(
            report.linear_iterations < exact_report.linear_iterations,
            "{} vs {}",
            report.linear_iterations,
            exact_report.linear_iterations
        );
    }

    #[test]
    fn a_spent_krylov_total_is_a_typed_error_naming_the_budget() {
        let mut problem = Cubic::new(200);
        let mut u = vec![0.0; 200];
        let tight = InexactNewtonParams {
            max_linear_iterations: 30,
            ..params()
        };
        match inexact_newton(&mut problem, &mut u, &tight, &mut SilentObserver) {
            Err(SolverError::BudgetSpent { field, .. }) => {
                assert_eq!(field, INEXACT_NEWTON_BUDGET_FIELD);
            }
            other => panic!("{other:?}"),
        }
        let bad = InexactNewtonParams {
            forcing: EisenstatWalker {
                gamma: 0.0,
                ..Default::default()
            },
            ..params()
        };
        assert!(matches!(
            inexact_newton(&mut problem, &mut u, &bad, &mut SilentObserver),
            Err(SolverError::InvalidParameter {
                field: "forcing.gamma",
                ..
            })
        ));
    }
}
