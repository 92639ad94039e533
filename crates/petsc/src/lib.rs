//! PETSc as a linear backend of capstan (`solver.linear = "petsc"`, the facade's `petsc`
//! feature): a distributed AIJ matrix whose rows are split over the MPI ranks in contiguous
//! blocks, solved by PETSc's KSP with the options of `solver.petsc_options`.
//!
//! Status: the linear algebra is distributed, each rank owning whole nodes
//! (`owned_blocks`); GAMG is given the caller's near-null space and block size. A
//! `PetscDistribution` installed as the process's row distribution lets the 3-D body
//! assemble only its rows and the contact model gather its residuals, evaluate the friction
//! law on its own contact sites and sum its stick/slip counts over the ranks; it also fetches
//! ghost entries of a vector held as each rank's rows (a `VecScatter` to given global
//! indices) and reduces scalars (sum, max). The caller's Newton iteration still runs on whole
//! vectors on every rank, each rank inserting its rows and receiving the whole solution. Built only with the system PETSc (Debian: `petsc-dev`, PETSc 3.18 on
//! Open MPI), never by the default workspace build.
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
mod policy;
#[cfg(feature = "petsc")]
mod session;
#[cfg(feature = "petsc")]
mod solver;

#[cfg(feature = "petsc")]
pub use distribution::{OWNED_NEWTON_OPTION, PetscDistribution};
#[cfg(feature = "petsc")]
pub use error::PetscError;
#[cfg(feature = "petsc")]
pub use policy::{FORCING_ETA_MAX_OPTION, FORCING_OPTION, PC_LAG_OPTION, StepPolicy};
#[cfg(feature = "petsc")]
pub use session::{DEFAULT_OPTIONS, MUMPS_OPTIONS, Session, running};
#[cfg(feature = "petsc")]
pub use solver::{NAME, NEAR_NULL_OPTION, PetscSolver, REGISTRATION, owned_blocks, owned_rows};

/// Whether the installed PETSc has MUMPS (the direct option, [`MUMPS_OPTIONS`]).
#[cfg(feature = "petsc")]
pub const HAVE_MUMPS: bool = capstan_petsc_sys::HAVE_MUMPS;
