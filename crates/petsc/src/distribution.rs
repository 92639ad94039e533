//! [`PetscDistribution`]: capstan's [`RowDistribution`] over PETSc's communicator, so that the
//! 3-D body assembles only this rank's rows and the contact model completes its residuals.

use std::sync::Mutex;

use capstan_petsc_sys as sys;
use capstan_solvers::SolverError;
use capstan_solvers::row_distribution::{RowDistribution, owned_blocks};

use crate::error::{PetscError, check};
use crate::session::{Session, on_session_thread, running};

/// A distributed vector of one length and its scatter to a full copy on every rank.
struct Gather {
    key: (usize, usize),
    local: sys::Vec,
    scatter: sys::VecScatter,
    all: sys::Vec,
}

impl Drop for Gather {
    fn drop(&mut self) {
        if !running() {
            return;
        }
        // SAFETY: created by PETSc in `PetscDistribution::gather_checked`, destroyed once.
        unsafe {
            sys::VecScatterDestroy(&mut self.scatter);
            sys::VecDestroy(&mut self.all);
            sys::VecDestroy(&mut self.local);
        }
    }
}

/// The ranks of `PETSC_COMM_WORLD` as a [`RowDistribution`]: rank `r` owns
/// [`owned_blocks`]`(n, block, r, K)` (the rows [`crate::PetscSolver`] owns), and
/// [`RowDistribution::gather`] is PETSc's scatter of a distributed vector to all ranks
/// (`VecScatterCreateToAll`, kept for the last length).
///
/// # Math
/// ```text
/// gather(x)_i = x_i on the rank owning row i       (every rank gets all n entries)
/// ```
/// A failing PETSc or MPI call is [`PetscError::Call`] naming it, inside
/// [`SolverError::External`]. The gather is collective: every rank must call it in the same
/// order as its other PETSc calls, from the thread that started the [`Session`] (PETSc is
/// initialised without thread support); two solves on two threads at once (as the contact
/// command's error estimate once ran its coarser grid) mix their messages and fail with
/// `MPI_ERR_TRUNCATE` on one rank and a broken scatter on the other.
pub struct PetscDistribution {
    rank: usize,
    size: usize,
    cache: Mutex<Option<Gather>>,
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
        Ok(Self {
            rank: session.rank(),
            size: session.size(),
            cache: Mutex::new(None),
        })
    }

    fn gather_checked(&self, all: &mut [f64], block: usize) -> Result<(), PetscError> {
        on_session_thread("gathering a distributed vector")?;
        let n = all.len();
        let rows = owned_blocks(n, block, self.rank, self.size);
        let mut cache = self.cache.lock().unwrap_or_else(|e| e.into_inner());
        if cache.as_ref().is_none_or(|g| g.key != (n, block)) {
            *cache = None;
            let mut g = Gather {
                key: (n, block),
                local: core::ptr::null_mut(),
                scatter: core::ptr::null_mut(),
                all: core::ptr::null_mut(),
            };
            let local = sys::PetscInt::try_from(rows.len()).map_err(|_| too_many(rows.len()))?;
            let global = sys::PetscInt::try_from(n).map_err(|_| too_many(n))?;
            // SAFETY: PETSc is running; the handles are owned by `g` and destroyed by its Drop.
            unsafe {
                check(
                    sys::VecCreateMPI(sys::PETSC_COMM_WORLD, local, global, &mut g.local),
                    "VecCreateMPI",
                )?;
                check(
                    sys::VecScatterCreateToAll(g.local, &mut g.scatter, &mut g.all),
                    "VecScatterCreateToAll",
                )?;
            }
            *cache = Some(g);
        }
        let g = cache.as_ref().expect("just made");
        // SAFETY: live handles; `local` has the owned rows' length, `all` all n entries.
        unsafe {
            let mut a: *mut f64 = core::ptr::null_mut();
            check(sys::VecGetArray(g.local, &mut a), "VecGetArray")?;
            core::slice::from_raw_parts_mut(a, rows.len()).copy_from_slice(&all[rows.clone()]);
            check(sys::VecRestoreArray(g.local, &mut a), "VecRestoreArray")?;
            for begin in [true, false] {
                let f = if begin {
                    sys::VecScatterBegin
                } else {
                    sys::VecScatterEnd
                };
                check(
                    f(
                        g.scatter,
                        g.local,
                        g.all,
                        sys::INSERT_VALUES,
                        sys::SCATTER_FORWARD,
                    ),
                    "VecScatter",
                )?;
            }
            let mut x: *const f64 = core::ptr::null();
            check(sys::VecGetArrayRead(g.all, &mut x), "VecGetArrayRead")?;
            all.copy_from_slice(core::slice::from_raw_parts(x, n));
            check(
                sys::VecRestoreArrayRead(g.all, &mut x),
                "VecRestoreArrayRead",
            )?;
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

impl RowDistribution for PetscDistribution {
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
