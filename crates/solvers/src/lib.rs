//! Linear and nonlinear solver backends for capstan. Knows no physics.
//!
//! # Quick start
//! ```
//! use capstan_solvers::{LinearSolver, SparseLu, SparsityPattern};
//! // [[0, 2], [1, 0]] x = [4, 3]: the pattern once, then values and right-hand sides
//! let (pattern, _) = SparsityPattern::from_entries(2, 2, &[(0, 0), (1, 0), (0, 1), (1, 1)]).unwrap();
//! let mut lu = SparseLu::default();
//! lu.analyse(&pattern).unwrap();
//! lu.factor(&[0.0, 1.0, 2.0, 0.0]).unwrap();
//! let mut x = vec![4.0, 3.0];
//! lu.solve_in_place(&mut x).unwrap();
//! assert_eq!(x, vec![3.0, 2.0]);
//! ```
//!
//! # Purpose
//! The discretised contact problems of capstan are sparse nonlinear systems `r(u) = 0` whose
//! Jacobian keeps one sparsity pattern for the whole solve. This crate provides:
//!
//! - [`SparsityPattern`]: a CSC pattern built once from `(row, col)` entries, with the slot of
//!   every entry so assembly is `values[slot[k]] += v`; views for faer and `sprs`.
//! - [`LinearSolver`]: `analyse` once per pattern, `factor` per set of values, `solve_in_place`
//!   for many right-hand sides. Backends: [`SparseLu`] and [`SparseCholesky`] (faer, symbolic
//!   analysis reused), [`Jacobi`] and [`GaussSeidel`] (the paper's iterative baseline),
//!   [`KrylovSolver`] (`multigrid`). Each is registered once in [`linear_registry`] (name, summary, parameters, builder);
//!   [`LinearBackend`] picks a registered one by name, and a crate that embeds capstan
//!   registers its own the same way.
//! - Krylov methods ([`krylov_solve`]: conjugate gradients, restarted right-preconditioned GMRES) on a
//!   [`CsrMatrix`], with a work budget and a typed [`SolverError::BudgetSpent`], and a
//!   [`Multigrid`] V-cycle on a given hierarchy of prolongations (Galerkin coarse operators,
//!   Chebyshev–Jacobi or damped-Jacobi smoothing, sparse LU on the coarsest level);
//!   [`KrylovSolver`] is the pair behind the [`LinearSolver`] calls.
//! - Fill-reducing orderings for the direct backends ([`DirectParams::ordering`],
//!   [`ColumnOrdering`]): COLAMD (LU's default), AMD on `A + A^T`, and a geometric nested
//!   dissection of a structured grid described by [`GridShape`] (no physics: only how the
//!   unknowns are numbered).
//! - [`Residual`] / [`Jacobian`] capability traits and [`NonlinearSolver`]s: [`Newton`] with a
//!   backtracking line search and [`JacobiNewton`]; [`NonlinearMethod`] picks one by name.
//!   Progress goes to an [`Observer`]; results come as a [`SolveReport`] or a typed
//!   [`SolverError`], never as a silent NaN.
//! - [`samples`]: model problems (2-D Poisson, convection–diffusion, random diagonally dominant
//!   matrices, nonlinear systems with known roots) shared by tests and benches.
//!
//! # Status
//! Complete for the needs of the elasticity crate: all backends are tested on the same
//! problems against each other and against the residual `|b - A x|`.
//!
//! # Limitations
//! - The faer backends and the nonlinear solvers are implemented for
//!   `f64` only; the pattern helpers and the iterative backends are generic over
//!   [`SolverScalar`].
//! - [`Jacobi`] and [`GaussSeidel`] are stationary methods without preconditioning or Krylov
//!   acceleration: they are baselines, and need diagonally dominant (Jacobi) or SPD /
//!   diagonally dominant (Gauss–Seidel) matrices. [`KrylovSolver`] and [`Multigrid`] are
//!   `f64` only and take the prolongations from the caller (no algebraic coarsening).
//! - Singularity of a direct factorisation is detected from the solution (non-finite, or a
//!   residual above [`DirectParams::residual_tolerance`] after refinement), because faer
//!   factorises numerically singular matrices without complaint; very ill-conditioned
//!   matrices (condition number above about `1e7` with the default) are reported as singular.
//! - Parallelism of the faer backends follows `faer::get_global_parallelism()`.
//! - [`SparseLu`]'s default multifrontal kernel ([`LuKind`]) reserves the structure of
//!   `A + A^T` and pivots only inside each front's diagonal block (threshold 0.01); a matrix
//!   that needs pivots from outside a front is refactorised with faer's supernodal kernel,
//!   whose structure (`A^T A`) takes about twice the memory: on the 2000 x 321 Navier grid
//!   (1.28 M unknowns) 3.3 GiB against 7.7 GiB. The multifrontal kernel runs its dense
//!   updates through faer (parallel), but its fronts one after another.
//!
//! # Example
//! ```
//! use capstan_solvers::{LinearBackend, samples::Poisson2d};
//! let system = Poisson2d::new(16).system();
//! let mut solutions = Vec::new();
//! // every registered backend that needs nothing from the caller (`multigrid` needs a
//! // hierarchy; `matrix-free-mg` is run by its caller on an operator, never on a matrix)
//! for backend in LinearBackend::all()
//!     .into_iter()
//!     .filter(|b| b.name() != "multigrid" && b.kind() != capstan_solvers::BackendKind::MatrixFree)
//! {
//!     let mut solver = backend.build(&Default::default(), &()).unwrap();
//!     solver.analyse(&system.pattern).unwrap();
//!     solver.factor(&system.values).unwrap();
//!     let mut x = system.rhs.clone();
//!     solver.solve_in_place(&mut x).unwrap();
//!     assert!(system.residual_norm(&x) < 1e-10);
//!     solutions.push(x);
//! }
//! assert!(solutions[0].iter().zip(&solutions[3]).all(|(a, b)| (a - b).abs() < 1e-8));
//! ```
#![warn(missing_docs)]

// First, so that `named_variants!` is in textual scope in the modules below.
#[macro_use]
mod named;

mod condensation;
mod csr_matrix;
mod direct_params;
mod direct_solve;
mod distributed_newton;
mod error;
mod inexact_newton;
mod iterative_params;
mod jacobi_newton;
mod krylov;
mod krylov_solver;
mod linear_backend;
mod linear_operator;
mod linear_registration;
pub mod linear_registry;
mod linear_solver;
mod lu_kind;
mod multifrontal_lu;
mod multigrid;
mod newton;
mod newton_driver;
mod nonlinear_method;
mod nonlinear_solver;
mod observer;
mod operator_multigrid;
mod ordering;
mod problem;
mod relaxation;
pub mod row_distribution;
pub mod samples;
mod scalar;
mod sparse_cholesky;
mod sparse_lu;
mod sparsity_pattern;
mod spectrum_estimate;

pub use condensation::{CondensationScratch, CondensedBlock, schur_complement};
pub use csr_matrix::CsrMatrix;
pub use direct_params::DirectParams;
pub use distributed_newton::{DistributedNewton, OwnedRowsProblem};
pub use error::SolverError;
pub use inexact_newton::{
    EisenstatWalker, INEXACT_NEWTON_BUDGET_FIELD, InexactNewtonParams, NewtonKrylovProblem,
    inexact_newton,
};
pub use iterative_params::IterativeParams;
pub use jacobi_newton::JacobiNewton;
pub use krylov::{
    IdentityPreconditioner, KRYLOV_BUDGET_FIELD, KrylovMethod, KrylovParams, KrylovReport,
    Preconditioner, krylov_solve, krylov_solve_operator,
};
pub use krylov_solver::KrylovSolver;
pub use linear_backend::LinearBackend;
pub use linear_operator::LinearOperator;
pub use linear_registration::{
    BackendKind, BoxedLinearSolver, LinearContext, LinearSettings, NearNullSpace, Parameter,
    RegisteredLinearSolver,
};
pub use linear_solver::LinearSolver;
pub use lu_kind::LuKind;
pub use multigrid::{Multigrid, MultigridParams, MultigridPreconditioner, Smoother};
pub use newton::{LineSearch, Newton, NewtonParams};
pub use newton_driver::{
    Flow, Merit, NewtonDirection, NewtonDriven, NewtonFailure, NewtonIterate, NewtonPolicy,
    NewtonSystem, Reduction, ResidualNorm, ShortStep, StepControl, newton_drive,
};
pub use nonlinear_method::{AnyNonlinearSolver, NonlinearMethod};
pub use nonlinear_solver::{NonlinearSolver, SolveReport};
pub use observer::{
    ActiveSet, Observer, Progress, SetUpPhase, SetUpWork, SilentObserver, SolveStage,
};
pub use operator_multigrid::{MATRIX_FREE_ESTIMATE_MARGIN, OperatorLevel, OperatorMultigrid};
pub use ordering::{
    ColumnOrdering, GridShape, amd_compressed, amd_symmetrised, is_permutation,
    nested_dissection_elements, nested_dissection_grid,
};
pub use problem::{Jacobian, Residual};
pub use relaxation::{GaussSeidel, Jacobi, Relaxation};
pub use scalar::{SolverScalar, max_abs, max_abs_difference};
pub use sparse_cholesky::SparseCholesky;
pub use sparse_lu::SparseLu;
pub use sparsity_pattern::SparsityPattern;
pub use spectrum_estimate::lanczos_estimate;
