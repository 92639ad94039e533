//! The declarations (feature `petsc`).

use core::ffi::{c_char, c_int, c_void};

/// `PetscInt`: the index type of the installed PETSc (`PETSC_USE_64BIT_INDICES` gives `i64`).
#[cfg(not(petsc_int64))]
pub type PetscInt = i32;
/// `PetscInt`: the index type of the installed PETSc (`PETSC_USE_64BIT_INDICES` gives `i64`).
#[cfg(petsc_int64)]
pub type PetscInt = i64;
/// `PetscScalar` of a real double-precision build (checked by `build.rs`).
pub type PetscScalar = f64;
/// `PetscReal` of a double-precision build.
pub type PetscReal = f64;
/// `PetscLogDouble`.
pub type PetscLogDouble = f64;
/// `PetscErrorCode`: 0 on success.
pub type PetscErrorCode = c_int;
/// `PetscBool` (`PETSC_FALSE = 0`, `PETSC_TRUE = 1`).
pub type PetscBool = c_int;
/// `MPI_Comm` of Open MPI: a pointer to `struct ompi_communicator_t`.
pub type MPI_Comm = *mut c_void;

/// Opaque `struct _p_Mat`.
#[repr(C)]
pub struct _p_Mat {
    _private: [u8; 0],
}
/// Opaque `struct _p_Vec`.
#[repr(C)]
pub struct _p_Vec {
    _private: [u8; 0],
}
/// Opaque `struct _p_KSP`.
#[repr(C)]
pub struct _p_KSP {
    _private: [u8; 0],
}
/// Opaque `struct _p_PetscSF` (a `VecScatter`).
#[repr(C)]
pub struct _p_PetscSF {
    _private: [u8; 0],
}
/// Opaque `struct _p_MatNullSpace`.
#[repr(C)]
pub struct _p_MatNullSpace {
    _private: [u8; 0],
}
/// Opaque `struct _p_IS`.
#[repr(C)]
pub struct _p_IS {
    _private: [u8; 0],
}
/// Opaque C `FILE`.
#[repr(C)]
pub struct FILE {
    _private: [u8; 0],
}
/// `Mat`.
pub type Mat = *mut _p_Mat;
/// `MatNullSpace`.
pub type MatNullSpace = *mut _p_MatNullSpace;
/// `Vec`.
pub type Vec = *mut _p_Vec;
/// `KSP`.
pub type KSP = *mut _p_KSP;
/// `VecScatter` (`PetscSF`).
pub type VecScatter = *mut _p_PetscSF;
/// `IS`: an index set.
pub type IS = *mut _p_IS;

/// `PETSC_DECIDE`: let PETSc choose.
pub const PETSC_DECIDE: PetscInt = -1;
/// `PETSC_DEFAULT`: keep PETSc's value.
pub const PETSC_DEFAULT: PetscInt = -2;
/// `MAT_FINAL_ASSEMBLY` (`MatAssemblyType`).
pub const MAT_FINAL_ASSEMBLY: c_int = 0;
/// `PETSC_COPY_VALUES` (`PetscCopyMode`): the index set keeps its own copy.
pub const PETSC_COPY_VALUES: c_int = 0;
/// `INSERT_VALUES` (`InsertMode`).
pub const INSERT_VALUES: c_int = 1;
/// `SCATTER_FORWARD` (`ScatterMode`).
pub const SCATTER_FORWARD: c_int = 0;
/// `MAT_NEW_NONZERO_ALLOCATION_ERR` (`MatOption`): inserting outside the preallocation errs.
pub const MAT_NEW_NONZERO_ALLOCATION_ERR: c_int = 19;
/// `KSP_DIVERGED_ITS` (`KSPConvergedReason`): the iteration budget was spent.
pub const KSP_DIVERGED_ITS: c_int = -3;
/// `KSP_DIVERGED_NANORINF`: a NaN or infinity appeared.
pub const KSP_DIVERGED_NANORINF: c_int = -9;
/// `KSP_DIVERGED_PC_FAILED`: the preconditioner could not be built or applied (a zero pivot).
pub const KSP_DIVERGED_PC_FAILED: c_int = -11;

/// A KSP monitor: `(ksp, iteration, residual norm, context)`.
pub type KSPMonitorFn =
    unsafe extern "C" fn(KSP, PetscInt, PetscReal, *mut c_void) -> PetscErrorCode;
/// Destroys a monitor context.
pub type MonitorDestroyFn = unsafe extern "C" fn(*mut *mut c_void) -> PetscErrorCode;

unsafe extern "C" {
    /// The communicator PETSc objects live on (`MPI_COMM_WORLD` unless set before init).
    pub static mut PETSC_COMM_WORLD: MPI_Comm;
    /// Where PETSc prints what goes to standard output (`PetscPrintf`, the ASCII stdout
    /// viewers of `-log_view`, `-ksp_view`, `-ksp_monitor`): `stdout`, set by
    /// `PetscInitialize`; may be changed after it.
    pub static mut PETSC_STDOUT: *mut FILE;
    /// Where PETSc prints errors: `stderr`, set by `PetscInitialize`.
    pub static mut PETSC_STDERR: *mut FILE;

    /// `PetscInitializeNoArguments()`: initialises PETSc (and MPI, unless already initialised).
    pub fn PetscInitializeNoArguments() -> PetscErrorCode;
    /// `PetscInitialized(&flag)`.
    pub fn PetscInitialized(flag: *mut PetscBool) -> PetscErrorCode;
    /// `PetscFinalized(&flag)`.
    pub fn PetscFinalized(flag: *mut PetscBool) -> PetscErrorCode;
    /// `PetscFinalize()`: finalises PETSc (and MPI if PETSc initialised it).
    pub fn PetscFinalize() -> PetscErrorCode;
    /// `PetscOptionsInsertString(NULL, "-ksp_type cg ...")`: adds to the global options database.
    pub fn PetscOptionsInsertString(options: *mut c_void, s: *const c_char) -> PetscErrorCode;
    /// `PetscOptionsGetBool(NULL, NULL, "-name", &value, &set)`: a boolean option of the
    /// global database (`set` false when absent; `value` then untouched).
    pub fn PetscOptionsGetBool(
        options: *mut c_void,
        prefix: *const c_char,
        name: *const c_char,
        value: *mut PetscBool,
        set: *mut PetscBool,
    ) -> PetscErrorCode;
    /// `PetscOptionsGetReal(NULL, NULL, "-name", &value, &set)`: a real option of the global
    /// database (`set` false when absent; `value` then untouched).
    pub fn PetscOptionsGetReal(
        options: *mut c_void,
        prefix: *const c_char,
        name: *const c_char,
        value: *mut PetscReal,
        set: *mut PetscBool,
    ) -> PetscErrorCode;
    /// `PetscMemoryGetMaximumUsage(&bytes)`: peak resident memory, once enabled by
    /// `PetscMemorySetGetMaximumUsage()`.
    pub fn PetscMemoryGetMaximumUsage(bytes: *mut PetscLogDouble) -> PetscErrorCode;
    /// `PetscMemorySetGetMaximumUsage()`.
    pub fn PetscMemorySetGetMaximumUsage() -> PetscErrorCode;

    /// `MPI_Comm_rank`.
    pub fn MPI_Comm_rank(comm: MPI_Comm, rank: *mut c_int) -> c_int;
    /// `MPI_Comm_size`.
    pub fn MPI_Comm_size(comm: MPI_Comm, size: *mut c_int) -> c_int;

    /// `MatCreate(comm, &A)`.
    pub fn MatCreate(comm: MPI_Comm, mat: *mut Mat) -> PetscErrorCode;
    /// `MatSetSizes(A, local rows, local cols, global rows, global cols)`.
    pub fn MatSetSizes(
        mat: Mat,
        m: PetscInt,
        n: PetscInt,
        big_m: PetscInt,
        big_n: PetscInt,
    ) -> PetscErrorCode;
    /// `MatSetType(A, "aij")`.
    pub fn MatSetType(mat: Mat, kind: *const c_char) -> PetscErrorCode;
    /// `MatSeqAIJSetPreallocation(A, nz, nnz)` (ignored by a parallel matrix).
    pub fn MatSeqAIJSetPreallocation(
        mat: Mat,
        nz: PetscInt,
        nnz: *const PetscInt,
    ) -> PetscErrorCode;
    /// `MatMPIAIJSetPreallocation(A, d_nz, d_nnz, o_nz, o_nnz)` (ignored by a sequential one).
    pub fn MatMPIAIJSetPreallocation(
        mat: Mat,
        d_nz: PetscInt,
        d_nnz: *const PetscInt,
        o_nz: PetscInt,
        o_nnz: *const PetscInt,
    ) -> PetscErrorCode;
    /// `MatSetOption(A, option, flag)`.
    pub fn MatSetOption(mat: Mat, option: c_int, flag: PetscBool) -> PetscErrorCode;
    /// `MatSetValues(A, m, rows, n, cols, values, mode)`: a dense `m x n` block, row-major.
    pub fn MatSetValues(
        mat: Mat,
        m: PetscInt,
        rows: *const PetscInt,
        n: PetscInt,
        cols: *const PetscInt,
        values: *const PetscScalar,
        mode: c_int,
    ) -> PetscErrorCode;
    /// `MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY)`.
    pub fn MatAssemblyBegin(mat: Mat, kind: c_int) -> PetscErrorCode;
    /// `MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY)`.
    pub fn MatAssemblyEnd(mat: Mat, kind: c_int) -> PetscErrorCode;
    /// `MatCreateVecs(A, &right, &left)`: vectors laid out like the columns and rows of `A`.
    pub fn MatCreateVecs(mat: Mat, right: *mut Vec, left: *mut Vec) -> PetscErrorCode;
    /// `MatDestroy(&A)`.
    pub fn MatDestroy(mat: *mut Mat) -> PetscErrorCode;
    /// `MatSetBlockSize(A, bs)`: unknowns per node (before preallocation), read by GAMG.
    pub fn MatSetBlockSize(mat: Mat, bs: PetscInt) -> PetscErrorCode;
    /// `MatNullSpaceCreate(comm, has_constant, n, vecs, &space)`: `vecs` orthonormal.
    pub fn MatNullSpaceCreate(
        comm: MPI_Comm,
        has_constant: PetscBool,
        n: PetscInt,
        vecs: *const Vec,
        space: *mut MatNullSpace,
    ) -> PetscErrorCode;
    /// `MatSetNearNullSpace(A, space)`: the near-null space algebraic multigrid coarsens with.
    pub fn MatSetNearNullSpace(mat: Mat, space: MatNullSpace) -> PetscErrorCode;
    /// `MatNullSpaceDestroy(&space)`.
    pub fn MatNullSpaceDestroy(space: *mut MatNullSpace) -> PetscErrorCode;

    /// `VecGetArray(v, &array)`: this rank's entries.
    pub fn VecGetArray(v: Vec, array: *mut *mut PetscScalar) -> PetscErrorCode;
    /// `VecRestoreArray(v, &array)`.
    pub fn VecRestoreArray(v: Vec, array: *mut *mut PetscScalar) -> PetscErrorCode;
    /// `VecGetArrayRead(v, &array)`.
    pub fn VecGetArrayRead(v: Vec, array: *mut *const PetscScalar) -> PetscErrorCode;
    /// `VecRestoreArrayRead(v, &array)`.
    pub fn VecRestoreArrayRead(v: Vec, array: *mut *const PetscScalar) -> PetscErrorCode;
    /// `VecScatterCreateToAll(v, &scatter, &all)`: a scatter to a sequential copy on every rank.
    pub fn VecScatterCreateToAll(v: Vec, scatter: *mut VecScatter, all: *mut Vec)
    -> PetscErrorCode;
    /// `VecScatterBegin(scatter, from, to, mode, direction)`.
    pub fn VecScatterBegin(
        scatter: VecScatter,
        from: Vec,
        to: Vec,
        mode: c_int,
        direction: c_int,
    ) -> PetscErrorCode;
    /// `VecScatterEnd(scatter, from, to, mode, direction)`.
    pub fn VecScatterEnd(
        scatter: VecScatter,
        from: Vec,
        to: Vec,
        mode: c_int,
        direction: c_int,
    ) -> PetscErrorCode;
    /// `VecScatterDestroy(&scatter)`.
    pub fn VecScatterDestroy(scatter: *mut VecScatter) -> PetscErrorCode;
    /// `VecDestroy(&v)`.
    pub fn VecDestroy(v: *mut Vec) -> PetscErrorCode;
    /// `VecCreateMPI(comm, local, global, &v)`: a distributed vector, `local` entries here.
    pub fn VecCreateMPI(
        comm: MPI_Comm,
        n: PetscInt,
        big_n: PetscInt,
        v: *mut Vec,
    ) -> PetscErrorCode;
    /// `VecDuplicate(v, &w)`: a new vector laid out like `v`.
    pub fn VecDuplicate(v: Vec, w: *mut Vec) -> PetscErrorCode;
    /// `VecDot(x, y, &dot)`: the global `y^H x`.
    pub fn VecDot(x: Vec, y: Vec, dot: *mut PetscScalar) -> PetscErrorCode;
    /// `VecAXPY(y, alpha, x)`: `y += alpha x`.
    pub fn VecAXPY(y: Vec, alpha: PetscScalar, x: Vec) -> PetscErrorCode;
    /// `VecNormalize(x, &norm)`: `x /= |x|_2`, the norm before.
    pub fn VecNormalize(x: Vec, norm: *mut PetscReal) -> PetscErrorCode;
    /// `VecSum(v, &sum)`: the global sum of the entries.
    pub fn VecSum(v: Vec, sum: *mut PetscScalar) -> PetscErrorCode;
    /// `VecMax(v, &index, &max)`: the global maximum entry (`index` may be null).
    pub fn VecMax(v: Vec, index: *mut PetscInt, max: *mut PetscReal) -> PetscErrorCode;
    /// `VecScatterCreate(x, ix, y, iy, &scatter)`: `y[iy[k]] = x[ix[k]]`, the local parts
    /// of the index sets paired on each rank (`iy` null: `y`'s own entries in order).
    pub fn VecScatterCreate(
        x: Vec,
        ix: IS,
        y: Vec,
        iy: IS,
        scatter: *mut VecScatter,
    ) -> PetscErrorCode;

    /// `ISCreateGeneral(comm, n, indices, mode, &is)`: this rank's `n` global indices.
    pub fn ISCreateGeneral(
        comm: MPI_Comm,
        n: PetscInt,
        indices: *const PetscInt,
        mode: c_int,
        is: *mut IS,
    ) -> PetscErrorCode;
    /// `ISDestroy(&is)`.
    pub fn ISDestroy(is: *mut IS) -> PetscErrorCode;

    /// `KSPCreate(comm, &ksp)`.
    pub fn KSPCreate(comm: MPI_Comm, ksp: *mut KSP) -> PetscErrorCode;
    /// `KSPSetOperators(ksp, A, P)`.
    pub fn KSPSetOperators(ksp: KSP, a: Mat, p: Mat) -> PetscErrorCode;
    /// `KSPSetFromOptions(ksp)`: reads `-ksp_*` / `-pc_*` from the options database.
    pub fn KSPSetFromOptions(ksp: KSP) -> PetscErrorCode;
    /// `KSPMonitorSet(ksp, monitor, context, destroy)`.
    pub fn KSPMonitorSet(
        ksp: KSP,
        monitor: Option<KSPMonitorFn>,
        context: *mut c_void,
        destroy: Option<MonitorDestroyFn>,
    ) -> PetscErrorCode;
    /// `KSPSolve(ksp, b, x)`.
    pub fn KSPSolve(ksp: KSP, b: Vec, x: Vec) -> PetscErrorCode;
    /// `KSPGetConvergedReason(ksp, &reason)`: positive converged, negative diverged.
    pub fn KSPGetConvergedReason(ksp: KSP, reason: *mut c_int) -> PetscErrorCode;
    /// `KSPGetIterationNumber(ksp, &its)`.
    pub fn KSPGetIterationNumber(ksp: KSP, its: *mut PetscInt) -> PetscErrorCode;
    /// `KSPGetTolerances(ksp, &rtol, &abstol, &dtol, &maxits)`.
    pub fn KSPGetTolerances(
        ksp: KSP,
        rtol: *mut PetscReal,
        abstol: *mut PetscReal,
        dtol: *mut PetscReal,
        maxits: *mut PetscInt,
    ) -> PetscErrorCode;
    /// `KSPSetTolerances(ksp, rtol, abstol, dtol, maxits)`.
    pub fn KSPSetTolerances(
        ksp: KSP,
        rtol: PetscReal,
        abstol: PetscReal,
        dtol: PetscReal,
        maxits: PetscInt,
    ) -> PetscErrorCode;
    /// `KSPSetReusePreconditioner(ksp, flag)`: with `PETSC_TRUE` the next solves keep the
    /// preconditioner built for earlier operator values (no new set-up when the matrix changes).
    pub fn KSPSetReusePreconditioner(ksp: KSP, flag: PetscBool) -> PetscErrorCode;
    /// `KSPDestroy(&ksp)`.
    pub fn KSPDestroy(ksp: *mut KSP) -> PetscErrorCode;
}

/// Whether the installed PETSc has MUMPS (`PETSC_HAVE_MUMPS`).
pub const HAVE_MUMPS: bool = cfg!(petsc_have_mumps);
