//! The registry of linear backends that scenes can name (`solver.linear`).
//!
//! A backend becomes usable from scenes, by [`crate::Newton`] and by both contact solvers by
//! writing its file and registering it once: a [`RegisteredLinearSolver`] names it, lists the
//! settings it reads and builds it from [`LinearSettings`] (validating them) and a
//! [`LinearContext`]. The built-ins register themselves in [`registry`]; a crate that embeds
//! capstan adds its own with [`register`] before it reads scenes. Nothing else changes: a
//! [`crate::LinearBackend`] is a handle to a registered entry, parsed from its name.
//!
//! The built-ins, in order: `lu` ([`crate::SparseLu`]), `cholesky`
//! ([`crate::SparseCholesky`]), `jacobi` ([`crate::Jacobi`]), `gauss-seidel`
//! ([`crate::GaussSeidel`]), `multigrid` ([`crate::KrylovSolver`] with the caller's
//! geometric hierarchy).
//!
//! # Example
//! ```
//! use capstan_solvers::{linear_registry, LinearBackend};
//! assert!(linear_registry::names().starts_with("lu, cholesky, jacobi, gauss-seidel, multigrid"));
//! let lu = linear_registry::find("lu").unwrap();
//! assert!(lu.kind == linear_registry::BackendKind::Direct && lu.parameters.iter().any(|p| p.key == "direct.ordering"));
//! assert_eq!("gauss-seidel".parse::<LinearBackend>().unwrap().name(), "gauss-seidel");
//! ```

use std::sync::{LazyLock, RwLock};

use crate::error::SolverError;

use crate::sparse_lu::SparseLu;

pub use crate::linear_registration::{
    BackendKind, BoxedLinearSolver, LinearContext, LinearSettings, Parameter,
    RegisteredLinearSolver,
};

/// The `lu` entry ([`SparseLu`]; here rather than in `sparse_lu.rs`, which the multigrid
/// coarse solve imports: no import cycle through the settings).
pub(crate) const LU_REGISTRATION: RegisteredLinearSolver = RegisteredLinearSolver {
    name: "lu",
    summary: "sparse LU (faer; multifrontal with supernodal fallback): any nonsingular matrix",
    parameters: &[
        Parameter {
            key: "direct.ordering",
            default: "auto",
            allowed: "auto, colamd, amd, nested-dissection",
        },
        Parameter {
            key: "direct.residual_tolerance",
            default: "1e-8",
            allowed: "(0, 1)",
        },
        Parameter {
            key: "direct.refinement_steps",
            default: "2",
            allowed: "[0, inf)",
        },
        Parameter {
            key: "direct.lu_kind",
            default: "auto",
            allowed: "auto, multifrontal, supernodal",
        },
    ],
    kind: BackendKind::Direct,
    build: |s, _| Ok(Box::new(SparseLu::new(s.direct)?)),
};

/// The built-in backends, in the order of [`names`].
fn builtin() -> Vec<&'static RegisteredLinearSolver> {
    vec![
        &LU_REGISTRATION,
        &crate::sparse_cholesky::REGISTRATION,
        &crate::relaxation::JACOBI_REGISTRATION,
        &crate::relaxation::GAUSS_SEIDEL_REGISTRATION,
        &crate::krylov_solver::REGISTRATION,
        &crate::operator_multigrid::MATRIX_FREE_REGISTRATION,
    ]
}

static REGISTRY: LazyLock<RwLock<Vec<&'static RegisteredLinearSolver>>> =
    LazyLock::new(|| RwLock::new(builtin()));

fn entries() -> std::sync::RwLockReadGuard<'static, Vec<&'static RegisteredLinearSolver>> {
    REGISTRY
        .read()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Every registered backend, built-ins first, then in the order of [`register`].
pub fn registry() -> Vec<&'static RegisteredLinearSolver> {
    entries().clone()
}

/// The backend named `name`, if registered.
pub fn find(name: &str) -> Option<&'static RegisteredLinearSolver> {
    entries().iter().copied().find(|r| r.name == name)
}

/// The registered names, comma-separated (for error messages).
pub fn names() -> String {
    entries()
        .iter()
        .map(|r| r.name)
        .collect::<Vec<_>>()
        .join(", ")
}

/// Adds `backend` to the registry, so that scenes and solvers can name it.
///
/// # Errors
/// [`SolverError::DuplicateName`] if a backend of that name is registered already.
pub fn register(
    backend: RegisteredLinearSolver,
) -> Result<&'static RegisteredLinearSolver, SolverError> {
    let mut all = REGISTRY
        .write()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    if all.iter().any(|r| r.name == backend.name) {
        return Err(SolverError::DuplicateName {
            kind: "linear backend",
            name: backend.name,
        });
    }
    let entry: &'static RegisteredLinearSolver = Box::leak(Box::new(backend));
    all.push(entry);
    Ok(entry)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtins_are_registered_once_under_their_scene_names() {
        // (tests of this binary may register more after them)
        assert!(names().starts_with("lu, cholesky, jacobi, gauss-seidel, multigrid"));
        assert!(find("superlu").is_none());
        let err = register(LU_REGISTRATION).unwrap_err();
        assert!(matches!(err, SolverError::DuplicateName { name: "lu", .. }));
        for r in builtin() {
            assert!(
                !r.summary.is_empty() && !r.parameters.is_empty(),
                "{}",
                r.name
            );
        }
    }
}
