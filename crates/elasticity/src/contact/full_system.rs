//! The full-system contact solver: Newton (sparse LU refactorised each step) or the paper's
//! Jacobi–Newton on the whole residual. The reference the boundary-only solver is checked
//! against, and the baseline of the benchmarks.

use capstan_friction::FrictionLaw;
use capstan_solvers::{
    Jacobian, LinearSolver, NewtonParams, NonlinearMethod, NonlinearSolver, Residual,
    SilentObserver, SolverError, SparseLu, SparsityPattern,
};

use crate::contact::boundary_solver::ContactSettings;
use crate::contact::error::ContactError;
use crate::contact::model::{ContactModel, EndLoads};
use crate::contact::solution::{ContactSolution, SolveStats};
use crate::discretisation::Discretisation;

/// Settings of [`FullSystemSolver`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FullSystemSettings {
    /// `newton` (linear backend `newton.linear`) or `jacobi-newton`.
    pub method: NonlinearMethod,
    /// Newton settings; the tolerances are replaced by `continuation.tolerance` relative to
    /// `max(1, |b|_2)`.
    pub newton: NewtonParams,
    /// Continuation settings (shared with the boundary-only solver).
    pub continuation: ContactSettings,
}

impl Default for FullSystemSettings {
    fn default() -> Self {
        Self {
            method: NonlinearMethod::Newton,
            newton: NewtonParams::default(),
            continuation: ContactSettings::default(),
        }
    }
}

/// The full residual `R(v)` and Jacobian of a contact model under fixed loads, as a
/// [`capstan_solvers`] problem.
///
/// # Math
/// ```text
/// R(v)  = A v - b - sum_k w_k e_row_k t_2,k(v)
/// dR/dv = A - sum_k w_k e_row_k (dt_2/dv^2 e_tdof_k^T + dt_2/dsigma N_k)
/// ```
/// on the pattern of `A` extended by the friction entries.
pub struct FullSystemProblem<'a, D, L: FrictionLaw<f64>> {
    model: &'a ContactModel<D, L>,
    rhs: Vec<f64>,
}

impl<'a, D, L: FrictionLaw<f64>> FullSystemProblem<'a, D, L> {
    /// The problem for `loads`.
    pub fn new(model: &'a ContactModel<D, L>, loads: EndLoads) -> Self {
        Self {
            rhs: model.rhs(loads),
            model,
        }
    }

    /// The right-hand side `b`.
    pub fn rhs(&self) -> &[f64] {
        &self.rhs
    }
}

impl<D, L: FrictionLaw<f64>> Residual<f64> for FullSystemProblem<'_, D, L> {
    type Error = core::convert::Infallible;
    fn residual(&self, u: &[f64], r: &mut [f64]) -> Result<(), Self::Error> {
        self.model.residual_into(&self.rhs, u, r);
        Ok(())
    }
}

impl<D, L: FrictionLaw<f64>> Jacobian<f64> for FullSystemProblem<'_, D, L> {
    fn pattern(&self) -> &SparsityPattern {
        &self.model.extended().pattern
    }
    fn jacobian(&self, u: &[f64], values: &mut [f64]) -> Result<(), Self::Error> {
        self.model.jacobian_into(u, values);
        Ok(())
    }
}

/// Newton or Jacobi–Newton on the full residual, with load continuation.
///
/// The start is the stuck solution (a stiff spring on `v^2` at the contact: the body held by
/// friction everywhere), scaled with the load factor.
pub struct FullSystemSolver<'a, D, L: FrictionLaw<f64>> {
    model: &'a ContactModel<D, L>,
    settings: FullSystemSettings,
    /// The stuck solution for unit `tau0` and unit `tau_max`.
    stuck: [Vec<f64>; 2],
}

impl<D, L: FrictionLaw<f64>> core::fmt::Debug for FullSystemSolver<'_, D, L> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("FullSystemSolver")
            .field("settings", &self.settings)
            .finish_non_exhaustive()
    }
}

impl<'a, D: Discretisation, L: FrictionLaw<f64>> FullSystemSolver<'a, D, L> {
    /// Prepares the starting guesses (one sparse LU of the stuck operator).
    ///
    /// # Errors
    /// Invalid settings; solver failures.
    pub fn new(
        model: &'a ContactModel<D, L>,
        settings: FullSystemSettings,
    ) -> Result<Self, ContactError> {
        settings.continuation.validate()?;
        settings.newton.validate()?;
        let ext = model.extended();
        let mut values = vec![0.0; ext.pattern.nnz()];
        for (k, &a) in model.system().values.iter().enumerate() {
            values[ext.a_slot[k]] += a;
        }
        for &slot in &ext.tangential_slot {
            values[slot] += 1e4 * values[slot].abs().max(1.0);
        }
        let mut lu = SparseLu::default();
        lu.analyse(&ext.pattern)?;
        lu.factor(&values)?;
        let stuck = [0, 1].map(|i| {
            let mut v = model.rhs_basis(i).to_vec();
            lu.solve_in_place(&mut v).map(|()| v)
        });
        let [a, b] = stuck;
        Ok(Self {
            model,
            settings,
            stuck: [a?, b?],
        })
    }

    fn stuck(&self, loads: EndLoads) -> Vec<f64> {
        self.stuck[0]
            .iter()
            .zip(&self.stuck[1])
            .map(|(a, b)| loads.tau0 * a + loads.tau_max * b)
            .collect()
    }

    fn newton(
        &self,
        loads: EndLoads,
        v: &mut [f64],
        stats: &mut SolveStats,
    ) -> Result<(), SolverError> {
        let problem = FullSystemProblem::new(self.model, loads);
        let b = problem.rhs().iter().map(|x| x * x).sum::<f64>().sqrt();
        let params = NewtonParams {
            absolute_tolerance: self.settings.continuation.tolerance * b.max(1.0),
            relative_tolerance: 0.0,
            max_iterations: self.settings.continuation.max_iterations,
            ..self.settings.newton
        };
        let mut solver = self.settings.method.build(params)?;
        let result = solver.solve(&problem, v, &mut SilentObserver);
        match result {
            Ok(report) => {
                stats.newton_iterations += report.iterations;
                stats.factorisations += report.factorisations;
                stats.linear_iterations += report.linear_iterations;
                Ok(())
            }
            Err(e) => {
                // (an inner Jacobi failure also reports `NotConverged`: not counted)
                stats.newton_iterations += match &e {
                    SolverError::Stagnated { iterations, .. } => *iterations,
                    SolverError::Diverged { iteration, .. } => *iteration,
                    _ => 0,
                };
                Err(e)
            }
        }
    }

    /// Solves for the loads.
    ///
    /// # Errors
    /// [`ContactError::NotConverged`] when the continuation fails; invalid loads.
    pub fn solve(&self, loads: EndLoads) -> Result<ContactSolution, ContactError> {
        loads.check()?;
        let method = match self.settings.method {
            NonlinearMethod::JacobiNewton => "full-jacobi-newton",
            _ => "full-newton",
        };
        let mut stats = SolveStats {
            method,
            newton_iterations: 0,
            continuation_steps: 1,
            residual: 0.0,
            linear_iterations: 0,
            factorisations: 1,
        };
        let mut v = self.stuck(loads);
        if self.newton(loads, &mut v, &mut stats).is_err() {
            let c = self.settings.continuation;
            let mut lambda = 0.0;
            let mut current = vec![0.0; v.len()];
            let mut step = c.initial_load_step;
            stats.continuation_steps = 0;
            let mut last = f64::INFINITY;
            while lambda < 1.0 && stats.continuation_steps < c.max_continuation_steps {
                stats.continuation_steps += 1;
                let next = (lambda + step).min(1.0);
                let mut trial: Vec<f64> = if lambda > 0.0 {
                    current.iter().map(|x| x * next / lambda).collect()
                } else {
                    self.stuck(loads.scaled(next))
                };
                match self.newton(loads.scaled(next), &mut trial, &mut stats) {
                    Ok(()) => {
                        lambda = next;
                        current = trial;
                        step = (step * 1.5).min(1.0);
                    }
                    Err(e) => {
                        last = match e {
                            SolverError::Stagnated { residual, .. }
                            | SolverError::NotConverged { residual, .. }
                            | SolverError::Diverged { residual, .. } => residual,
                            _ => f64::INFINITY,
                        };
                        step *= 0.5;
                        if step < c.min_load_step {
                            break;
                        }
                    }
                }
            }
            if lambda < 1.0 {
                return Err(ContactError::NotConverged {
                    iterations: stats.newton_iterations,
                    residual: last,
                    load_factor: lambda,
                });
            }
            v = current;
        }
        Ok(ContactSolution::new(self.model, loads, v, stats))
    }
}
