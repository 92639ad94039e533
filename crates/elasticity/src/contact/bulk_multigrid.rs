//! What the contact solvers tell a linear backend about their matrices
//! ([`capstan_solvers::LinearContext`]): the discretisation's geometric hierarchy (for
//! `solver.linear = "multigrid"`) and its near-null space (rigid motions, for PETSc's GAMG),
//! built once and shared, and whether the matrix is symmetric positive definite.

use std::sync::{Arc, OnceLock};

use capstan_solvers::{
    BoxedLinearSolver, CsrMatrix, DirectParams, LinearBackend, LinearContext, LinearSettings,
    NearNullSpace,
};

use crate::contact::error::ContactError;
use crate::contact::operator::ContactOperator;
use crate::error::ElasticityError;

/// What the backends of one contact solver share, computed on first use: the
/// discretisation's multigrid prolongations and its near-null space.
#[derive(Default)]
pub(crate) struct BackendCache {
    prolongations: OnceLock<Arc<[CsrMatrix]>>,
    near_null_space: OnceLock<Option<Arc<NearNullSpace>>>,
}

/// The context of one contact solver's linear solves: its discretisation's multigrid
/// prolongations ([`ContactOperator::multigrid_prolongations`]) and near-null space
/// ([`ContactOperator::near_null_space`]), computed on first use and kept in `cache` for
/// every later backend of the solver.
pub(crate) struct OperatorContext<'a, D: ?Sized> {
    pub(crate) operator: &'a D,
    pub(crate) cache: &'a BackendCache,
    /// The matrices are symmetric positive definite (the stuck start of a symmetric bulk).
    pub(crate) symmetric_positive_definite: bool,
}

impl<D: ContactOperator + ?Sized> LinearContext for OperatorContext<'_, D> {
    fn prolongations(&self, coarsest_unknowns: usize) -> Option<Arc<[CsrMatrix]>> {
        let cache = &self.cache.prolongations;
        if let Some(p) = cache.get() {
            return Some(Arc::clone(p));
        }
        let p = self.operator.multigrid_prolongations(coarsest_unknowns)?;
        Some(Arc::clone(cache.get_or_init(|| p)))
    }

    fn near_null_space(&self) -> Option<Arc<NearNullSpace>> {
        self.cache
            .near_null_space
            .get_or_init(|| self.operator.near_null_space().map(Arc::new))
            .clone()
    }

    fn symmetric_positive_definite(&self) -> bool {
        self.symmetric_positive_definite
    }
}

/// `backend` built from `settings` for the matrices of `operator`, with the discretisation's
/// fill-reducing ordering ([`ContactOperator::lu_ordering`]) unless `settings.direct` sets
/// one.
///
/// # Errors
/// [`ElasticityError::InvalidParameter`] naming `solver.linear` when the backend needs a
/// multigrid hierarchy the discretisation does not have (the plane-strain bodies); invalid
/// settings.
pub(crate) fn build_backend<D: ContactOperator + ?Sized>(
    backend: LinearBackend,
    settings: &LinearSettings,
    operator: &D,
    cache: &BackendCache,
    symmetric_positive_definite: bool,
) -> Result<BoxedLinearSolver, ContactError> {
    let mut settings = *settings;
    if settings.direct.ordering == DirectParams::default().ordering {
        settings.direct.ordering = operator.lu_ordering();
    }
    let context = OperatorContext {
        operator,
        cache,
        symmetric_positive_definite,
    };
    backend.build(&settings, &context).map_err(|e| match e {
        capstan_solvers::SolverError::InvalidParameter { field: "linear", .. }
            if backend.kind() == capstan_solvers::BackendKind::MatrixFree =>
        {
            ContactError::from(ElasticityError::InvalidParameter {
                field: "solver.linear",
                value: f64::NAN,
                allowed: "`matrix-free-mg` only with solver.nonlinear = \"full-newton\" or \"auto\" on the 3-D body (body.dimension = 3)",
            })
        }
        capstan_solvers::SolverError::InvalidParameter { field: "linear", .. } => {
            ContactError::from(ElasticityError::InvalidParameter {
                field: "solver.linear",
                value: f64::NAN,
                allowed: "`multigrid` only for a discretisation with a multigrid hierarchy (the 3-D body, body.dimension = 3)",
            })
        }
        other => other.into(),
    })
}
