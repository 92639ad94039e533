//! The errors of the PETSc layer.

/// What can go wrong talking to PETSc.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PetscError {
    /// A PETSc (or MPI) function returned a non-zero error code; PETSc has printed its
    /// traceback on stderr.
    #[error("PETSc call `{function}` failed with error code {code}")]
    Call {
        /// The C function.
        function: &'static str,
        /// Its `PetscErrorCode`.
        code: i32,
    },
    /// A PETSc object was needed before [`crate::Session::start`] (or after its end).
    #[error(
        "PETSc is not running: start a `capstan_petsc::Session` first (solver.linear = \"petsc\")"
    )]
    NotStarted,
    /// A PETSc object was used from a thread other than the one that started the
    /// [`crate::Session`] (PETSc runs without thread support; every rank must make its
    /// collective calls in one order).
    #[error(
        "{what} called from a thread other than the one that started PETSc: distributed solves \
         run one at a time on that thread (PETSc is initialised without thread support)"
    )]
    WrongThread {
        /// The operation refused.
        what: &'static str,
    },
    /// [`crate::Session::start`] was called a second time in this process (MPI cannot be
    /// initialised twice).
    #[error("PETSc was already started in this process")]
    AlreadyStarted,
    /// The options string cannot be passed to C.
    #[error("`solver.petsc_options` = {value:?}: {allowed}")]
    InvalidOptions {
        /// The string given.
        value: String,
        /// What is allowed.
        allowed: &'static str,
    },
    /// KSP stopped without converging for a reason other than its iteration budget.
    #[error("KSP diverged (KSPConvergedReason {reason}: {name}) after {iterations} iterations")]
    Diverged {
        /// The `KSPConvergedReason` (negative).
        reason: i32,
        /// Its PETSc name.
        name: &'static str,
        /// Iterations done.
        iterations: usize,
    },
    /// A size does not fit PETSc's index type (`PetscInt`).
    #[error("{quantity} = {value} does not fit PETSc's index type (PetscInt of {bits} bits)")]
    IndexOverflow {
        /// What was too large.
        quantity: &'static str,
        /// Its value.
        value: usize,
        /// Bits of `PetscInt` in the installed PETSc.
        bits: u32,
    },
}

/// `Ok(())` for a zero error code, else [`PetscError::Call`] naming `function`.
pub(crate) fn check(code: i32, function: &'static str) -> Result<(), PetscError> {
    if code == 0 {
        Ok(())
    } else {
        Err(PetscError::Call { function, code })
    }
}

/// The PETSc name of a negative `KSPConvergedReason`.
pub(crate) fn diverged_name(reason: i32) -> &'static str {
    match reason {
        -2 => "KSP_DIVERGED_NULL",
        -3 => "KSP_DIVERGED_ITS",
        -4 => "KSP_DIVERGED_DTOL",
        -5 => "KSP_DIVERGED_BREAKDOWN",
        -6 => "KSP_DIVERGED_BREAKDOWN_BICG",
        -7 => "KSP_DIVERGED_NONSYMMETRIC",
        -8 => "KSP_DIVERGED_INDEFINITE_PC",
        -9 => "KSP_DIVERGED_NANORINF",
        -10 => "KSP_DIVERGED_INDEFINITE_MAT",
        -11 => "KSP_DIVERGED_PC_FAILED",
        _ => "unknown KSPConvergedReason",
    }
}

impl From<PetscError> for capstan_solvers::SolverError {
    fn from(e: PetscError) -> Self {
        Self::External {
            backend: "petsc",
            source: Box::new(e),
        }
    }
}
