//! `mpirun -n K capstan sweep ...` (feature `mpi`): rank 0 hands the sweep points to the other
//! ranks one at a time (dynamic: a rank that finishes early gets the next point) and gathers
//! the results; its outputs are those of the serial run.
//!
//! # Protocol
//! ```text
//! worker -> 0 : bytes   empty (ready) or JSON {"index": k, "point": SweepPoint}
//! 0 -> worker : u64     the next 0-based point k, or u64::MAX (stop)
//! ```
//! Rank 0 only dispatches: with `K` ranks, `K - 1` solve. Each point is one
//! [`crate::commands::sweep::report`] of a single value, so a load sweep refactorises per point
//! instead of sharing one factorisation (known limitation). Set `RAYON_NUM_THREADS` per rank
//! so ranks on one node do not oversubscribe its cores.

use mpi::traits::{Communicator, Destination, Source};
use serde::{Deserialize, Serialize};

use crate::commands::sweep::{SweepPoint, SweepReport};
use crate::error::CliError;

/// What this process did.
#[derive(Debug)]
pub enum MpiSweep {
    /// Not started by `mpirun` with more than one rank: run the sweep serially.
    Serial,
    /// Rank 0: the gathered report.
    Root(SweepReport),
    /// Another rank: its points were sent to rank 0; nothing to print.
    Worker,
}

const STOP: u64 = u64::MAX;

#[derive(Serialize, Deserialize)]
struct Done {
    index: usize,
    point: SweepPoint,
}

/// Runs the sweep across MPI ranks when there are at least two.
///
/// # Errors
/// Bad input that concerns every point (as the serial sweep); a malformed message.
///
/// # Panics
/// If MPI cannot be initialised (the `mpi` crate aborts then).
pub fn sweep(
    path: Option<&std::path::Path>,
    sets: &[String],
    key: &str,
    values: &[f64],
) -> Result<MpiSweep, CliError> {
    let Some(universe) = mpi::initialize() else {
        return Ok(MpiSweep::Serial); // already initialised elsewhere: stay serial
    };
    let world = universe.world();
    if world.size() < 2 {
        return Ok(MpiSweep::Serial);
    }
    // Every rank checks the scene first, so bad input fails everywhere alike.
    crate::scene::Scene::load(path, sets)?;
    if world.rank() == 0 {
        let t = std::time::Instant::now();
        let mut points: Vec<Option<SweepPoint>> = vec![None; values.len()];
        let mut next = 0usize;
        let mut stopped = 0;
        while stopped < world.size() - 1 {
            let (bytes, status) = world.any_process().receive_vec::<u8>();
            if !bytes.is_empty() {
                let done: Done = serde_json::from_slice(&bytes).map_err(|e| {
                    crate::scale::ShardError::Malformed {
                        path: format!("MPI rank {}", status.source_rank()),
                        reason: e.to_string(),
                    }
                })?;
                points[done.index] = Some(done.point);
            }
            let reply = if next < values.len() {
                next += 1;
                (next - 1) as u64
            } else {
                stopped += 1;
                STOP
            };
            world.process_at_rank(status.source_rank()).send(&reply);
        }
        let shared = key == "loads.tau_max" || key == "loads.tau0";
        Ok(MpiSweep::Root(SweepReport {
            param: key.to_owned(),
            points: points
                .into_iter()
                .map(|p| p.expect("every point was handed out and answered"))
                .collect(),
            shared_factorisation: shared,
            seconds: t.elapsed().as_secs_f64(),
        }))
    } else {
        let root = world.process_at_rank(0);
        let mut message = Vec::new();
        loop {
            root.send(&message[..]);
            let (k, _) = root.receive::<u64>();
            if k == STOP {
                break;
            }
            let k = k as usize;
            let r = crate::commands::sweep::report(path, sets, key, &values[k..=k])?;
            let done = Done {
                index: k,
                point: r.points[0].clone(),
            };
            message = serde_json::to_vec(&done).map_err(crate::output::OutputError::Json)?;
        }
        Ok(MpiSweep::Worker)
    }
}
