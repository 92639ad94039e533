//! The rows of one distributed solve: which contiguous block of unknowns this process owns,
//! and how the owners' entries of a vector reach every process. Physics-free; the
//! communication is an engine's (PETSc over MPI: `capstan-petsc`), installed once per process
//! ([`install`]) like a registered backend.

use std::ops::Range;
use std::sync::{Arc, OnceLock};

/// A process's share of a distributed solve: `size` processes, this one `rank`, each owning
/// the contiguous block of rows [`owned_blocks`] of every vector.
pub trait RowDistribution: Send + Sync {
    /// This process's rank (0-based).
    fn rank(&self) -> usize;

    /// The number of processes.
    fn size(&self) -> usize;

    /// Every process's owned entries of `all` (its [`owned_blocks`] rows for `block`
    /// unknowns per node) to every process: on return `all` is the owners' vector everywhere.
    /// Collective: every process calls it with a vector of the same length, in the same
    /// order as every other collective call, from one thread (a program keeps all its
    /// distributed solves on the thread that started the engine: two solves at once on two
    /// threads interleave their messages differently on different processes).
    ///
    /// # Errors
    /// The engine's failure, as [`crate::SolverError::External`] (MPI is then usually
    /// unusable and the job should end).
    fn gather(&self, all: &mut [f64], block: usize) -> Result<(), crate::SolverError>;

    /// Entries of a distributed vector by their global index: `owned` is this process's
    /// rows of a vector of `n` entries ([`owned_blocks`]`(n, block, ..)`), and on return
    /// `out[k] = x[indices[k]]` for any global `indices` (the ghosts a process reads: rows
    /// another process owns), without making `x` whole anywhere. Collective: every process
    /// calls it in the same order (each with its own `indices`, possibly none).
    ///
    /// # Math
    /// ```text
    /// out_k = x_{indices_k},   x_i = owned_{i - first} on the process owning row i
    /// ```
    ///
    /// # Errors
    /// [`crate::SolverError::DimensionMismatch`] when `owned` is not this process's share of
    /// `n` or `out` is not as long as `indices`, [`crate::SolverError::InvalidParameter`]
    /// for an index not below `n`; the engine's failure as
    /// [`crate::SolverError::External`].
    fn fetch(
        &self,
        owned: &[f64],
        n: usize,
        block: usize,
        indices: &[usize],
        out: &mut [f64],
    ) -> Result<(), crate::SolverError>;

    /// The sum over all processes of `value` (each its own). Collective.
    ///
    /// # Errors
    /// The engine's failure as [`crate::SolverError::External`].
    fn sum(&self, value: f64) -> Result<f64, crate::SolverError>;

    /// The maximum over all processes of `value` (each its own; a NaN anywhere gives NaN).
    /// Collective.
    ///
    /// # Errors
    /// The engine's failure as [`crate::SolverError::External`].
    fn max(&self, value: f64) -> Result<f64, crate::SolverError>;

    /// Whether a Newton iteration over this distribution holds its vectors as each
    /// process's rows ([`crate::DistributedNewton`]; the default) rather than whole on every
    /// process (for comparisons: `-capstan_owned_newton false` under PETSc).
    fn newton_on_owned_rows(&self) -> bool {
        true
    }

    /// The rows this process owns among `n` with `block` unknowns per node.
    fn owned(&self, n: usize, block: usize) -> Range<usize> {
        owned_blocks(n, block, self.rank(), self.size())
    }
}

/// The contiguous block of rows rank `rank` of `size` owns among `n`: PETSc's own split
/// (`PetscSplitOwnership`), the first `n mod size` ranks one row more.
///
/// # Math
/// ```text
/// local(r) = floor(n / size) + (r < n mod size),   first(r) = sum_{q < r} local(q)
/// ```
pub fn owned_rows(n: usize, rank: usize, size: usize) -> Range<usize> {
    let size = size.max(1);
    let (base, extra) = (n / size, n % size);
    let first = rank * base + rank.min(extra);
    first..first + base + usize::from(rank < extra)
}

/// [`owned_rows`] in whole blocks of `block` rows (the unknowns of one node stay on one
/// process): the blocks split like rows, times `block`.
///
/// # Math
/// ```text
/// rows(r) = block owned_rows(n / block, r, size)     (n a multiple of block)
/// ```
pub fn owned_blocks(n: usize, block: usize, rank: usize, size: usize) -> Range<usize> {
    let block = block.max(1);
    let b = owned_rows(n / block, rank, size);
    block * b.start..block * b.end
}

static INSTALLED: OnceLock<Arc<dyn RowDistribution>> = OnceLock::new();

/// Makes `distribution` the process's: discretisations that can assemble a block of rows
/// (the 3-D body) then assemble only this process's rows, and the contact model completes
/// its residuals with [`RowDistribution::gather`]. Once per process; `false` (and nothing
/// changed) if one was installed before.
pub fn install(distribution: Arc<dyn RowDistribution>) -> bool {
    INSTALLED.set(distribution).is_ok()
}

/// The process's distribution, if one with more than one process is installed.
pub fn installed() -> Option<Arc<dyn RowDistribution>> {
    INSTALLED.get().filter(|d| d.size() > 1).cloned()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn owned_rows_tile_the_range_like_petsc_split_ownership() {
        for (n, size) in [(10, 3), (7, 7), (3, 4), (1_000_001, 128)] {
            let blocks: Vec<_> = (0..size).map(|r| owned_rows(n, r, size)).collect();
            assert_eq!(blocks[0].start, 0);
            assert_eq!(blocks[size - 1].end, n);
            for w in blocks.windows(2) {
                assert_eq!(w[0].end, w[1].start);
                assert!(w[0].len() >= w[1].len() && w[0].len() <= w[1].len() + 1);
            }
        }
        assert_eq!(owned_rows(10, 0, 3), 0..4);
        assert_eq!(owned_rows(10, 2, 3), 7..10);
    }

    #[test]
    fn owned_blocks_keep_whole_nodes_on_one_rank() {
        // 5 nodes of 3 unknowns on 2 ranks: nodes 0..3 and 3..5
        assert_eq!(owned_blocks(15, 3, 0, 2), 0..9);
        assert_eq!(owned_blocks(15, 3, 1, 2), 9..15);
        assert_eq!(owned_blocks(10, 1, 2, 3), owned_rows(10, 2, 3));
        for size in 1..6 {
            let blocks: Vec<_> = (0..size).map(|r| owned_blocks(3 * 7, 3, r, size)).collect();
            assert!(blocks.iter().all(|b| b.start % 3 == 0 && b.end % 3 == 0));
            assert_eq!(blocks.last().unwrap().end, 21);
        }
    }
}
