//! Beyond one machine: sweep shards and their merge, a stable scene hash, Matrix Market export
//! of assembled systems, and (feature `mpi`) sweep points handed out across MPI ranks.
//!
//! A sweep of `steps` points split into `N` shards gives shard `I` (1-based, `1 <= I <= N`)
//! the points `k` (0-based) with `k % N == I - 1`. Each shard writes a self-describing part
//! ([`ShardFile`]): the scene hash, the whole parameter grid, which points it ran and their
//! results. [`merge`] checks that parts belong together and cover the grid exactly once, and
//! rebuilds the report an unsharded run would have written.
//!
//! Known limitations: the hash covers the scene as this version of capstan serialises it, so
//! parts written by different versions may refuse to merge even when the physics agrees; a
//! merged report's `seconds` is the longest part's wall time (the only field that differs from
//! an unsharded run's).

pub mod merge_command;
#[cfg(feature = "mpi")]
pub mod mpi;
#[cfg(feature = "petsc")]
pub mod petsc;
mod scene_hash;
mod shard;

pub use crate::features::{PETSC_ENABLED, register_feature_backends};
pub use crate::output::{write_matrix_market_array, write_matrix_market_coordinate};
pub use crate::shard_error::ShardError;
pub use scene_hash::{Fnv1a64, sweep_hash};
pub use shard::{ShardFile, ShardSpec, merge, read_parts, run_shard, shard_file_name};
