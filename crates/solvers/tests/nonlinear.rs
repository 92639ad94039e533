//! Public behaviour of the nonlinear solvers.

use core::convert::Infallible;

use capstan_solvers::samples::{Arctangent, CubeRoot, CubicReaction};
use capstan_solvers::{
    IterativeParams, JacobiNewton, Jacobian, LineSearch, LinearBackend, Newton, NewtonParams,
    NonlinearMethod, NonlinearSolver, Observer, Progress, Residual, SilentObserver, SolveStage,
    SolverError, SparsityPattern, max_abs_difference,
};

/// The registered backends that need nothing from the caller (`multigrid` needs a hierarchy).
const STANDALONE: [LinearBackend; 4] = [
    LinearBackend::LU,
    LinearBackend::CHOLESKY,
    LinearBackend::JACOBI,
    LinearBackend::GAUSS_SEIDEL,
];

/// The failure of Newton with `params` but no line search on `problem` from `u`.
fn newton_failure<P: Jacobian<f64>>(
    params: NewtonParams,
    problem: &P,
    u: &mut [f64],
) -> SolverError {
    let params = NewtonParams {
        line_search: LineSearch::None,
        ..params
    };
    Newton::new(params)
        .unwrap()
        .solve(problem, u, &mut SilentObserver)
        .unwrap_err()
}

#[test]
fn newton_converges_quadratically_on_the_cubic_reaction() {
    let problem = CubicReaction::new(50);
    let mut u = vec![0.0; 50];
    let mut newton = Newton::new(NewtonParams {
        absolute_tolerance: 1e-12,
        relative_tolerance: 0.0,
        ..Default::default()
    })
    .unwrap();
    let report = newton.solve(&problem, &mut u, &mut SilentObserver).unwrap();
    assert_eq!(report.iterations, 6);
    assert_eq!(report.factorisations, 6);
    assert_eq!(report.linear_iterations, 0); // direct backend
    assert_eq!(report.residuals.len(), report.iterations + 1);
    assert!(max_abs_difference(&u, &problem.exact_solution()) < 1e-12);
    // |r_{k+1}| <= C |r_k|^2 once in the asymptotic regime (|r_k| < 1), above round-off
    let r = &report.residuals;
    let mut checked = 0;
    for k in 0..r.len() - 1 {
        if r[k] < 1.0 && r[k + 1] > 1e-13 {
            let c = r[k + 1] / (r[k] * r[k]);
            assert!(c < 1.0, "step {k}: {} -> {}, C = {c}", r[k], r[k + 1]);
            checked += 1;
        }
    }
    assert!(checked >= 2, "{r:?}");
}

#[test]
fn newton_gives_the_same_root_with_every_linear_backend() {
    let problem = CubicReaction::new(30);
    let exact = problem.exact_solution();
    for backend in STANDALONE {
        if backend == LinearBackend::CHOLESKY {
            continue; // J = diag(3u^2) + A is SPD here too, but keep Cholesky to its own test
        }
        let mut u = vec![0.0; 30];
        let report = Newton::new(NewtonParams {
            linear: backend,
            iterative: IterativeParams {
                tolerance: 1e-13,
                ..Default::default()
            },
            ..Default::default()
        })
        .unwrap()
        .solve(&problem, &mut u, &mut SilentObserver)
        .unwrap();
        assert!(max_abs_difference(&u, &exact) < 1e-10, "{backend}");
        assert_eq!(
            report.linear_iterations > 0,
            !backend.is_direct(),
            "{backend}"
        );
    }
}

#[test]
fn newton_with_cholesky_solves_the_spd_jacobian_problem() {
    let problem = CubicReaction::new(30);
    let mut u = vec![0.5; 30];
    Newton::new(NewtonParams {
        linear: LinearBackend::CHOLESKY,
        ..Default::default()
    })
    .unwrap()
    .solve(&problem, &mut u, &mut SilentObserver)
    .unwrap();
    assert!(max_abs_difference(&u, &problem.exact_solution()) < 1e-10);
}

#[test]
fn jacobi_newton_finds_the_same_root() {
    let problem = CubicReaction::new(40);
    let mut newton_u = vec![0.0; 40];
    Newton::new(Default::default())
        .unwrap()
        .solve(&problem, &mut newton_u, &mut SilentObserver)
        .unwrap();
    let mut u = vec![0.0; 40];
    let mut solver = JacobiNewton::new(NewtonParams {
        iterative: IterativeParams {
            tolerance: 1e-6,
            ..Default::default()
        },
        ..Default::default()
    })
    .unwrap();
    let report = solver.solve(&problem, &mut u, &mut SilentObserver).unwrap();
    // inexact inner solves: linear outer convergence with rate ~1e-6
    assert_eq!(report.iterations, 6);
    assert_eq!(report.linear_iterations, 148);
    assert!(max_abs_difference(&u, &newton_u) < 1e-10);
    // chosen by name it is the same solver
    let mut by_name = NonlinearMethod::JacobiNewton
        .build(*solver.params())
        .unwrap();
    let mut v = vec![0.0; 40];
    let again = by_name
        .solve(&problem, &mut v, &mut SilentObserver)
        .unwrap();
    assert_eq!(again, report);
    assert_eq!(u, v);
}

#[test]
fn line_search_rescues_newton_on_arctangent() {
    let problem = Arctangent::new(3);
    let start = [10.0, -3.0, 0.5]; // full steps overshoot from |u| > 1.39
    let mut u = start.to_vec();
    let mut lengths = Vec::new();
    let mut observer = |p: &Progress<f64>| lengths.push(p.step_length);
    let report = Newton::new(Default::default())
        .unwrap()
        .solve(&problem, &mut u, &mut observer)
        .unwrap();
    assert!(u.iter().all(|v| v.abs() < 1e-10), "{u:?}");
    assert_eq!(report.iterations, 10);
    assert!(lengths[1] < 1.0, "the first step is damped: {lengths:?}");
    assert_eq!(*lengths.last().unwrap(), 1.0); // full steps near the root
    // monotone residual under Armijo
    assert!(report.residuals.windows(2).all(|w| w[1] < w[0]));

    let mut u = start.to_vec();
    let err = newton_failure(NewtonParams::default(), &problem, &mut u);
    // the iterates explode (10 -> -139 -> 3e4 -> -1.4e9 ...) until J underflows to 0
    assert!(
        matches!(
            err,
            SolverError::Singular { .. } | SolverError::NonFinite { .. }
        ),
        "{err:?}"
    );
}

#[test]
fn newton_without_line_search_reports_divergence_on_cube_root() {
    let problem = CubeRoot::new(2);
    let mut u = vec![1.0, -2.0];
    let params = NewtonParams {
        divergence_limit: 10.0,
        ..Default::default()
    };
    let err = newton_failure(params, &problem, &mut u);
    // |r| grows by 2^(1/3) per step: 2^(k/3) > 10 first at k = 10
    assert!(
        matches!(err, SolverError::Diverged { iteration: 10, .. }),
        "{err:?}"
    );
}

#[test]
fn iteration_cap_is_not_converged() {
    let problem = CubicReaction::new(10);
    let mut u = vec![0.0; 10];
    let err = Newton::new(NewtonParams {
        max_iterations: 2,
        ..Default::default()
    })
    .unwrap()
    .solve(&problem, &mut u, &mut SilentObserver)
    .unwrap_err();
    assert!(
        matches!(err, SolverError::NotConverged { iterations: 2, residual } if residual > 1e-10),
        "{err:?}"
    );
}

/// `r(u) = sqrt(u) - 1` (NaN for u < 0) or a NaN everywhere.
struct Sqrt {
    pattern: SparsityPattern,
    always_nan: bool,
}

impl Sqrt {
    fn new(always_nan: bool) -> Self {
        Self {
            pattern: SparsityPattern::from_entries(1, 1, &[(0, 0)]).unwrap().0,
            always_nan,
        }
    }
}

impl Residual<f64> for Sqrt {
    type Error = Infallible;
    fn residual(&self, u: &[f64], r: &mut [f64]) -> Result<(), Infallible> {
        r[0] = if self.always_nan {
            f64::NAN
        } else {
            u[0].sqrt() - 1.0
        };
        Ok(())
    }
}

impl Jacobian<f64> for Sqrt {
    fn pattern(&self) -> &SparsityPattern {
        &self.pattern
    }
    fn jacobian(&self, u: &[f64], values: &mut [f64]) -> Result<(), Infallible> {
        values[0] += 0.5 / u[0].sqrt();
        Ok(())
    }
}

#[test]
fn nan_residual_is_non_finite() {
    let mut u = vec![4.0];
    let err = Newton::new(Default::default())
        .unwrap()
        .solve(&Sqrt::new(true), &mut u, &mut SilentObserver)
        .unwrap_err();
    assert!(
        matches!(
            err,
            SolverError::NonFinite {
                quantity: "residual",
                index: 0,
                iteration: Some(0)
            }
        ),
        "{err:?}"
    );
}

#[test]
fn line_search_backs_off_from_a_nan_trial_point() {
    // from u = 16 the full step lands at u = 16 - 2*4*3 = -8 where sqrt is NaN
    let problem = Sqrt::new(false);
    let mut u = vec![16.0];
    Newton::new(Default::default())
        .unwrap()
        .solve(&problem, &mut u, &mut SilentObserver)
        .unwrap();
    assert!((u[0] - 1.0).abs() < 1e-9);
    // without a line search the NaN is reported, not returned
    let mut u = vec![16.0];
    let err = newton_failure(NewtonParams::default(), &problem, &mut u);
    assert!(
        matches!(
            err,
            SolverError::NonFinite {
                quantity: "residual",
                iteration: Some(1),
                ..
            }
        ),
        "{err:?}"
    );
    assert_eq!(u, vec![16.0]); // the last accepted iterate
}

#[derive(Debug)]
struct Broken;
impl core::fmt::Display for Broken {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str("constitutive law out of range")
    }
}
impl std::error::Error for Broken {}

struct Failing(SparsityPattern);
impl Residual<f64> for Failing {
    type Error = Broken;
    fn residual(&self, _u: &[f64], r: &mut [f64]) -> Result<(), Broken> {
        r[0] = 1.0;
        Ok(())
    }
}
impl Jacobian<f64> for Failing {
    fn pattern(&self) -> &SparsityPattern {
        &self.0
    }
    fn jacobian(&self, _u: &[f64], _values: &mut [f64]) -> Result<(), Broken> {
        Err(Broken)
    }
}

#[test]
fn problem_errors_arrive_with_their_source() {
    let problem = Failing(SparsityPattern::from_entries(1, 1, &[(0, 0)]).unwrap().0);
    let err = Newton::new(Default::default())
        .unwrap()
        .solve(&problem, &mut [0.0], &mut SilentObserver)
        .unwrap_err();
    assert!(matches!(
        err,
        SolverError::Problem {
            stage: "jacobian",
            ..
        }
    ));
    let source = std::error::Error::source(&err).unwrap();
    assert_eq!(source.to_string(), "constitutive law out of range");
}

#[test]
fn wrong_length_of_u_is_a_dimension_mismatch() {
    let problem = CubicReaction::new(4);
    let err = Newton::new(Default::default())
        .unwrap()
        .solve(&problem, &mut [0.0; 3], &mut SilentObserver)
        .unwrap_err();
    assert!(matches!(
        err,
        SolverError::DimensionMismatch {
            expected: 4,
            found: 3,
            ..
        }
    ));
}

#[test]
fn observer_sees_every_iteration() {
    let problem = CubicReaction::new(10);
    let mut u = vec![0.0; 10];
    let mut seen = Vec::new();
    let mut observer = |p: &Progress<f64>| {
        assert_eq!(p.stage, SolveStage::Newton);
        seen.push((p.iteration, p.residual_norm, p.step_length))
    };
    let report = Newton::new(Default::default())
        .unwrap()
        .solve(&problem, &mut u, &mut observer)
        .unwrap();
    assert_eq!(seen.len(), report.iterations + 1);
    assert_eq!(seen[0].2, 0.0);
    for (k, (i, r, _)) in seen.iter().enumerate() {
        assert_eq!(*i, k);
        assert_eq!(*r, report.residuals[k]);
    }
}

/// Stops after a fixed number of iterations, as Ctrl-C in an embedding interpreter would.
struct StopAfter(usize, Vec<usize>);

impl Observer<f64> for StopAfter {
    fn iteration(&mut self, p: &Progress<f64>) {
        self.1.push(p.iteration);
    }
    fn interrupted(&mut self) -> bool {
        self.1.len() > self.0
    }
}

#[test]
fn an_interrupting_observer_stops_newton_and_jacobi_newton_with_a_typed_error() {
    let problem = CubicReaction::new(10);
    let mut newton = Newton::new(Default::default()).unwrap();
    let mut stop = StopAfter(1, Vec::new());
    let err = newton
        .solve(&problem, &mut [0.0; 10], &mut stop)
        .unwrap_err();
    assert!(
        matches!(err, SolverError::Interrupted { iteration: 1 }),
        "{err:?}"
    );
    assert_eq!(stop.1, vec![0, 1]);
    let mut stages = Vec::new();
    let mut record = |p: &Progress<f64>| stages.push(p.stage);
    JacobiNewton::new(Default::default())
        .unwrap()
        .solve(&problem, &mut [0.0; 10], &mut record)
        .unwrap();
    assert!(stages.iter().all(|s| *s == SolveStage::JacobiNewton) && stages.len() > 1);
}

#[test]
fn solver_can_be_reused_across_solves_and_patterns() {
    // the second solve starts at the root (to the relative tolerance of the first): at most
    // one more step
    let problem = CubicReaction::new(10);
    let mut newton = Newton::new(Default::default()).unwrap();
    let mut u = vec![0.0; 10];
    newton.solve(&problem, &mut u, &mut SilentObserver).unwrap();
    let report = newton.solve(&problem, &mut u, &mut SilentObserver).unwrap();
    assert!(report.iterations <= 1);
    assert!(report.final_residual().unwrap() <= 1e-10);
    // a different pattern is analysed afresh
    let other = CubicReaction::new(12);
    let mut v = vec![0.0; 12];
    newton.solve(&other, &mut v, &mut SilentObserver).unwrap();
    assert!(max_abs_difference(&v, &other.exact_solution()) < 1e-10);
}
