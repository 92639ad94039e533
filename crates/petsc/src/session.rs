//! PETSc's lifetime in the process: one [`Session`], started once, finalised on drop.

use std::ffi::CString;
use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, Ordering};
use std::thread::ThreadId;

use capstan_petsc_sys as sys;

use crate::error::{PetscError, check};

/// The options every solve starts from; `solver.petsc_options` (inserted after) overrides any.
///
/// GMRES (the Newton Jacobians carry the non-symmetric friction tangent) preconditioned by
/// PETSc's algebraic multigrid GAMG with Chebyshev/SOR smoothing, to a relative residual of
/// `1e-8` (an inexact Newton method with that forcing term, as capstan's own multigrid bulk
/// solver), within 2,000 iterations (restart 100). Measured on the 3-D ellipse at 15,795
/// unknowns: 38 Krylov iterations a Newton step, against 197 with GAMG's default smoother
/// (Chebyshev/Jacobi) and 45 with hypre's BoomerAMG (5x slower a solve here).
pub const DEFAULT_OPTIONS: &str = "-ksp_type gmres -ksp_gmres_restart 100 -pc_type gamg \
     -mg_levels_ksp_type chebyshev -mg_levels_pc_type sor -ksp_rtol 1e-8 -ksp_max_it 2000";

/// The options of the direct alternative: one LU factorisation by MUMPS (distributed; the
/// Debian build has it, [`capstan_petsc_sys::HAVE_MUMPS`]).
pub const MUMPS_OPTIONS: &str = "-ksp_type preonly -pc_type lu -pc_factor_mat_solver_type mumps";

static STARTED: AtomicBool = AtomicBool::new(false);

/// The thread that called [`Session::start`]: PETSc is initialised without thread support
/// (`MPI_THREAD_SINGLE`), so every PETSc call of the process is made from it.
static THREAD: OnceLock<ThreadId> = OnceLock::new();

/// PETSc running in this process: `PetscInitialize` on [`Session::start`], `PetscFinalize` on
/// drop.
///
/// MPI is initialised by PETSc unless it already is (e.g. by the `mpi` crate of capstan's
/// `mpi` feature: one `MPI_Init` per process either way, and PETSc then leaves
/// `MPI_Finalize` to whoever called `MPI_Init`). A process starts PETSc at most once.
#[derive(Debug)]
pub struct Session {
    rank: usize,
    size: usize,
}

impl Session {
    /// Starts PETSc with [`DEFAULT_OPTIONS`] overridden by `options` (PETSc's command-line
    /// syntax, e.g. `"-ksp_type cg -pc_type gamg -ksp_monitor"`; also read: the environment
    /// variable `PETSC_OPTIONS`). What PETSc prints to standard output (`-log_view`,
    /// `-ksp_view`, monitors) goes to standard error (`PETSC_STDOUT = PETSC_STDERR`): the
    /// process's standard output is capstan's report. The calling thread becomes the one
    /// every PETSc call must come from ([`PetscError::WrongThread`]).
    ///
    /// # Errors
    /// [`PetscError::AlreadyStarted`]; [`PetscError::InvalidOptions`] for a string with a NUL
    /// byte; [`PetscError::Call`] when PETSc fails to start or rejects the options.
    pub fn start(options: &str) -> Result<Self, PetscError> {
        let user = CString::new(options).map_err(|_| PetscError::InvalidOptions {
            value: options.to_owned(),
            allowed: "PETSc options without NUL bytes",
        })?;
        if STARTED.swap(true, Ordering::SeqCst) {
            return Err(PetscError::AlreadyStarted);
        }
        let _ = THREAD.set(std::thread::current().id());
        let defaults = CString::new(DEFAULT_OPTIONS).expect("no NUL in the defaults");
        // SAFETY: called once per process (STARTED); the strings outlive the calls.
        unsafe {
            check(
                sys::PetscInitializeNoArguments(),
                "PetscInitializeNoArguments",
            )?;
            // capstan's standard output is its report (one JSON document under `--json`):
            // what PETSc prints (`-log_view`, `-ksp_view`, monitors) goes to standard error
            sys::PETSC_STDOUT = sys::PETSC_STDERR;
            check(
                sys::PetscOptionsInsertString(core::ptr::null_mut(), defaults.as_ptr()),
                "PetscOptionsInsertString",
            )?;
            check(
                sys::PetscOptionsInsertString(core::ptr::null_mut(), user.as_ptr()),
                "PetscOptionsInsertString",
            )?;
            check(
                sys::PetscMemorySetGetMaximumUsage(),
                "PetscMemorySetGetMaximumUsage",
            )?;
        }
        let (mut rank, mut size) = (0, 1);
        // SAFETY: PETSc (hence MPI) is initialised; PETSC_COMM_WORLD is set by it.
        unsafe {
            let comm = sys::PETSC_COMM_WORLD;
            check(sys::MPI_Comm_rank(comm, &mut rank), "MPI_Comm_rank")?;
            check(sys::MPI_Comm_size(comm, &mut size), "MPI_Comm_size")?;
        }
        Ok(Self {
            rank: rank as usize,
            size: size as usize,
        })
    }

    /// Adds `options` to the database (overriding earlier values of the same keys); solvers
    /// built afterwards read them (a [`crate::PetscSolver`] reads the database at each
    /// `factor`).
    ///
    /// # Errors
    /// [`PetscError::InvalidOptions`] for a string with a NUL byte; [`PetscError::Call`].
    pub fn insert_options(&self, options: &str) -> Result<(), PetscError> {
        let c = CString::new(options).map_err(|_| PetscError::InvalidOptions {
            value: options.to_owned(),
            allowed: "PETSc options without NUL bytes",
        })?;
        // SAFETY: PETSc is running (self exists); the string outlives the call.
        unsafe {
            check(
                sys::PetscOptionsInsertString(core::ptr::null_mut(), c.as_ptr()),
                "PetscOptionsInsertString",
            )
        }
    }

    /// This process's rank in `PETSC_COMM_WORLD` (0-based).
    pub fn rank(&self) -> usize {
        self.rank
    }

    /// The number of ranks.
    pub fn size(&self) -> usize {
        self.size
    }

    /// Peak resident memory of this process so far, bytes, as PETSc measures it
    /// (`PetscMemoryGetMaximumUsage`; 0 where the platform gives none).
    ///
    /// # Errors
    /// [`PetscError::Call`].
    pub fn peak_memory(&self) -> Result<f64, PetscError> {
        let mut bytes = 0.0;
        // SAFETY: PETSc is running (self exists).
        unsafe {
            check(
                sys::PetscMemoryGetMaximumUsage(&mut bytes),
                "PetscMemoryGetMaximumUsage",
            )?;
        }
        Ok(bytes)
    }
}

/// `Ok` on the thread that started the [`Session`] (or before any session), else
/// [`PetscError::WrongThread`]: collective PETSc calls from a second thread would interleave
/// with the first thread's differently on different ranks (an MPI error, or a hang).
///
/// # Errors
/// [`PetscError::WrongThread`] naming `what`.
pub(crate) fn on_session_thread(what: &'static str) -> Result<(), PetscError> {
    match THREAD.get() {
        Some(&id) if id != std::thread::current().id() => Err(PetscError::WrongThread { what }),
        _ => Ok(()),
    }
}

/// The boolean option `-name` of PETSc's options database: `Some(value)` when it is set,
/// `None` when not (PETSc must be running).
///
/// # Errors
/// PETSc's error of `PetscOptionsGetBool`.
pub(crate) fn option_bool(name: &str) -> Result<Option<bool>, PetscError> {
    let name = CString::new(name).expect("option names have no NUL");
    let (mut value, mut set) = (0, 0);
    // SAFETY: the caller runs PETSc; the name outlives the call.
    unsafe {
        check(
            sys::PetscOptionsGetBool(
                core::ptr::null_mut(),
                core::ptr::null(),
                name.as_ptr(),
                &mut value,
                &mut set,
            ),
            "PetscOptionsGetBool",
        )?;
    }
    Ok((set != 0).then_some(value != 0))
}

/// Whether PETSc is running (started and not finalised).
pub fn running() -> bool {
    let (mut started, mut finalised) = (0, 0);
    // SAFETY: both may be called at any time, before initialisation and after finalisation.
    unsafe {
        sys::PetscInitialized(&mut started);
        sys::PetscFinalized(&mut finalised);
    }
    started != 0 && finalised == 0
}

impl Drop for Session {
    fn drop(&mut self) {
        // SAFETY: PETSc was started by this session; objects still alive afterwards are
        // leaked by their own Drop (they check `running`).
        unsafe {
            sys::PetscFinalize();
        }
    }
}
