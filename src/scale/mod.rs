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

mod error;
mod matrix_market;
#[cfg(feature = "mpi")]
pub mod mpi;
#[cfg(feature = "petsc")]
pub mod petsc;
mod scene_hash;
mod shard;

pub use error::ShardError;
pub use matrix_market::{write_matrix_market_array, write_matrix_market_coordinate};
pub use scene_hash::{Fnv1a64, sweep_hash};
pub use shard::{ShardFile, ShardSpec, merge, read_parts, run_shard, shard_file_name};

/// Whether this build has the PETSc backend (`solver.linear = "petsc"`, cargo feature `petsc`).
pub const PETSC_ENABLED: bool = cfg!(feature = "petsc");

/// Registers the linear backends of this build's optional features in
/// `capstan_solvers::linear_registry` (feature `petsc`: `petsc`), once per process; scene
/// validation and [`crate::Scene::build`] call it before they parse `solver.linear`.
pub fn register_feature_backends() {
    #[cfg(feature = "petsc")]
    {
        static ONCE: std::sync::Once = std::sync::Once::new();
        ONCE.call_once(|| {
            // a program that registered it itself first keeps its entry
            let _ =
                capstan_elasticity::solvers::linear_registry::register(capstan_petsc::REGISTRATION);
        });
    }
}
