//! Newton on owned rows: the damped Newton loop of [`crate::newton_drive`] with every vector
//! (iterate, residual, direction, line-search trial) held as one process's rows of a
//! distributed problem, the norms and line-search decisions reduced over the processes, and
//! each step's linear system solved by a distributed backend on the same rows
//! ([`LinearSolver::solve_owned_in_place_observed`]).

use std::ops::Range;

use crate::error::SolverError;
use crate::linear_registration::BoxedLinearSolver;
use crate::linear_solver::LinearSolver;
use crate::newton::NewtonParams;
use crate::newton_driver::{
    Flow, NewtonDirection, NewtonIterate, NewtonSystem, Reduction, newton_drive,
};
use crate::nonlinear_solver::SolveReport;
use crate::observer::{Observer, Progress, SolveStage};
use crate::row_distribution::RowDistribution;
use crate::scalar::first_non_finite;
use crate::sparsity_pattern::SparsityPattern;

/// A nonlinear problem `R(u) = 0` of `n` unknowns held as this process's rows
/// ([`OwnedRowsProblem::rows`]): the residual and the Jacobian's rows of this process from
/// this process's rows of `u` (the problem fetches the other entries its rows read, the
/// ghosts, from their owners: [`RowDistribution::fetch`]).
pub trait OwnedRowsProblem {
    /// The processes and this one's rank.
    fn distribution(&self) -> &dyn RowDistribution;

    /// This process's rows of the `n` unknowns (contiguous; whole nodes).
    fn rows(&self) -> Range<usize>;

    /// The Jacobian's pattern: `n x n`, with entries in this process's rows (the other rows
    /// are not read).
    fn pattern(&self) -> &SparsityPattern;

    /// `r = R(u)` on this process's rows, `u` this process's rows of the iterate. Collective
    /// (it fetches ghosts): every process calls it in the same order.
    ///
    /// # Errors
    /// The evaluation's or the communication's failure.
    fn residual_owned(&self, u: &[f64], r: &mut [f64]) -> Result<(), SolverError>;

    /// The values of `dR/du` on [`OwnedRowsProblem::pattern`] in this process's rows (the
    /// others zero), `u` this process's rows. Collective.
    ///
    /// # Errors
    /// The evaluation's or the communication's failure.
    fn jacobian_owned(&self, u: &[f64], values: &mut [f64]) -> Result<(), SolverError>;
}

/// Newton on owned rows ([`OwnedRowsProblem`]): the same iteration, line search and tests as
/// [`crate::Newton`] (its [`NewtonParams`]), each process holding only its rows of every
/// vector.
///
/// # Math
/// ```text
/// u_p, r_p = R(u)_p, d_p   (p: this process's rows; ghosts fetched inside R)
/// J_pp-rows(u) d = -r      (the distributed backend, on the same rows)
/// |r|_2 = s sqrt(sum_p sum_i (r_i / s)^2),  s = max_p max_i |r_i|      (reductions)
/// ```
/// Every decision (convergence, Armijo, failure) reads only reduced values, so it is the same
/// on every process; a non-finite entry on any process is [`SolverError::NonFinite`] with the
/// same global index on every process.
pub struct DistributedNewton {
    params: NewtonParams,
    linear: BoxedLinearSolver,
    analysed: Option<SparsityPattern>,
}

impl core::fmt::Debug for DistributedNewton {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("DistributedNewton")
            .field("params", &self.params)
            .finish_non_exhaustive()
    }
}

impl DistributedNewton {
    /// Newton with the distributed backend `linear` (`params.linear` is ignored).
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] if a setting is out of range.
    pub fn new(params: NewtonParams, linear: BoxedLinearSolver) -> Result<Self, SolverError> {
        params.validate()?;
        Ok(Self {
            params,
            linear,
            analysed: None,
        })
    }

    /// Solves `R(u) = 0` from `u` (this process's rows; the solution's rows on return).
    /// Collective.
    ///
    /// # Errors
    /// [`SolverError::DimensionMismatch`] when `u` is not this process's rows or the pattern
    /// is not square of their global size; the failures of [`crate::Newton`] (the same on
    /// every process).
    pub fn solve<P: OwnedRowsProblem + ?Sized>(
        &mut self,
        problem: &P,
        u: &mut [f64],
        observer: &mut dyn Observer<f64>,
    ) -> Result<SolveReport<f64>, SolverError> {
        let rows = problem.rows();
        let pattern = problem.pattern();
        if !pattern.is_square() {
            return Err(SolverError::NotSquare {
                nrows: pattern.nrows(),
                ncols: pattern.ncols(),
            });
        }
        if u.len() != rows.len() || rows.end > pattern.nrows() {
            return Err(SolverError::DimensionMismatch {
                quantity: "u (owned rows)",
                expected: rows.len(),
                found: u.len(),
            });
        }
        if self.analysed.as_ref() != Some(pattern) {
            self.analysed = None;
            self.linear.analyse(pattern)?;
            self.analysed = Some(pattern.clone());
        }
        let params = self.params;
        let policy = params.policy();
        let mut system = OwnedSystem {
            problem,
            linear: self.linear.as_mut(),
            values: vec![0.0; pattern.nnz()],
            first: rows.start,
            observer,
        };
        Ok(newton_drive(&mut system, u, &policy)?.into())
    }
}

/// [`DistributedNewton`]'s problem for the driver.
struct OwnedSystem<'a, P: ?Sized> {
    problem: &'a P,
    linear: &'a mut (dyn LinearSolver<f64> + Send),
    values: Vec<f64>,
    first: usize,
    observer: &'a mut dyn Observer<f64>,
}

impl<P: OwnedRowsProblem + ?Sized> NewtonSystem for OwnedSystem<'_, P> {
    type Error = SolverError;

    fn residual(&mut self, u: &[f64], r: &mut [f64]) -> Result<(), SolverError> {
        self.problem.residual_owned(u, r)
    }

    fn direction(
        &mut self,
        at: &NewtonIterate<'_>,
        du: &mut [f64],
    ) -> Result<NewtonDirection, SolverError> {
        self.values.fill(0.0);
        self.problem.jacobian_owned(at.u, &mut self.values)?;
        // every process fails together: the first non-finite value's slot over all of them
        let local = first_non_finite(&self.values).map_or(f64::NEG_INFINITY, |i| -(i as f64));
        let bad = self.reduce(local, Reduction::Max)?;
        if bad > f64::NEG_INFINITY {
            return Err(SolverError::NonFinite {
                quantity: "jacobian",
                index: (-bad) as usize,
                iteration: Some(at.iteration + 1),
            });
        }
        self.linear.factor(&self.values)?;
        for (d, ri) in du.iter_mut().zip(at.r) {
            *d = -ri;
        }
        self.linear
            .solve_owned_in_place_observed(self.first, du, self.observer)?;
        Ok(NewtonDirection {
            factorisations: 1,
            linear_iterations: self.linear.last_iterations().unwrap_or(0),
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
        // the observer of one process may ask to stop: all stop together
        let stop = at.iteration > 0 && self.observer.interrupted();
        let any = self.reduce(f64::from(u8::from(stop)), Reduction::Max)?;
        Ok(if any > 0.0 {
            Flow::Interrupt
        } else {
            Flow::Continue
        })
    }

    fn row_offset(&self) -> Option<usize> {
        Some(self.first)
    }

    fn reduce(&mut self, local: f64, op: Reduction) -> Result<f64, SolverError> {
        let d = self.problem.distribution();
        match op {
            Reduction::Sum => d.sum(local),
            Reduction::Max => d.max(local),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{LinearBackend, NonlinearSolver, SilentObserver};

    /// One process: the whole vector is its rows; sums and maxima are the values.
    struct Alone;

    impl RowDistribution for Alone {
        fn rank(&self) -> usize {
            0
        }
        fn size(&self) -> usize {
            1
        }
        fn gather(&self, _: &mut [f64], _: usize) -> Result<(), SolverError> {
            Ok(())
        }
        fn fetch(
            &self,
            owned: &[f64],
            _: usize,
            _: usize,
            indices: &[usize],
            out: &mut [f64],
        ) -> Result<(), SolverError> {
            for (o, &i) in out.iter_mut().zip(indices) {
                *o = owned[i];
            }
            Ok(())
        }
        fn sum(&self, value: f64) -> Result<f64, SolverError> {
            Ok(value)
        }
        fn max(&self, value: f64) -> Result<f64, SolverError> {
            Ok(value)
        }
    }

    /// The sparse LU as a "distributed" backend of one process (all rows owned).
    struct OneProcessLu(BoxedLinearSolver);

    impl LinearSolver<f64> for OneProcessLu {
        fn analyse(&mut self, pattern: &SparsityPattern) -> Result<(), SolverError> {
            self.0.analyse(pattern)
        }
        fn factor(&mut self, values: &[f64]) -> Result<(), SolverError> {
            self.0.factor(values)
        }
        fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<(), SolverError> {
            self.0.solve_in_place(rhs)
        }
        fn last_iterations(&self) -> Option<usize> {
            None
        }
        fn solve_owned_in_place_observed(
            &mut self,
            first: usize,
            rhs: &mut [f64],
            _: &mut dyn Observer<f64>,
        ) -> Result<(), SolverError> {
            assert_eq!(first, 0);
            self.0.solve_in_place(rhs)
        }
    }

    /// `R_i(u) = 2 u_i - u_{i-1} - u_{i+1} + h^2 u_i^3 - h^2 f_i` on `n` points (zero ends),
    /// `f` from the root `u_i = sin(pi x_i)`; `nan_at`: the residual is NaN at that entry.
    struct Bratu {
        n: usize,
        f: Vec<f64>,
        pattern: SparsityPattern,
        nan_at: Option<usize>,
    }

    impl Bratu {
        fn new(n: usize) -> Self {
            let h = 1.0 / (n + 1) as f64;
            let exact = |i: usize| (std::f64::consts::PI * (i + 1) as f64 * h).sin();
            let mut entries = Vec::new();
            for i in 0..n {
                for j in i.saturating_sub(1)..(i + 2).min(n) {
                    entries.push((i, j));
                }
            }
            let (pattern, _) = SparsityPattern::from_entries(n, n, &entries).unwrap();
            let f = (0..n)
                .map(|i| {
                    let (l, r) = (
                        if i > 0 { exact(i - 1) } else { 0.0 },
                        if i + 1 < n { exact(i + 1) } else { 0.0 },
                    );
                    (2.0 * exact(i) - l - r) / (h * h) + exact(i).powi(3)
                })
                .collect();
            Self {
                n,
                f,
                pattern,
                nan_at: None,
            }
        }
        fn h2(&self) -> f64 {
            (1.0 / (self.n + 1) as f64).powi(2)
        }
    }

    impl crate::Residual<f64> for Bratu {
        type Error = SolverError;
        fn residual(&self, u: &[f64], r: &mut [f64]) -> Result<(), SolverError> {
            self.residual_owned(u, r)
        }
    }

    impl crate::Jacobian<f64> for Bratu {
        fn pattern(&self) -> &SparsityPattern {
            &self.pattern
        }
        fn jacobian(&self, u: &[f64], values: &mut [f64]) -> Result<(), SolverError> {
            self.jacobian_owned(u, values)
        }
    }

    impl OwnedRowsProblem for Bratu {
        fn distribution(&self) -> &dyn RowDistribution {
            &Alone
        }
        fn rows(&self) -> Range<usize> {
            0..self.n
        }
        fn pattern(&self) -> &SparsityPattern {
            &self.pattern
        }
        fn residual_owned(&self, u: &[f64], r: &mut [f64]) -> Result<(), SolverError> {
            let h2 = self.h2();
            for i in 0..self.n {
                let l = if i > 0 { u[i - 1] } else { 0.0 };
                let rr = if i + 1 < self.n { u[i + 1] } else { 0.0 };
                r[i] = 2.0 * u[i] - l - rr + h2 * (u[i].powi(3) - self.f[i]);
            }
            if let Some(k) = self.nan_at {
                r[k] = f64::NAN;
            }
            Ok(())
        }
        fn jacobian_owned(&self, u: &[f64], values: &mut [f64]) -> Result<(), SolverError> {
            let h2 = self.h2();
            for ((i, j), slot) in self.pattern.entries().zip(0..) {
                values[slot] = if i == j {
                    2.0 + 3.0 * h2 * u[i] * u[i]
                } else {
                    -1.0
                };
            }
            Ok(())
        }
    }

    fn lu() -> BoxedLinearSolver {
        LinearBackend::LU.build(&Default::default(), &()).unwrap()
    }

    #[test]
    fn one_process_gives_the_serial_newton_to_rounding() {
        let problem = Bratu::new(60);
        let params = NewtonParams {
            absolute_tolerance: 1e-13,
            relative_tolerance: 0.0,
            ..NewtonParams::default()
        };
        let mut serial = vec![0.0; 60];
        let s = crate::Newton::with_linear_solver(params, lu())
            .unwrap()
            .solve(&problem, &mut serial, &mut SilentObserver)
            .unwrap();
        let mut owned = vec![0.0; 60];
        let d = DistributedNewton::new(params, Box::new(OneProcessLu(lu())))
            .unwrap()
            .solve(&problem, &mut owned, &mut SilentObserver)
            .unwrap();
        assert_eq!(s.iterations, d.iterations);
        for (a, b) in serial.iter().zip(&owned) {
            assert!((a - b).abs() <= 1e-14, "{a} {b}");
        }
        for (a, b) in s.residuals.iter().zip(&d.residuals) {
            assert!((a - b).abs() <= 1e-12 * a.max(1e-300), "{a} {b}");
        }
        // the discrete solution is within O(h^2) of sin(pi x): the Newton converged
        assert!((owned[29] - (std::f64::consts::PI * 30.0 / 61.0).sin()).abs() < 1e-3);
    }

    #[test]
    fn a_non_finite_residual_is_the_typed_error_with_its_global_index() {
        let mut problem = Bratu::new(20);
        problem.nan_at = Some(7);
        let mut u = vec![0.0; 20];
        let e = DistributedNewton::new(NewtonParams::default(), Box::new(OneProcessLu(lu())))
            .unwrap()
            .solve(&problem, &mut u, &mut SilentObserver)
            .unwrap_err();
        assert!(
            matches!(
                e,
                SolverError::NonFinite {
                    quantity: "residual",
                    index: 7,
                    ..
                }
            ),
            "{e:?}"
        );
    }

    #[test]
    fn a_backend_that_is_not_distributed_is_refused_by_name() {
        let problem = Bratu::new(10);
        let mut u = vec![0.0; 10];
        let e = DistributedNewton::new(NewtonParams::default(), lu())
            .unwrap()
            .solve(&problem, &mut u, &mut SilentObserver)
            .unwrap_err();
        assert!(
            matches!(
                e,
                SolverError::InvalidParameter {
                    field: "solver.linear",
                    ..
                }
            ),
            "{e:?}"
        );
        let mut short = vec![0.0; 9];
        let e = DistributedNewton::new(NewtonParams::default(), lu())
            .unwrap()
            .solve(&problem, &mut short, &mut SilentObserver)
            .unwrap_err();
        assert!(matches!(e, SolverError::DimensionMismatch { .. }), "{e:?}");
    }
}
