//! What a linear backend registers ([`RegisteredLinearSolver`]): its name, its parameters and
//! how to build it from the settings ([`LinearSettings`]) and from what the caller knows about
//! its matrices ([`LinearContext`]). The registry itself is [`crate::linear_registry`].

use std::sync::Arc;

use crate::csr_matrix::CsrMatrix;
use crate::direct_params::DirectParams;
use crate::error::SolverError;
use crate::iterative_params::IterativeParams;
use crate::krylov::KrylovParams;
use crate::linear_solver::LinearSolver;
use crate::multigrid::MultigridParams;

/// A linear solver chosen at run time.
pub type BoxedLinearSolver = Box<dyn LinearSolver<f64> + Send>;

/// The settings every registered backend draws its parameters from: one struct per family,
/// each with its defaults and its own `validate`. A backend reads the families it needs and
/// validates them by constructing itself.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LinearSettings {
    /// The direct backends: fill-reducing ordering, LU kernel, solution check.
    pub direct: DirectParams,
    /// The stationary iterative backends (Jacobi, Gauss–Seidel): tolerance, sweeps, relaxation.
    pub iterative: IterativeParams,
    /// The Krylov backends: tolerance, work budget, restart (the method is chosen by the
    /// backend from [`LinearContext::symmetric_positive_definite`]).
    pub krylov: KrylovParams,
    /// The multigrid preconditioner: smoother and smoothing steps.
    pub multigrid: MultigridParams,
}

/// What the caller knows about the matrices it will factor, for backends that need more than
/// the values: the prolongations of a geometric hierarchy, symmetry. Physics-free: a
/// discretisation answers with matrices and flags. Every method has a default ("nothing
/// known"), so `&()` is a context.
pub trait LinearContext {
    /// Prolongations `P_l` (finest first, `P_l` maps level `l + 1` to level `l`) of a
    /// geometric hierarchy whose coarsest level has at most `coarsest_unknowns` unknowns;
    /// `None` when the unknowns have no hierarchy.
    fn prolongations(&self, coarsest_unknowns: usize) -> Option<Arc<[CsrMatrix]>> {
        let _ = coarsest_unknowns;
        None
    }

    /// Whether every matrix factored is symmetric positive definite (CG may be used).
    fn symmetric_positive_definite(&self) -> bool {
        false
    }

    /// The near-null space of the matrices (e.g. an elastic body's rigid-body modes), for
    /// algebraic multigrid; `None` when unknown.
    fn near_null_space(&self) -> Option<Arc<NearNullSpace>> {
        None
    }
}

/// Vectors the matrices nearly annihilate, and the number of unknowns per node, for an
/// algebraic multigrid preconditioner (PETSc's GAMG: `MatSetNearNullSpace`,
/// `MatSetBlockSize`). Physics-free: a discretisation fills it (an elastic body: its rigid
/// motions, 3 in the plane, 6 in space).
///
/// # Math
/// ```text
/// |A z_k| << |A| |z_k|   for every k    (exactly 0 without boundary conditions)
/// unknown i belongs to node floor(i / block_size)
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct NearNullSpace {
    /// Unknowns per node (the dofs of a node are consecutive): 2 or 3 for elasticity.
    pub block_size: usize,
    /// The vectors `z_k`, each of the matrices' dimension (need not be orthonormal).
    pub vectors: Vec<Vec<f64>>,
}

impl NearNullSpace {
    /// Checks the vectors: every one of length `n` (a multiple of the block size) and finite.
    ///
    /// # Errors
    /// [`SolverError::DimensionMismatch`] naming `near-null vector` or `block size`;
    /// [`SolverError::NonFinite`] naming `near-null vector`.
    pub fn check(&self, n: usize) -> Result<(), SolverError> {
        if self.block_size == 0 || !n.is_multiple_of(self.block_size) {
            return Err(SolverError::DimensionMismatch {
                quantity: "block size",
                expected: n,
                found: self.block_size,
            });
        }
        for z in &self.vectors {
            if z.len() != n {
                return Err(SolverError::DimensionMismatch {
                    quantity: "near-null vector",
                    expected: n,
                    found: z.len(),
                });
            }
            if let Some(index) = z.iter().position(|x| !x.is_finite()) {
                return Err(SolverError::NonFinite {
                    quantity: "near-null vector",
                    index,
                    iteration: None,
                });
            }
        }
        Ok(())
    }
}

/// Nothing known about the matrices.
impl LinearContext for () {}

/// One parameter of a registered backend: the key (a field of [`LinearSettings`], as
/// `family.field`), its default and the allowed range, for listings and docs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Parameter {
    /// The key, e.g. `"iterative.tolerance"`.
    pub key: &'static str,
    /// The default, as text.
    pub default: &'static str,
    /// The allowed range, as text.
    pub allowed: &'static str,
}

/// How a registered backend solves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BackendKind {
    /// A factorisation: exact to round-off, setup (`factor`) dominates, memory superlinear.
    Direct,
    /// A Krylov method (possibly preconditioned, e.g. by multigrid): solves to a relative
    /// tolerance, suited to large and stiff systems.
    Krylov,
    /// A stationary iteration (Jacobi, Gauss–Seidel): the paper's baseline, slow on stiff
    /// systems; solvers use it where it was asked for (the Newton steps), not for their setup
    /// solves.
    Stationary,
    /// A matrix-free solve the caller runs itself on an operator's action (no assembled
    /// matrix: building it as a [`crate::LinearSolver`] is refused).
    MatrixFree,
}

/// A linear backend that scenes (`solver.linear`) and both contact solvers can name.
///
/// # Example
/// A backend written outside this crate: sparse LU that counts its factorisations, registered
/// once and then chosen by name like the built-ins.
/// ```
/// use std::sync::atomic::{AtomicUsize, Ordering};
/// use capstan_solvers::{linear_registry, BackendKind, LinearBackend, LinearSolver, RegisteredLinearSolver, SolverError, SparseLu, SparsityPattern};
///
/// static FACTORISATIONS: AtomicUsize = AtomicUsize::new(0);
/// #[derive(Debug)]
/// struct Counting(SparseLu);
/// impl LinearSolver<f64> for Counting {
///     fn analyse(&mut self, p: &SparsityPattern) -> Result<(), SolverError> { self.0.analyse(p) }
///     fn factor(&mut self, v: &[f64]) -> Result<(), SolverError> {
///         FACTORISATIONS.fetch_add(1, Ordering::Relaxed);
///         self.0.factor(v)
///     }
///     fn solve_in_place(&mut self, b: &mut [f64]) -> Result<(), SolverError> { self.0.solve_in_place(b) }
///     fn last_iterations(&self) -> Option<usize> { None }
/// }
/// linear_registry::register(RegisteredLinearSolver {
///     name: "counting-lu-doc",
///     summary: "sparse LU that counts its factorisations",
///     parameters: &[],
///     kind: BackendKind::Direct,
///     build: |s, _| Ok(Box::new(Counting(SparseLu::new(s.direct)?))),
/// })
/// .unwrap();
///
/// let backend: LinearBackend = "counting-lu-doc".parse().unwrap();
/// let mut solver = backend.build(&Default::default(), &()).unwrap();
/// let (pattern, _) = SparsityPattern::from_entries(1, 1, &[(0, 0)]).unwrap();
/// solver.analyse(&pattern).unwrap();
/// solver.factor(&[2.0]).unwrap();
/// let mut x = [4.0];
/// solver.solve_in_place(&mut x).unwrap();
/// assert_eq!((x[0], FACTORISATIONS.load(Ordering::Relaxed)), (2.0, 1));
/// ```
#[derive(Debug, Clone, Copy)]
pub struct RegisteredLinearSolver {
    /// The value of `solver.linear` that selects it (e.g. `"lu"`).
    pub name: &'static str,
    /// One line for listings and docs.
    pub summary: &'static str,
    /// The settings it reads, with defaults and ranges.
    pub parameters: &'static [Parameter],
    /// How it solves (what a caller may expect of its cost and accuracy).
    pub kind: BackendKind,
    /// Builds the backend, validating the settings it reads by constructing itself.
    ///
    /// # Errors
    /// [`SolverError::InvalidParameter`] naming the first bad setting, or a context that lacks
    /// what the backend needs.
    pub build: fn(&LinearSettings, &dyn LinearContext) -> Result<BoxedLinearSolver, SolverError>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn near_null_space_check_names_the_wrong_length_block_or_value() {
        let z = |block_size, vectors| NearNullSpace {
            block_size,
            vectors,
        };
        assert!(z(2, vec![vec![1.0; 4]]).check(4).is_ok());
        assert!(z(2, vec![]).check(4).is_ok());
        for (space, n, quantity) in [
            (z(3, vec![]), 4, "block size"),
            (z(0, vec![]), 4, "block size"),
            (z(2, vec![vec![1.0; 3]]), 4, "near-null vector"),
        ] {
            match space.check(n) {
                Err(SolverError::DimensionMismatch { quantity: q, .. }) => assert_eq!(q, quantity),
                other => panic!("{other:?}"),
            }
        }
        assert!(matches!(
            z(1, vec![vec![1.0, f64::NAN]]).check(2),
            Err(SolverError::NonFinite { index: 1, .. })
        ));
    }
}
