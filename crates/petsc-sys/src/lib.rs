//! The hand-written `extern "C"` surface of the system PETSc that `capstan-petsc` uses, and
//! nothing more: initialisation and the options database, distributed AIJ matrices with
//! preallocation, vectors and their gather to every rank, KSP with a monitor.
//!
//! Status: checked against PETSc 3.18 (Debian's `petsc-dev`, real double precision, 32-bit
//! indices, Open MPI). `build.rs` reads the installed `petscconf.h` and refuses a
//! configuration these declarations do not match (complex or single-precision scalars, an MPI
//! other than Open MPI); 64-bit indices select `PetscInt = i64` (`cfg(petsc_int64)`).
//!
//! Every function returns a `PetscErrorCode` (0: success). Nothing in this crate is safe to
//! call without reading the PETSc manual page of the function; the safe layer is
//! `capstan-petsc`.
#![warn(missing_docs)]
#![allow(non_camel_case_types, non_snake_case)] // PETSc's own spelling

/// Whether this build links PETSc (the crate feature `petsc`); without it the crate is empty.
pub const LINKED: bool = cfg!(feature = "petsc");

#[cfg(feature = "petsc")]
mod ffi;
#[cfg(feature = "petsc")]
pub use ffi::*;
