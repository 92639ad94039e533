//! PETSc as a linear backend of capstan (`solver.linear = "petsc"`, the facade's `petsc`
//! feature): a distributed AIJ matrix whose rows are split over the MPI ranks in contiguous
//! blocks, solved by PETSc's KSP with the options of `solver.petsc_options`.
//!
//! Status: the linear algebra is distributed; the caller (the full-system contact Newton)
//! runs replicated on every rank with the whole pattern, values and right-hand side, each rank
//! inserting only its rows and receiving the whole solution. Memory per rank therefore still
//! holds one copy of the assembled system; only PETSc's matrix, its preconditioner and the
//! Krylov vectors are split. Built only with the system PETSc (Debian: `petsc-dev`, PETSc
//! 3.18 on Open MPI), never by the default workspace build.
//!
//! Without the crate feature `petsc` (which the facade's feature `petsc` turns on) the crate
//! is empty, so the default workspace build needs no PETSc.
#![warn(missing_docs)]

/// Whether this build has the PETSc backend (the crate feature `petsc`).
pub const ENABLED: bool = cfg!(feature = "petsc");

#[cfg(feature = "petsc")]
mod distribution;
#[cfg(feature = "petsc")]
mod error;
#[cfg(feature = "petsc")]
mod session;
#[cfg(feature = "petsc")]
mod solver;

#[cfg(feature = "petsc")]
pub use distribution::PetscDistribution;
#[cfg(feature = "petsc")]
pub use error::PetscError;
#[cfg(feature = "petsc")]
pub use session::{DEFAULT_OPTIONS, MUMPS_OPTIONS, Session, running};
#[cfg(feature = "petsc")]
pub use solver::{NAME, NEAR_NULL_OPTION, PetscSolver, REGISTRATION, owned_blocks, owned_rows};

/// Whether the installed PETSc has MUMPS (the direct option, [`MUMPS_OPTIONS`]).
#[cfg(feature = "petsc")]
pub const HAVE_MUMPS: bool = capstan_petsc_sys::HAVE_MUMPS;
