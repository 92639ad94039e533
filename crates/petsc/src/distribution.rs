//! [`PetscDistribution`]: capstan's [`RowDistribution`] over PETSc's communicator, so that the
//! 3-D body assembles only this rank's rows and the contact model completes its residuals.

use std::sync::Mutex;

use capstan_petsc_sys as sys;
use capstan_solvers::SolverError;
use capstan_solvers::row_distribution::{RowDistribution, owned_blocks};

use crate::error::{PetscError, check};
use crate::session::{Session, on_session_thread, option_bool, running};

/// The PETSc option that keeps the full-system Newton's vectors whole on every rank
/// (`solver.petsc_options = "-capstan_owned_newton false"`; default true: each rank holds its
/// rows, [`capstan_solvers::DistributedNewton`]), for comparisons.
pub const OWNED_NEWTON_OPTION: &str = "-capstan_owned_newton";

/// A PETSc scatter between two vectors, cached under `key`: the full copy on every rank of a
/// distributed vector ([`Gather`]), or the entries each rank asks for ([`Ghosts`]).
struct Scatter<K> {
    key: K,
    /// The distributed vector scattered from (this rank's owned rows).
    from: sys::Vec,
    scatter: sys::VecScatter,
    /// The vector scattered into.
    to: sys::Vec,
}

impl<K> Scatter<K> {
    /// An empty scatter under `key`, its handles filled in by PETSc's create calls.
    fn empty(key: K) -> Self {
        Self {
            key,
            from: core::ptr::null_mut(),
            scatter: core::ptr::null_mut(),
            to: core::ptr::null_mut(),
        }
    }
}

impl<K> Drop for Scatter<K> {
    fn drop(&mut self) {
        if !running() {
            return;
        }
        // SAFETY: created by PETSc in `PetscDistribution::gather_checked` or `fetch_checked`
        // (null handles are ignored by the destroy calls), destroyed once.
        unsafe {
            sys::VecScatterDestroy(&mut self.scatter);
            sys::VecDestroy(&mut self.to);
            sys::VecDestroy(&mut self.from);
        }
    }
}

/// A distributed vector of `(n, block)` and its scatter to a full copy on every rank.
type Gather = Scatter<(usize, usize)>;

/// The ranks of `PETSC_COMM_WORLD` as a [`RowDistribution`]: rank `r` owns
/// [`owned_blocks`]`(n, block, r, K)` (the rows [`crate::PetscSolver`] owns), and
/// [`RowDistribution::gather`] is PETSc's scatter of a distributed vector to all ranks
/// (`VecScatterCreateToAll`, kept for the last length).
///
/// # Math
/// ```text
/// gather(x)_i = x_i on the rank owning row i       (every rank gets all n entries)
/// fetch(x, I)_k = x_{I_k}                         (each rank its own global indices I)
/// sum(a) = sum_r a_r,   max(a) = max_r a_r          (NaN on any rank: NaN)
/// ```
/// The fetch scatters from a distributed vector of the owned rows (`VecCreateMPI`) to one
/// whose local part is the requested entries (`ISCreateGeneral`, `VecScatterCreate`; the
/// scatter is kept for the last request); the reductions are `VecSum` / `VecMax` over a
/// vector of one entry a rank.
/// A failing PETSc or MPI call is [`PetscError::Call`] naming it, inside
/// [`SolverError::External`]. The gather is collective: every rank must call it in the same
/// order as its other PETSc calls, from the thread that started the [`Session`] (PETSc is
/// initialised without thread support); two solves on two threads at once (as the contact
/// command's error estimate once ran its coarser grid) mix their messages and fail with
/// `MPI_ERR_TRUNCATE` on one rank and a broken scatter on the other.
pub struct PetscDistribution {
    rank: usize,
    size: usize,
    /// [`OWNED_NEWTON_OPTION`] (default true).
    owned_newton: bool,
    cache: Mutex<Option<Gather>>,
    ghosts: Mutex<Option<Ghosts>>,
    one: Mutex<Option<OnePerRank>>,
}

// SAFETY: the PETSc handles are only touched under the mutex; MPI is initialised
// single-threaded and capstan's Newton iteration (the only caller) runs on one thread.
unsafe impl Send for PetscDistribution {}
// SAFETY: as above: every access to the handles goes through the mutex.
unsafe impl Sync for PetscDistribution {}

impl core::fmt::Debug for PetscDistribution {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("PetscDistribution")
            .field("rank", &self.rank)
            .field("size", &self.size)
            .finish_non_exhaustive()
    }
}

impl PetscDistribution {
    /// The distribution of the running [`Session`] (`rank`, `size` of
    /// `PETSC_COMM_WORLD`).
    ///
    /// # Errors
    /// [`PetscError::NotStarted`] without a running session.
    pub fn new(session: &Session) -> Result<Self, PetscError> {
        if !running() {
            return Err(PetscError::NotStarted);
        }
        let owned_newton = option_bool(OWNED_NEWTON_OPTION)?.unwrap_or(true);
        Ok(Self {
            rank: session.rank(),
            size: session.size(),
            owned_newton,
            cache: Mutex::new(None),
            ghosts: Mutex::new(None),
            one: Mutex::new(None),
        })
    }

    /// The distribution of the running PETSc of `rank` of `size` (for this crate's solver,
    /// which has no [`Session`] at hand).
    pub(crate) fn of_running(rank: usize, size: usize) -> Result<Self, PetscError> {
        if !running() {
            return Err(PetscError::NotStarted);
        }
        Ok(Self {
            rank,
            size,
            owned_newton: true,
            cache: Mutex::new(None),
            ghosts: Mutex::new(None),
            one: Mutex::new(None),
        })
    }

    fn gather_checked(&self, all: &mut [f64], block: usize) -> Result<(), PetscError> {
        on_session_thread("gathering a distributed vector")?;
        let n = all.len();
        let rows = owned_blocks(n, block, self.rank, self.size);
        let mut cache = self.cache.lock().unwrap_or_else(|e| e.into_inner());
        if cache.as_ref().is_none_or(|g| g.key != (n, block)) {
            *cache = None;
            let mut g = Gather::empty((n, block));
            let local = sys::PetscInt::try_from(rows.len()).map_err(|_| too_many(rows.len()))?;
            let global = sys::PetscInt::try_from(n).map_err(|_| too_many(n))?;
            // SAFETY: PETSc is running; the handles are owned by `g` and destroyed by its Drop.
            unsafe {
                check(
                    sys::VecCreateMPI(sys::PETSC_COMM_WORLD, local, global, &mut g.from),
                    "VecCreateMPI",
                )?;
                check(
                    sys::VecScatterCreateToAll(g.from, &mut g.scatter, &mut g.to),
                    "VecScatterCreateToAll",
                )?;
            }
            *cache = Some(g);
        }
        let g = cache.as_ref().expect("just made");
        // SAFETY: live handles; `local` has the owned rows' length (possibly none: more ranks
        // than nodes), `all` all n entries.
        unsafe {
            set_local(g.from, &all[rows.clone()])?;
            for begin in [true, false] {
                let f = if begin {
                    sys::VecScatterBegin
                } else {
                    sys::VecScatterEnd
                };
                check(
                    f(
                        g.scatter,
                        g.from,
                        g.to,
                        sys::INSERT_VALUES,
                        sys::SCATTER_FORWARD,
                    ),
                    "VecScatter",
                )?;
            }
            get_local(g.to, all)?;
        }
        Ok(())
    }
}

fn too_many(value: usize) -> PetscError {
    PetscError::IndexOverflow {
        quantity: "unknowns",
        value,
        bits: sys::PetscInt::BITS,
    }
}

/// A scatter from a distributed vector of `n` entries to the entries `indices` of each rank
/// (a distributed vector whose local part is this rank's requested entries, in order).
type Ghosts = Scatter<(usize, usize, Vec<usize>)>;

/// A distributed vector of one entry per rank, for the reductions.
struct OnePerRank {
    v: sys::Vec,
}

impl Drop for OnePerRank {
    fn drop(&mut self) {
        if running() {
            // SAFETY: created by PETSc in `PetscDistribution::reduce`, destroyed once.
            unsafe {
                sys::VecDestroy(&mut self.v);
            }
        }
    }
}

/// Copies `values` into the local part of `v` (as long as `values`).
///
/// # Safety
/// `v` is a live vector whose local part has `values.len()` entries.
unsafe fn set_local(v: sys::Vec, values: &[f64]) -> Result<(), PetscError> {
    let mut a: *mut f64 = core::ptr::null_mut();
    // SAFETY: as the function's contract.
    unsafe {
        check(sys::VecGetArray(v, &mut a), "VecGetArray")?;
        if !values.is_empty() {
            core::slice::from_raw_parts_mut(a, values.len()).copy_from_slice(values);
        }
        check(sys::VecRestoreArray(v, &mut a), "VecRestoreArray")
    }
}

/// Copies the local part of `v` into `out` (as long as it).
///
/// # Safety
/// `v` is a live vector whose local part has `out.len()` entries.
unsafe fn get_local(v: sys::Vec, out: &mut [f64]) -> Result<(), PetscError> {
    let mut x: *const f64 = core::ptr::null();
    // SAFETY: as the function's contract.
    unsafe {
        check(sys::VecGetArrayRead(v, &mut x), "VecGetArrayRead")?;
        if !out.is_empty() {
            out.copy_from_slice(core::slice::from_raw_parts(x, out.len()));
        }
        check(sys::VecRestoreArrayRead(v, &mut x), "VecRestoreArrayRead")
    }
}

fn petsc_int(value: usize, quantity: &'static str) -> Result<sys::PetscInt, PetscError> {
    sys::PetscInt::try_from(value).map_err(|_| PetscError::IndexOverflow {
        quantity,
        value,
        bits: sys::PetscInt::BITS,
    })
}

impl PetscDistribution {
    fn fetch_checked(
        &self,
        owned: &[f64],
        n: usize,
        block: usize,
        indices: &[usize],
        out: &mut [f64],
    ) -> Result<(), SolverError> {
        on_session_thread("fetching entries of a distributed vector")?;
        let rows = owned_blocks(n, block, self.rank, self.size);
        if owned.len() != rows.len() {
            return Err(SolverError::DimensionMismatch {
                quantity: "owned rows",
                expected: rows.len(),
                found: owned.len(),
            });
        }
        if out.len() != indices.len() {
            return Err(SolverError::DimensionMismatch {
                quantity: "fetched entries",
                expected: indices.len(),
                found: out.len(),
            });
        }
        if let Some(&bad) = indices.iter().find(|&&i| i >= n) {
            return Err(SolverError::InvalidParameter {
                field: "index",
                value: bad as f64,
                allowed: "below the vector's length",
            });
        }
        let mut cache = self.ghosts.lock().unwrap_or_else(|e| e.into_inner());
        if cache
            .as_ref()
            .is_none_or(|g| g.key.0 != n || g.key.1 != block || g.key.2 != indices)
        {
            *cache = None;
            let mut g = Ghosts::empty((n, block, indices.to_vec()));
            let idx = indices
                .iter()
                .map(|&i| petsc_int(i, "unknowns"))
                .collect::<Result<Vec<_>, _>>()?;
            let (local, global) = (
                petsc_int(rows.len(), "unknowns")?,
                petsc_int(n, "unknowns")?,
            );
            let wanted = petsc_int(indices.len(), "fetched entries")?;
            // SAFETY: PETSc is running; the handles are owned by `g` (destroyed by its Drop)
            // but the index set, destroyed here after the scatter copied it.
            unsafe {
                check(
                    sys::VecCreateMPI(sys::PETSC_COMM_WORLD, local, global, &mut g.from),
                    "VecCreateMPI",
                )?;
                check(
                    sys::VecCreateMPI(sys::PETSC_COMM_WORLD, wanted, sys::PETSC_DECIDE, &mut g.to),
                    "VecCreateMPI",
                )?;
                let mut is: sys::IS = core::ptr::null_mut();
                check(
                    sys::ISCreateGeneral(
                        sys::PETSC_COMM_WORLD,
                        wanted,
                        idx.as_ptr(),
                        sys::PETSC_COPY_VALUES,
                        &mut is,
                    ),
                    "ISCreateGeneral",
                )?;
                let made = check(
                    sys::VecScatterCreate(g.from, is, g.to, core::ptr::null_mut(), &mut g.scatter),
                    "VecScatterCreate",
                );
                check(sys::ISDestroy(&mut is), "ISDestroy")?;
                made?;
            }
            *cache = Some(g);
        }
        let g = cache.as_ref().expect("just made");
        // SAFETY: live handles; `x`'s local part has the owned rows' length, `y`'s the
        // requested entries'.
        unsafe {
            set_local(g.from, owned)?;
            check(
                sys::VecScatterBegin(
                    g.scatter,
                    g.from,
                    g.to,
                    sys::INSERT_VALUES,
                    sys::SCATTER_FORWARD,
                ),
                "VecScatterBegin",
            )?;
            check(
                sys::VecScatterEnd(
                    g.scatter,
                    g.from,
                    g.to,
                    sys::INSERT_VALUES,
                    sys::SCATTER_FORWARD,
                ),
                "VecScatterEnd",
            )?;
            get_local(g.to, out)?;
        }
        Ok(())
    }

    /// `VecSum` (`max = false`) or `VecMax` over one entry per rank.
    fn reduce(&self, value: f64, max: bool) -> Result<f64, PetscError> {
        on_session_thread("reducing over the ranks")?;
        let mut one = self.one.lock().unwrap_or_else(|e| e.into_inner());
        if one.is_none() {
            let mut v: sys::Vec = core::ptr::null_mut();
            // SAFETY: PETSc is running; `v` is owned by the cache, destroyed by its Drop.
            unsafe {
                check(
                    sys::VecCreateMPI(sys::PETSC_COMM_WORLD, 1, sys::PETSC_DECIDE, &mut v),
                    "VecCreateMPI",
                )?;
            }
            *one = Some(OnePerRank { v });
        }
        let v = one.as_ref().expect("just made").v;
        let mut out = 0.0;
        // SAFETY: a live vector with one local entry.
        unsafe {
            if max {
                // MPI's maximum drops a NaN of one rank: count them first (every rank makes
                // both calls, in the same order)
                set_local(v, &[f64::from(u8::from(value.is_nan()))])?;
                check(sys::VecSum(v, &mut out), "VecSum")?;
                if out > 0.0 {
                    return Ok(f64::NAN);
                }
                set_local(v, &[value])?;
                check(sys::VecMax(v, core::ptr::null_mut(), &mut out), "VecMax")?;
            } else {
                set_local(v, &[value])?;
                check(sys::VecSum(v, &mut out), "VecSum")?;
            }
        }
        Ok(out)
    }
}

impl RowDistribution for PetscDistribution {
    fn fetch(
        &self,
        owned: &[f64],
        n: usize,
        block: usize,
        indices: &[usize],
        out: &mut [f64],
    ) -> Result<(), SolverError> {
        self.fetch_checked(owned, n, block, indices, out)
    }

    fn sum(&self, value: f64) -> Result<f64, SolverError> {
        self.reduce(value, false).map_err(SolverError::from)
    }

    fn max(&self, value: f64) -> Result<f64, SolverError> {
        self.reduce(value, true).map_err(SolverError::from)
    }

    fn newton_on_owned_rows(&self) -> bool {
        self.owned_newton
    }

    fn rank(&self) -> usize {
        self.rank
    }

    fn size(&self) -> usize {
        self.size
    }

    fn gather(&self, all: &mut [f64], block: usize) -> Result<(), SolverError> {
        self.gather_checked(all, block).map_err(SolverError::from)
    }
}
