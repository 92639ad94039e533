//! [`PetscSolver`]: capstan's [`LinearSolver`] over a distributed PETSc matrix and KSP.

use core::ffi::{c_int, c_void};
use std::ffi::CString;
use std::sync::Arc;

use capstan_petsc_sys as sys;
use capstan_solvers::{
    BackendKind, BoxedLinearSolver, LinearContext, LinearSettings, LinearSolver, NearNullSpace,
    Observer, Progress, RegisteredLinearSolver, SolveStage, SolverError, SparsityPattern,
};

use crate::error::{PetscError, check, diverged_name};
use crate::policy::{FORCING_ETA_MAX_OPTION, FORCING_OPTION, PC_LAG_OPTION, StepPolicy};
use crate::session::{on_session_thread, option_bool, running};

/// The name of the backend in `solver.linear`.
pub const NAME: &str = "petsc";

/// The backend's entry for `capstan_solvers::linear_registry::register` (a program registers
/// it once, after opening the PETSc [`crate::Session`]): `solver.linear = "petsc"` then
/// reaches both contact solvers like the built-ins. It reads its settings from PETSc's options
/// database (`solver.petsc_options`), not from [`LinearSettings`].
pub const REGISTRATION: RegisteredLinearSolver = RegisteredLinearSolver {
    name: NAME,
    summary: "PETSc KSP over the MPI ranks (default GMRES + GAMG to 1e-8; options from solver.petsc_options)",
    parameters: &[],
    kind: BackendKind::Krylov,
    build: build_boxed,
};

fn build_boxed(
    _: &LinearSettings,
    context: &dyn LinearContext,
) -> Result<BoxedLinearSolver, SolverError> {
    let solver = PetscSolver::new()?;
    Ok(Box::new(match context.near_null_space() {
        Some(space) => solver.with_near_null_space(space),
        None => solver,
    }))
}

/// The PETSc option that turns the near-null space and block size off
/// (`solver.petsc_options = "-capstan_near_null_space false"`; default true).
pub const NEAR_NULL_OPTION: &str = "-capstan_near_null_space";

pub use capstan_solvers::row_distribution::{owned_blocks, owned_rows};

fn index(value: usize, quantity: &'static str) -> Result<sys::PetscInt, PetscError> {
    sys::PetscInt::try_from(value).map_err(|_| PetscError::IndexOverflow {
        quantity,
        value,
        bits: sys::PetscInt::BITS,
    })
}

/// The PETSc objects of one analysed pattern.
struct Objects {
    mat: sys::Mat,
    ksp: sys::KSP,
    x: sys::Vec,
    b: sys::Vec,
    scatter: sys::VecScatter,
    all: sys::Vec,
}

impl Drop for Objects {
    fn drop(&mut self) {
        if !running() {
            return; // PETSc is finalised: its memory went with it
        }
        // SAFETY: each handle was created by PETSc in `analyse` and is destroyed once.
        unsafe {
            sys::KSPDestroy(&mut self.ksp);
            sys::VecScatterDestroy(&mut self.scatter);
            sys::VecDestroy(&mut self.all);
            sys::VecDestroy(&mut self.x);
            sys::VecDestroy(&mut self.b);
            sys::MatDestroy(&mut self.mat);
        }
    }
}

/// The residual norms of the current KSP solve, as PETSc's monitor reports them.
#[derive(Default)]
struct Monitor {
    norms: Vec<f64>,
}

unsafe extern "C" fn monitor(
    _ksp: sys::KSP,
    _iteration: sys::PetscInt,
    norm: sys::PetscReal,
    context: *mut c_void,
) -> sys::PetscErrorCode {
    // SAFETY: `context` is the `Monitor` boxed in the `PetscSolver` that set this monitor and
    // outlives its KSP.
    let m = unsafe { &mut *context.cast::<Monitor>() };
    m.norms.push(norm);
    0
}

/// A [`LinearSolver`] that hands `A x = b` to PETSc: `A` a distributed AIJ matrix of which
/// each MPI rank owns a contiguous block of rows ([`owned_rows`]), solved by KSP with the
/// options of the [`crate::Session`] (default [`crate::DEFAULT_OPTIONS`]: GMRES + GAMG).
///
/// Every rank calls every method with the same pattern and values (each rank's rows read);
/// `solve_in_place` takes the whole right-hand side and gives every rank the whole solution
/// (`VecScatterCreateToAll`, made at the first such solve), `solve_owned_in_place_observed`
/// takes and gives only the rank's rows (a Newton on owned rows:
/// `capstan_solvers::DistributedNewton`).
///
/// # Math
/// ```text
/// analyse: rows first..end of rank r; per row, d_nnz = entries with first <= col < end,
///          o_nnz = the others (exact MPIAIJ preallocation, new non-zeros are an error)
/// factor:  MatSetValues row by row, MatAssembly, KSPSetOperators (PC rebuilt at the solve)
/// solve:   KSPSolve to |b - A x| <= rtol |b| (left-preconditioned norm for GMRES), then
///          x gathered to every rank
/// ```
///
/// # Example
/// ```
/// use capstan_petsc::{PetscSolver, Session};
/// use capstan_solvers::{LinearSolver, SparsityPattern};
/// let session = Session::start("-ksp_type cg -pc_type jacobi").unwrap();
/// let (pattern, slots) =
///     SparsityPattern::from_entries(2, 2, &[(0, 0), (1, 0), (0, 1), (1, 1)]).unwrap();
/// let mut values = vec![0.0; pattern.nnz()];
/// for (k, v) in [4.0, 1.0, 1.0, 3.0].into_iter().enumerate() {
///     values[slots[k]] += v;
/// }
/// let mut solver = PetscSolver::new().unwrap();
/// solver.analyse(&pattern).unwrap();
/// solver.factor(&values).unwrap();
/// let mut x = vec![1.0, 2.0];
/// solver.solve_in_place(&mut x).unwrap();
/// assert!((x[0] - 1.0 / 11.0).abs() < 1e-8);
/// drop(session);
/// ```
/// # Errors
/// KSP's budget (`-ksp_max_it`) spent: [`SolverError::BudgetSpent`] naming
/// `solver.petsc_options -ksp_max_it`; a failed preconditioner (e.g. a zero pivot of LU):
/// [`SolverError::Singular`]; other divergence and PETSc failures:
/// [`SolverError::External`] around a [`PetscError`].
pub struct PetscSolver {
    n: usize,
    rows: core::ops::Range<usize>,
    /// Owned rows in CSR: `row_ptr` (length rows + 1), global columns, CSC slots.
    row_ptr: Vec<usize>,
    cols: Vec<sys::PetscInt>,
    slots: Vec<usize>,
    row_values: Vec<f64>,
    objects: Option<Objects>,
    factored: bool,
    monitor: Box<Monitor>,
    last_iterations: Option<usize>,
    rank: usize,
    size: usize,
    /// Given to GAMG: `MatSetBlockSize` and `MatSetNearNullSpace`.
    near_null_space: Option<Arc<NearNullSpace>>,
    /// Whether `MatSetBlockSize` is called (not under `-capstan_near_null_space false`).
    tell_block_size: bool,
    /// Eisenstat–Walker forcing and preconditioner lagging across the Newton steps.
    policy: StepPolicy,
    /// The reductions of the solves on owned rows (the norm of `b`, a non-finite entry on
    /// any rank), made on first use.
    reductions: Option<crate::distribution::PetscDistribution>,
}

// SAFETY: the PETSc handles are owned by this value alone and used from one thread at a time
// (`&mut self`); MPI is initialised single-threaded, so the caller keeps all PETSc work on one
// thread (capstan's Newton iteration runs on the calling thread).
unsafe impl Send for PetscSolver {}

impl core::fmt::Debug for PetscSolver {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("PetscSolver")
            .field("n", &self.n)
            .field("rows", &self.rows)
            .field("rank", &self.rank)
            .field("size", &self.size)
            .finish_non_exhaustive()
    }
}

impl PetscSolver {
    /// A solver on `PETSC_COMM_WORLD`.
    ///
    /// # Errors
    /// [`PetscError::NotStarted`] without a running [`crate::Session`];
    /// [`PetscError::WrongThread`] on a thread other than the session's.
    pub fn new() -> Result<Self, PetscError> {
        if !running() {
            return Err(PetscError::NotStarted);
        }
        on_session_thread("PetscSolver::new")?;
        let (mut rank, mut size): (c_int, c_int) = (0, 1);
        // SAFETY: PETSc (hence MPI) is running.
        unsafe {
            check(
                sys::MPI_Comm_rank(sys::PETSC_COMM_WORLD, &mut rank),
                "MPI_Comm_rank",
            )?;
            check(
                sys::MPI_Comm_size(sys::PETSC_COMM_WORLD, &mut size),
                "MPI_Comm_size",
            )?;
        }
        Ok(Self {
            n: 0,
            rows: 0..0,
            row_ptr: Vec::new(),
            cols: Vec::new(),
            slots: Vec::new(),
            row_values: Vec::new(),
            objects: None,
            factored: false,
            monitor: Box::default(),
            last_iterations: None,
            rank: rank as usize,
            size: size as usize,
            near_null_space: None,
            tell_block_size: true,
            policy: StepPolicy::off(),
            reductions: None,
        })
    }

    /// The solver telling PETSc the unknowns per node and the near-null space of its matrices
    /// (`MatSetBlockSize`, `MatSetNearNullSpace`: GAMG builds its coarse spaces from them;
    /// without, it assumes one unknown per node and the constant vector). The vectors are
    /// orthonormalised (Gram–Schmidt, twice) before PETSc gets them; rows are owned in whole
    /// blocks ([`owned_blocks`]). Checked against the pattern at [`LinearSolver::analyse`].
    #[must_use]
    pub fn with_near_null_space(mut self, space: Arc<NearNullSpace>) -> Self {
        self.near_null_space = Some(space);
        self
    }

    /// The unknowns per node PETSc is told (1 without a near-null space).
    fn block_size(&self) -> usize {
        self.near_null_space.as_ref().map_or(1, |z| z.block_size)
    }

    /// Drops the near-null vectors and the block size when the options database says
    /// `-capstan_near_null_space false` (for comparisons: GAMG then coarsens as for a scalar
    /// problem); the rows stay owned in whole nodes.
    fn read_near_null_option(&mut self) -> Result<(), PetscError> {
        if option_bool(NEAR_NULL_OPTION)? == Some(false) {
            // the rows stay owned in whole nodes (as the caller may have assembled them)
            self.near_null_space = self.near_null_space.take().map(|z| {
                Arc::new(NearNullSpace {
                    block_size: z.block_size,
                    vectors: Vec::new(),
                })
            });
            self.tell_block_size = false;
        }
        Ok(())
    }

    /// The forcing and lagging policy of the options database ([`FORCING_OPTION`], default
    /// false, with [`FORCING_ETA_MAX_OPTION`], default 0.9; [`PC_LAG_OPTION`], default 0: off).
    fn read_policy_options(&mut self) -> Result<(), SolverError> {
        let forcing_name = CString::new(FORCING_OPTION).expect("no NUL");
        let lag_name = CString::new(PC_LAG_OPTION).expect("no NUL");
        let eta_name = CString::new(FORCING_ETA_MAX_OPTION).expect("no NUL");
        let (mut eta_max, mut eta_set) = (0.9, 0);
        let (mut forcing, mut forcing_set) = (0, 0);
        let (mut lag, mut lag_set) = (0.0, 0);
        // SAFETY: PETSc is running (checked in `new`); the names outlive the calls.
        unsafe {
            check(
                sys::PetscOptionsGetBool(
                    core::ptr::null_mut(),
                    core::ptr::null(),
                    forcing_name.as_ptr(),
                    &mut forcing,
                    &mut forcing_set,
                ),
                "PetscOptionsGetBool",
            )?;
            check(
                sys::PetscOptionsGetReal(
                    core::ptr::null_mut(),
                    core::ptr::null(),
                    lag_name.as_ptr(),
                    &mut lag,
                    &mut lag_set,
                ),
                "PetscOptionsGetReal",
            )?;
            check(
                sys::PetscOptionsGetReal(
                    core::ptr::null_mut(),
                    core::ptr::null(),
                    eta_name.as_ptr(),
                    &mut eta_max,
                    &mut eta_set,
                ),
                "PetscOptionsGetReal",
            )?;
        }
        let forcing = (forcing_set != 0 && forcing != 0).then_some(eta_max);
        self.policy = StepPolicy::new(forcing, lag)?;
        Ok(())
    }

    /// The rows this rank owns (after [`LinearSolver::analyse`]).
    pub fn owned(&self) -> core::ops::Range<usize> {
        self.rows.clone()
    }

    /// The residual norms PETSc's monitor reported in the last solve (iteration 0 first).
    pub fn last_residuals(&self) -> &[f64] {
        &self.monitor.norms
    }

    fn create(&mut self) -> Result<Objects, PetscError> {
        let local = self.rows.len();
        let (first, end) = (self.rows.start, self.rows.end);
        let mut d_nnz = Vec::with_capacity(local);
        let mut o_nnz = Vec::with_capacity(local);
        for i in 0..local {
            let cols = &self.cols[self.row_ptr[i]..self.row_ptr[i + 1]];
            let d = cols
                .iter()
                .filter(|&&c| (first..end).contains(&(c as usize)))
                .count();
            d_nnz.push(index(d, "row entries")?);
            o_nnz.push(index(cols.len() - d, "row entries")?);
        }
        let n = index(self.n, "unknowns")?;
        let local = index(local, "owned rows")?;
        let aij = CString::new("aij").expect("no NUL");
        let mut o = Objects {
            mat: core::ptr::null_mut(),
            ksp: core::ptr::null_mut(),
            x: core::ptr::null_mut(),
            b: core::ptr::null_mut(),
            scatter: core::ptr::null_mut(),
            all: core::ptr::null_mut(),
        };
        // SAFETY: PETSc is running; every out-pointer is a field of `o`, destroyed by its Drop
        // (null handles are ignored by PETSc's destroy functions).
        unsafe {
            let comm = sys::PETSC_COMM_WORLD;
            check(sys::MatCreate(comm, &mut o.mat), "MatCreate")?;
            check(sys::MatSetSizes(o.mat, local, local, n, n), "MatSetSizes")?;
            check(sys::MatSetType(o.mat, aij.as_ptr()), "MatSetType")?;
            let block = self.block_size();
            if block > 1 && self.tell_block_size {
                check(
                    sys::MatSetBlockSize(o.mat, index(block, "block size")?),
                    "MatSetBlockSize",
                )?;
            }
            // Whichever applies (one rank: SeqAIJ; more: MPIAIJ); the other is a no-op.
            check(
                sys::MatSeqAIJSetPreallocation(o.mat, 0, d_nnz.as_ptr()),
                "MatSeqAIJSetPreallocation",
            )?;
            check(
                sys::MatMPIAIJSetPreallocation(o.mat, 0, d_nnz.as_ptr(), 0, o_nnz.as_ptr()),
                "MatMPIAIJSetPreallocation",
            )?;
            check(
                sys::MatSetOption(o.mat, sys::MAT_NEW_NONZERO_ALLOCATION_ERR, 1),
                "MatSetOption",
            )?;
            check(
                sys::MatCreateVecs(o.mat, &mut o.x, &mut o.b),
                "MatCreateVecs",
            )?;
            if let Some(space) = &self.near_null_space
                && !space.vectors.is_empty()
            {
                self.set_near_null_space(o.mat, o.x, space)?;
            }
            check(sys::KSPCreate(comm, &mut o.ksp), "KSPCreate")?;
            let context: *mut Monitor = &mut *self.monitor;
            check(
                sys::KSPMonitorSet(o.ksp, Some(monitor), context.cast(), None),
                "KSPMonitorSet",
            )?;
        }
        Ok(o)
    }

    /// Gives `mat` the near-null space `space`: each vector's owned rows into a vector laid
    /// out like `like`, orthonormalised by classical Gram–Schmidt applied twice (PETSc's
    /// `MatNullSpaceCreate` wants orthonormal vectors), dependent ones dropped.
    ///
    /// # Safety
    /// `mat` and `like` are live PETSc objects of this solver's layout.
    unsafe fn set_near_null_space(
        &self,
        mat: sys::Mat,
        like: sys::Vec,
        space: &NearNullSpace,
    ) -> Result<(), PetscError> {
        let mut basis: Vec<sys::Vec> = Vec::with_capacity(space.vectors.len());
        let result = (|| -> Result<(), PetscError> {
            for z in &space.vectors {
                let mut v: sys::Vec = core::ptr::null_mut();
                // SAFETY: `like` is live; `v` is destroyed below; the local array has the
                // owned rows' length.
                unsafe {
                    check(sys::VecDuplicate(like, &mut v), "VecDuplicate")?;
                    basis.push(v);
                    let mut a: *mut f64 = core::ptr::null_mut();
                    check(sys::VecGetArray(v, &mut a), "VecGetArray")?;
                    core::slice::from_raw_parts_mut(a, self.rows.len())
                        .copy_from_slice(&z[self.rows.clone()]);
                    check(sys::VecRestoreArray(v, &mut a), "VecRestoreArray")?;
                    let mut first = 0.0;
                    check(sys::VecNormalize(v, &mut first), "VecNormalize")?;
                    let kept = basis.len() - 1;
                    for _pass in 0..2 {
                        for &q in &basis[..kept] {
                            let mut d = 0.0;
                            check(sys::VecDot(v, q, &mut d), "VecDot")?;
                            check(sys::VecAXPY(v, -d, q), "VecAXPY")?;
                        }
                    }
                    let mut norm = 0.0;
                    check(sys::VecNormalize(v, &mut norm), "VecNormalize")?;
                    if norm.is_nan() || norm <= 1e-10 {
                        // dependent on the earlier ones (or zero): not a new direction
                        let mut v = basis.pop().expect("just pushed");
                        sys::VecDestroy(&mut v);
                    }
                }
            }
            let mut nsp: sys::MatNullSpace = core::ptr::null_mut();
            // SAFETY: the vectors are live and orthonormal; the null space keeps its own
            // references, so destroying ours afterwards is right.
            unsafe {
                check(
                    sys::MatNullSpaceCreate(
                        sys::PETSC_COMM_WORLD,
                        0,
                        index(basis.len(), "near-null vectors")?,
                        basis.as_ptr(),
                        &mut nsp,
                    ),
                    "MatNullSpaceCreate",
                )?;
                let set = check(sys::MatSetNearNullSpace(mat, nsp), "MatSetNearNullSpace");
                sys::MatNullSpaceDestroy(&mut nsp);
                set
            }
        })();
        for v in &mut basis {
            // SAFETY: each was created by VecDuplicate above and is destroyed once.
            unsafe {
                sys::VecDestroy(v);
            }
        }
        result
    }

    fn solve_observed(
        &mut self,
        rhs: &mut [f64],
        observer: &mut dyn Observer<f64>,
    ) -> Result<(), SolverError> {
        let Some(o) = self.objects.as_ref().filter(|_| self.factored) else {
            return Err(SolverError::CallOrder {
                called: "solve_in_place",
                requires: "factor",
            });
        };
        if rhs.len() != self.n {
            return Err(SolverError::DimensionMismatch {
                quantity: "rhs",
                expected: self.n,
                found: rhs.len(),
            });
        }
        if let Some(index) = rhs.iter().position(|v| !v.is_finite()) {
            return Err(SolverError::NonFinite {
                quantity: "right-hand side",
                index,
                iteration: None,
            });
        }
        // SAFETY: the handle is live; the array is borrowed between Get/Restore only and has
        // the local length PETSc created it with.
        unsafe {
            let mut b: *mut f64 = core::ptr::null_mut();
            check(sys::VecGetArray(o.b, &mut b), "VecGetArray")?;
            core::slice::from_raw_parts_mut(b, self.rows.len())
                .copy_from_slice(&rhs[self.rows.clone()]);
            check(sys::VecRestoreArray(o.b, &mut b), "VecRestoreArray")?;
        }
        // the forcing term (rhs is whole on every rank: the same on all)
        let rhs_norm = rhs.iter().map(|v| v * v).sum::<f64>().sqrt();
        self.ksp_run(rhs_norm, observer)?;
        let o = self.objects.as_mut().expect("checked above");
        // SAFETY: as above; `all` holds all n entries on every rank after the scatter (made
        // at the first solve of a whole vector: a Newton on owned rows never makes it).
        unsafe {
            if o.scatter.is_null() {
                check(
                    sys::VecScatterCreateToAll(o.x, &mut o.scatter, &mut o.all),
                    "VecScatterCreateToAll",
                )?;
            }
            check(
                sys::VecScatterBegin(
                    o.scatter,
                    o.x,
                    o.all,
                    sys::INSERT_VALUES,
                    sys::SCATTER_FORWARD,
                ),
                "VecScatterBegin",
            )?;
            check(
                sys::VecScatterEnd(
                    o.scatter,
                    o.x,
                    o.all,
                    sys::INSERT_VALUES,
                    sys::SCATTER_FORWARD,
                ),
                "VecScatterEnd",
            )?;
            let mut x: *const f64 = core::ptr::null();
            check(sys::VecGetArrayRead(o.all, &mut x), "VecGetArrayRead")?;
            rhs.copy_from_slice(core::slice::from_raw_parts(x, self.n));
            check(
                sys::VecRestoreArrayRead(o.all, &mut x),
                "VecRestoreArrayRead",
            )?;
        }
        if let Some(index) = rhs.iter().position(|v| !v.is_finite()) {
            return Err(SolverError::NonFinite {
                quantity: "solution",
                index,
                iteration: None,
            });
        }
        Ok(())
    }
    /// KSP on the right-hand side already in `o.b` (`rhs_norm` its global 2-norm, for the
    /// forcing term), with the preconditioner policy; the iterations reported to `observer`;
    /// the solution in `o.x`.
    fn ksp_run(
        &mut self,
        rhs_norm: f64,
        observer: &mut dyn Observer<f64>,
    ) -> Result<(), SolverError> {
        let o = self
            .objects
            .as_ref()
            .expect("a factored solver has its objects");
        let (mut rtol, mut atol, mut dtol, mut max_it) = (0.0, 0.0, 0.0, 0);
        // SAFETY: the KSP is live.
        unsafe {
            check(
                sys::KSPGetTolerances(o.ksp, &mut rtol, &mut atol, &mut dtol, &mut max_it),
                "KSPGetTolerances",
            )?;
        }
        let eta = self.policy.tolerance(rhs_norm, rtol);
        let (mut reason, mut iterations) =
            ksp_solve(o, &mut self.monitor, eta, (rtol, atol, dtol, max_it))?;
        let mut reduction = reduction(&self.monitor.norms);
        self.policy.solved(iterations, reduction, reason < 0);
        if reason < 0 && !self.policy.fresh() {
            // a kept preconditioner that no longer serves: rebuild it and solve again
            let previous = iterations;
            // SAFETY: the KSP is live.
            unsafe {
                check(
                    sys::KSPSetReusePreconditioner(o.ksp, 0),
                    "KSPSetReusePreconditioner",
                )?;
            }
            self.policy.rebuilt();
            (reason, iterations) =
                ksp_solve(o, &mut self.monitor, eta, (rtol, atol, dtol, max_it))?;
            reduction = self::reduction(&self.monitor.norms);
            self.policy.solved(iterations, reduction, reason < 0);
            iterations += previous;
        }
        self.last_iterations = Some(iterations);
        let norms = &self.monitor.norms;
        let r0 = norms.first().copied().unwrap_or(0.0);
        let relative = |r: f64| if r0 > 0.0 { r / r0 } else { r };
        for (k, &r) in norms.iter().enumerate().skip(1) {
            observer.iteration(&Progress::new(SolveStage::Krylov, k, relative(r), 1.0));
        }
        if observer.interrupted() {
            return Err(SolverError::Interrupted {
                iteration: iterations,
            });
        }
        if reason < 0 {
            let last = relative(norms.last().copied().unwrap_or(f64::INFINITY));
            return Err(match reason {
                sys::KSP_DIVERGED_ITS => SolverError::BudgetSpent {
                    field: "solver.petsc_options -ksp_max_it",
                    iterations,
                    residual: last,
                    tolerance: rtol,
                },
                sys::KSP_DIVERGED_PC_FAILED => SolverError::Singular { pivot: None },
                _ => PetscError::Diverged {
                    reason,
                    name: diverged_name(reason),
                    iterations,
                }
                .into(),
            });
        }
        Ok(())
    }

    /// [`LinearSolver::solve_owned_in_place_observed`]: `b` and `x` as this rank's rows only
    /// (no gather of the solution).
    fn solve_owned(
        &mut self,
        first: usize,
        rhs: &mut [f64],
        observer: &mut dyn Observer<f64>,
    ) -> Result<(), SolverError> {
        let Some(o) = self.objects.as_ref().filter(|_| self.factored) else {
            return Err(SolverError::CallOrder {
                called: "solve_owned_in_place_observed",
                requires: "factor",
            });
        };
        if first != self.rows.start || rhs.len() != self.rows.len() {
            return Err(SolverError::DimensionMismatch {
                quantity: "rhs (owned rows)",
                expected: self.rows.len(),
                found: rhs.len(),
            });
        }
        // SAFETY: the handle is live; the array is borrowed between Get/Restore only and has
        // the local length PETSc created it with.
        unsafe {
            let mut b: *mut f64 = core::ptr::null_mut();
            check(sys::VecGetArray(o.b, &mut b), "VecGetArray")?;
            core::slice::from_raw_parts_mut(b, rhs.len()).copy_from_slice(rhs);
            check(sys::VecRestoreArray(o.b, &mut b), "VecRestoreArray")?;
        }
        let local_bad = rhs.iter().position(|v| !v.is_finite());
        let norm = self.global_sum(if local_bad.is_some() {
            f64::INFINITY
        } else {
            rhs.iter().map(|v| v * v).sum::<f64>()
        })?;
        if !norm.is_finite() {
            // on every rank the same error: the first non-finite entry over all of them
            let index = self.first_over_ranks(local_bad.map(|i| first + i))?;
            return Err(SolverError::NonFinite {
                quantity: "right-hand side",
                index: index.unwrap_or(first),
                iteration: None,
            });
        }
        self.ksp_run(norm.sqrt(), observer)?;
        let o = self.objects.as_ref().expect("checked above");
        // SAFETY: as above, for `x`.
        unsafe {
            let mut x: *const f64 = core::ptr::null();
            check(sys::VecGetArrayRead(o.x, &mut x), "VecGetArrayRead")?;
            rhs.copy_from_slice(core::slice::from_raw_parts(x, rhs.len()));
            check(sys::VecRestoreArrayRead(o.x, &mut x), "VecRestoreArrayRead")?;
        }
        let local_bad = rhs.iter().position(|v| !v.is_finite());
        if let Some(index) = self.first_over_ranks(local_bad.map(|i| first + i))? {
            return Err(SolverError::NonFinite {
                quantity: "solution",
                index,
                iteration: None,
            });
        }
        Ok(())
    }

    /// The reductions over the ranks, made on first use.
    fn reductions(&mut self) -> Result<&crate::distribution::PetscDistribution, SolverError> {
        if self.reductions.is_none() {
            self.reductions = Some(crate::distribution::PetscDistribution::of_running(
                self.rank, self.size,
            )?);
        }
        Ok(self.reductions.as_ref().expect("just made"))
    }

    /// `value` summed over the ranks (collective).
    fn global_sum(&mut self, value: f64) -> Result<f64, SolverError> {
        use capstan_solvers::row_distribution::RowDistribution;
        self.reductions()?.sum(value)
    }

    /// The smallest of the ranks' global indices (`None` on a rank: none there); collective.
    fn first_over_ranks(&mut self, local: Option<usize>) -> Result<Option<usize>, SolverError> {
        use capstan_solvers::row_distribution::RowDistribution;
        let value = local.map_or(f64::NEG_INFINITY, |i| -(i as f64));
        let max = self.reductions()?.max(value)?;
        Ok((max > f64::NEG_INFINITY).then(|| (-max) as usize))
    }
}

impl LinearSolver<f64> for PetscSolver {
    fn analyse(&mut self, pattern: &SparsityPattern) -> Result<(), SolverError> {
        if !pattern.is_square() {
            return Err(SolverError::NotSquare {
                nrows: pattern.nrows(),
                ncols: pattern.ncols(),
            });
        }
        self.objects = None;
        self.factored = false;
        self.n = pattern.nrows();
        self.read_near_null_option()?;
        self.read_policy_options()?;
        if let Some(space) = &self.near_null_space {
            space.check(self.n)?;
        }
        self.rows = owned_blocks(self.n, self.block_size(), self.rank, self.size);
        let (row_ptr, col_idx, slot) = pattern.row_layout();
        let (lo, hi) = (row_ptr[self.rows.start], row_ptr[self.rows.end]);
        self.row_ptr = row_ptr[self.rows.start..=self.rows.end]
            .iter()
            .map(|p| p - lo)
            .collect();
        self.cols = col_idx[lo..hi]
            .iter()
            .map(|&c| index(c, "column"))
            .collect::<Result<_, _>>()?;
        self.slots = slot[lo..hi].to_vec();
        self.row_values = vec![0.0; hi - lo];
        self.objects = Some(self.create()?);
        Ok(())
    }

    fn factor(&mut self, values: &[f64]) -> Result<(), SolverError> {
        let Some(o) = self.objects.as_ref() else {
            return Err(SolverError::CallOrder {
                called: "factor",
                requires: "analyse",
            });
        };
        self.factored = false;
        if let Some(&max) = self.slots.iter().max()
            && max >= values.len()
        {
            return Err(SolverError::DimensionMismatch {
                quantity: "values",
                expected: max + 1,
                found: values.len(),
            });
        }
        if let Some(index) = values.iter().position(|v| !v.is_finite()) {
            return Err(SolverError::NonFinite {
                quantity: "matrix value",
                index,
                iteration: None,
            });
        }
        for (v, &s) in self.row_values.iter_mut().zip(&self.slots) {
            *v = values[s];
        }
        // SAFETY: live handles; each row's columns and values are slices of equal length.
        unsafe {
            for (i, row) in self.rows.clone().enumerate() {
                let (a, b) = (self.row_ptr[i], self.row_ptr[i + 1]);
                let global = row as sys::PetscInt;
                check(
                    sys::MatSetValues(
                        o.mat,
                        1,
                        &global,
                        (b - a) as sys::PetscInt,
                        self.cols[a..b].as_ptr(),
                        self.row_values[a..b].as_ptr(),
                        sys::INSERT_VALUES,
                    ),
                    "MatSetValues",
                )?;
            }
            check(
                sys::MatAssemblyBegin(o.mat, sys::MAT_FINAL_ASSEMBLY),
                "MatAssemblyBegin",
            )?;
            check(
                sys::MatAssemblyEnd(o.mat, sys::MAT_FINAL_ASSEMBLY),
                "MatAssemblyEnd",
            )?;
            check(sys::KSPSetOperators(o.ksp, o.mat, o.mat), "KSPSetOperators")?;
            check(sys::KSPSetFromOptions(o.ksp), "KSPSetFromOptions")?;
            let reuse = self.policy.reuse_for_new_matrix();
            check(
                sys::KSPSetReusePreconditioner(o.ksp, sys::PetscBool::from(reuse)),
                "KSPSetReusePreconditioner",
            )?;
        }
        self.factored = true;
        Ok(())
    }

    fn solve_in_place(&mut self, rhs: &mut [f64]) -> Result<(), SolverError> {
        self.solve_observed(rhs, &mut capstan_solvers::SilentObserver)
    }

    fn solve_in_place_observed(
        &mut self,
        rhs: &mut [f64],
        observer: &mut dyn Observer<f64>,
    ) -> Result<(), SolverError> {
        self.solve_observed(rhs, observer)
    }

    fn last_iterations(&self) -> Option<usize> {
        self.last_iterations
    }

    fn solve_owned_in_place_observed(
        &mut self,
        first: usize,
        rhs: &mut [f64],
        observer: &mut dyn Observer<f64>,
    ) -> Result<(), SolverError> {
        self.solve_owned(first, rhs, observer)
    }
}

/// One `KSPSolve` of the right-hand side in `o.b` to the relative tolerance `eta` (the other
/// tolerances as `(rtol, atol, dtol, max_it)`, restored afterwards): the converged reason and
/// the iterations.
fn ksp_solve(
    o: &Objects,
    monitor: &mut Monitor,
    eta: f64,
    (rtol, atol, dtol, max_it): (f64, f64, f64, sys::PetscInt),
) -> Result<(c_int, usize), PetscError> {
    let (mut reason, mut iterations): (c_int, sys::PetscInt) = (0, 0);
    monitor.norms.clear();
    // SAFETY: the handles are live.
    unsafe {
        check(
            sys::KSPSetTolerances(o.ksp, eta, atol, dtol, max_it),
            "KSPSetTolerances",
        )?;
        let solved = check(sys::KSPSolve(o.ksp, o.b, o.x), "KSPSolve");
        check(
            sys::KSPSetTolerances(o.ksp, rtol, atol, dtol, max_it),
            "KSPSetTolerances",
        )?;
        solved?;
        check(
            sys::KSPGetConvergedReason(o.ksp, &mut reason),
            "KSPGetConvergedReason",
        )?;
        check(
            sys::KSPGetIterationNumber(o.ksp, &mut iterations),
            "KSPGetIterationNumber",
        )?;
    }
    Ok((reason, iterations as usize))
}

/// The monitored residual's reduction `r_last / r_0` of a solve (1 without iterations).
fn reduction(norms: &[f64]) -> f64 {
    match (norms.first(), norms.last()) {
        (Some(&r0), Some(&r)) if r0 > 0.0 => r / r0,
        _ => 1.0,
    }
}
