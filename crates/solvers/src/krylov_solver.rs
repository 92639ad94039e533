//! A Krylov method preconditioned by a multigrid V-cycle, as a [`LinearSolver`].

use std::sync::Arc;

use crate::csr_matrix::CsrMatrix;
use crate::error::SolverError;
use crate::krylov::{IdentityPreconditioner, KrylovMethod, KrylovParams, krylov_solve};
use crate::linear_registration::{
    BackendKind, BoxedLinearSolver, LinearContext, LinearSettings, Parameter,
    RegisteredLinearSolver,
};
use crate::linear_solver::{LinearSolver, check_rhs, check_square};
use crate::multigrid::{Multigrid, MultigridParams};
use crate::observer::SilentObserver;
use crate::sparsity_pattern::SparsityPattern;

/// CG or GMRES ([`KrylovParams`]) preconditioned by a [`Multigrid`] V-cycle on the given
/// prolongations, behind the [`LinearSolver`] calls: `analyse` keeps a row-compressed copy of
/// the pattern, `factor` copies the values and builds the Galerkin hierarchy,
/// `solve_in_place` iterates from zero to the relative tolerance.
///
/// # Math
/// ```text
/// factor:  A_0 = A,  A_{l+1} = P_l^T A_l P_l,  LU of A_L
/// solve:   x with |b - A x| <= tolerance |b|,  M^-1 = one V-cycle
/// ```
/// A solve is inexact by design: a Newton method using it is an inexact Newton method with
/// the forcing term `tolerance`.
///
/// # Example
/// ```
/// use capstan_solvers::{KrylovParams, KrylovSolver, LinearSolver, samples::Poisson2d};
/// let system = Poisson2d::new(16).system();
/// // no prolongations: the coarsest level is the matrix itself (one LU, one iteration)
/// let mut s = KrylovSolver::new(KrylovParams::default(), Some((vec![].into(), Default::default()))).unwrap();
/// s.analyse(&system.pattern).unwrap();
/// s.factor(&system.values).unwrap();
/// let mut x = system.rhs.clone();
/// s.solve_in_place(&mut x).unwrap();
/// assert!(system.residual_norm(&x) < 1e-8 * system.rhs.iter().map(|v| v * v).sum::<f64>().sqrt());
/// assert_eq!(s.last_iterations(), Some(1));
/// ```
#[derive(Debug)]
pub struct KrylovSolver {
    params: KrylovParams,
    multigrid: Option<Multigrid>,
    /// CSC slot of each row-ordered entry.
    slot: Vec<u32>,
    matrix: Option<CsrMatrix>,
    factored: bool,
    last_iterations: Option<usize>,
    last_residual: Option<f64>,
}

/// The `multigrid` entry of [`crate::linear_registry`]: CG (symmetric positive definite
/// matrices, [`LinearContext::symmetric_positive_definite`]) or GMRES preconditioned by one
/// V-cycle on the context's hierarchy ([`LinearContext::prolongations`], coarsest level at
/// most [`MultigridParams::coarsest_unknowns`] unknowns).
pub(crate) const REGISTRATION: RegisteredLinearSolver = RegisteredLinearSolver {
    name: "multigrid",
    summary: "GMRES (CG when symmetric positive definite) preconditioned by a V-cycle of the caller's geometric hierarchy",
    parameters: &[
        Parameter {
            key: "krylov.tolerance",
            default: "1e-8",
            allowed: "(0, 1)",
        },
        Parameter {
            key: "krylov.max_iterations",
            default: "500",
            allowed: "[1, inf)",
        },
        Parameter {
            key: "krylov.restart",
            default: "100",
            allowed: "[1, inf)",
        },
        Parameter {
            key: "multigrid.smoother",
            default: "chebyshev",
            allowed: "jacobi, chebyshev",
        },
        Parameter {
            key: "multigrid.smoothing_steps",
            default: "1",
            allowed: "[1, inf)",
        },
        Parameter {
            key: "multigrid.coarsest_unknowns",
            default: "5000",
            allowed: "[1, inf)",
        },
    ],
    kind: BackendKind::Krylov,
    build: build_multigrid,
};

fn build_multigrid(
    s: &LinearSettings,
    context: &dyn LinearContext,
) -> Result<BoxedLinearSolver, SolverError> {
    s.krylov.validate()?;
    s.multigrid.validate()?;
    let prolongations = context
        .prolongations(s.multigrid.coarsest_unknowns)
        .ok_or(SolverError::InvalidParameter {
            field: "linear",
            value: f64::NAN,
            allowed: "`multigrid` only where the caller gives a geometric hierarchy (LinearContext::prolongations)",
        })?;
    let method = if context.symmetric_positive_definite() {
        KrylovMethod::Cg
    } else {
        KrylovMethod::Gmres
    };
    let krylov = KrylovParams { method, ..s.krylov };
    Ok(Box::new(KrylovSolver::new(
        krylov,
        Some((prolongations, s.multigrid)),
    )?))
}

impl KrylovSolver {
    /// The solver; `multigrid` is `(prolongations, settings)` of the V-cycle preconditioner
    /// (finest first), `None` for none.
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] for bad settings; see [`Multigrid::new`].
    pub fn new(
        params: KrylovParams,
        multigrid: Option<(Arc<[CsrMatrix]>, MultigridParams)>,
    ) -> Result<Self, SolverError> {
        params.validate()?;
        let multigrid = multigrid.map(|(p, mp)| Multigrid::new(p, mp)).transpose()?;
        Ok(Self {
            params,
            multigrid,
            slot: Vec::new(),
            matrix: None,
            factored: false,
            last_iterations: None,
            last_residual: None,
        })
    }

    /// The settings.
    pub fn params(&self) -> &KrylovParams {
        &self.params
    }

    /// The relative residual `|b - A x| / |b|` of the last solve.
    pub fn last_residual(&self) -> Option<f64> {
        self.last_residual
    }

    /// The multigrid preconditioner, if any.
    pub fn multigrid(&self) -> Option<&Multigrid> {
        self.multigrid.as_ref()
    }
}

impl LinearSolver<f64> for KrylovSolver {
    fn analyse(&mut self, pattern: &SparsityPattern) -> Result<(), SolverError> {
        let n = check_square(pattern)?;
        if pattern.nnz() > u32::MAX as usize {
            return Err(SolverError::invalid(
                "nnz",
                pattern.nnz() as f64,
                "[0, 2^32)",
            ));
        }
        self.factored = false;
        let (row_ptr, col_idx, slot) = pattern.row_layout();
        self.slot = slot.into_iter().map(|s| s as u32).collect();
        let nnz = col_idx.len();
        self.matrix = Some(CsrMatrix::new(
            n,
            n,
            row_ptr,
            col_idx.into_iter().map(|c| c as u32).collect(),
            vec![0.0; nnz],
        )?);
        Ok(())
    }

    fn factor(&mut self, values: &[f64]) -> Result<(), SolverError> {
        let Some(matrix) = self.matrix.as_mut() else {
            return Err(SolverError::call_order("factor", "analyse"));
        };
        self.factored = false;
        crate::linear_solver::check_value_count(values, self.slot.len())?;
        for (v, &s) in matrix.values_mut().iter_mut().zip(&self.slot) {
            *v = values[s as usize];
        }
        if let Some(mg) = self.multigrid.as_mut() {
            mg.setup(matrix)?;
        }
        self.factored = true;
        Ok(())
    }

    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<(), SolverError> {
        let (true, Some(a)) = (self.factored, self.matrix.as_ref()) else {
            return Err(SolverError::call_order("solve_in_place", "factor"));
        };
        check_rhs(rhs, a.nrows())?;
        let b = rhs.to_vec();
        self.last_iterations = None;
        let result = match self.multigrid.as_mut() {
            Some(mg) => krylov_solve(
                a,
                &b,
                rhs,
                &mut mg.with(a),
                &self.params,
                &mut SilentObserver,
            ),
            None => krylov_solve(
                a,
                &b,
                rhs,
                &mut IdentityPreconditioner,
                &self.params,
                &mut SilentObserver,
            ),
        };
        match result {
            Ok(report) => {
                self.last_iterations = Some(report.iterations);
                self.last_residual = Some(report.residuals.last().copied().unwrap_or(0.0));
                Ok(())
            }
            Err(e) => {
                if let SolverError::BudgetSpent {
                    iterations,
                    residual,
                    ..
                } = &e
                {
                    self.last_iterations = Some(*iterations);
                    self.last_residual = Some(*residual);
                }
                Err(e)
            }
        }
    }

    fn last_iterations(&self) -> Option<usize> {
        self.last_iterations
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::samples::Poisson2d;

    #[test]
    fn calls_out_of_order_are_typed_errors() {
        let mut s = KrylovSolver::new(KrylovParams::default(), None).unwrap();
        assert!(matches!(
            s.factor(&[1.0]),
            Err(SolverError::CallOrder { .. })
        ));
        let system = Poisson2d::new(4).system();
        s.analyse(&system.pattern).unwrap();
        let mut x = system.rhs.clone();
        assert!(matches!(
            s.solve_in_place(&mut x),
            Err(SolverError::CallOrder { .. })
        ));
        s.factor(&system.values).unwrap();
        s.solve_in_place(&mut x).unwrap();
        assert!(system.residual_norm(&x) < 1e-7);
    }
}
