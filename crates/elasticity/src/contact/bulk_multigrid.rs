//! The iterative bulk solver of the full-system Newton: a Krylov method preconditioned by the
//! discretisation's geometric multigrid (`solver.linear = "multigrid"`).

use std::sync::{Arc, OnceLock};

use capstan_solvers::{
    CsrMatrix, KrylovMethod, KrylovParams, KrylovSolver, LinearSolver, MultigridParams,
};

use crate::contact::error::ContactError;
use crate::contact::operator::ContactOperator;
use crate::error::ElasticityError;

/// Settings of the iterative bulk solver of [`crate::contact::FullSystemSolver`]
/// ([`crate::contact::FullSystemSettings::multigrid`]).
///
/// # Math
/// Each Newton step solves `J du = -r` by right-preconditioned GMRES to
/// `|J du + r| <= krylov.tolerance |r|` (an inexact Newton method with the fixed forcing term
/// `krylov.tolerance`), the preconditioner one V-cycle of the Galerkin hierarchy
/// `J_{l+1} = P_l^T J_l P_l` built on the Jacobian itself (the friction rows included), the
/// prolongations `P_l` those of the discretisation
/// ([`ContactOperator::multigrid_prolongations`]). The stuck starting guess (the bulk with a
/// stiff spring on the tangential contact rows: symmetric positive definite) is solved by CG
/// with the same V-cycle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BulkMultigrid {
    /// Tolerance, work budget and restart of the Krylov solves (the method is chosen: GMRES
    /// for the Jacobians, CG for the stuck start).
    pub krylov: KrylovParams,
    /// Smoother and smoothing steps of the V-cycle.
    pub multigrid: MultigridParams,
    /// Coarsening stops at a level of at most this many unknowns (solved by a sparse LU).
    pub coarsest_unknowns: usize,
}

impl Default for BulkMultigrid {
    fn default() -> Self {
        Self {
            krylov: KrylovParams::default(),
            multigrid: MultigridParams::default(),
            coarsest_unknowns: 5_000,
        }
    }
}

impl BulkMultigrid {
    /// Checks every field.
    ///
    /// # Errors
    /// [`ContactError::Solver`] naming a bad Krylov or multigrid setting.
    pub fn validate(&self) -> Result<(), ContactError> {
        self.krylov.validate()?;
        self.multigrid.validate()?;
        Ok(())
    }

    /// A linear solver of `method` (CG or GMRES) with the V-cycle on the prolongations of
    /// `operator`, cached in `cache` after the first call.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `solver.linear` when the discretisation has
    /// no multigrid hierarchy (the plane-strain bodies); invalid settings.
    pub(crate) fn build<D: ContactOperator + ?Sized>(
        &self,
        operator: &D,
        method: KrylovMethod,
        cache: &OnceLock<Arc<[CsrMatrix]>>,
    ) -> Result<Box<dyn LinearSolver<f64> + Send>, ContactError> {
        let prolongations = match cache.get() {
            Some(p) => Arc::clone(p),
            None => {
                let p = operator
                    .multigrid_prolongations(self.coarsest_unknowns)
                    .ok_or(ContactError::from(ElasticityError::InvalidParameter {
                        field: "solver.linear",
                        value: f64::NAN,
                        allowed: "`multigrid` only for a discretisation with a multigrid hierarchy (the 3-D body, body.dimension = 3)",
                    }))?;
                Arc::clone(cache.get_or_init(|| p))
            }
        };
        let krylov = KrylovParams {
            method,
            ..self.krylov
        };
        Ok(Box::new(KrylovSolver::new(
            krylov,
            Some((prolongations, self.multigrid)),
        )?))
    }
}
