//! The distributed pieces of `PetscDistribution` on 1, 2 and 4 ranks: a vector held only as
//! each rank's rows, its ghost entries fetched by a PETSc scatter (any global indices,
//! repeated, none on some ranks), the round trip back to the whole vector by the gather, and
//! the sum and maximum over the ranks. The test re-runs its own binary under
//! `mpirun -n K` (skipped with a note when `mpirun` is not installed); each rank checks its
//! answers and exits non-zero on a mismatch.
#![cfg(feature = "petsc")]

use std::process::Command;

use capstan_petsc::{PetscDistribution, Session};
use capstan_solvers::SolverError;
use capstan_solvers::row_distribution::{RowDistribution, owned_blocks};

const CHILD: &str = "CAPSTAN_PETSC_DISTRIBUTED_VECTORS_CHILD";
const TEST: &str = "scatter_gather_round_trip_and_reductions_on_1_2_4_ranks";

/// The test vector: distinct, exactly representable entries.
fn entry(i: usize) -> f64 {
    0.5 * i as f64 - 3.0
}

/// What one rank checks (every rank runs the same collective calls in the same order).
fn rank_checks() {
    let session = Session::start("").unwrap();
    let d = PetscDistribution::new(&session).unwrap();
    let (rank, size) = (d.rank(), d.size());
    assert_eq!((rank, size), (session.rank(), session.size()));

    for (n, block) in [(21, 3), (10, 1), (2, 1)] {
        let whole: Vec<f64> = (0..n).map(entry).collect();
        let rows = owned_blocks(n, block, rank, size);
        assert_eq!(rows, d.owned(n, block));
        let owned = &whole[rows.clone()];

        // ghosts: every index from the end, one repeated, and an own row; rank 1 asks for none
        let indices: Vec<usize> = if rank == 1 {
            Vec::new()
        } else {
            let mut ix: Vec<usize> = (0..n).rev().collect();
            ix.push(n / 2);
            ix.push(rows.start.min(n - 1));
            ix
        };
        let mut out = vec![f64::NAN; indices.len()];
        d.fetch(owned, n, block, &indices, &mut out).unwrap();
        let expected: Vec<f64> = indices.iter().map(|&i| entry(i)).collect();
        assert_eq!(out, expected, "fetch, n {n}, rank {rank} of {size}");
        // the cached scatter is reused for the same request
        let mut again = vec![0.0; indices.len()];
        d.fetch(owned, n, block, &indices, &mut again).unwrap();
        assert_eq!(again, expected);

        // round trip: owned rows only (NaN elsewhere) -> gather -> the whole vector
        let mut v = vec![f64::NAN; n];
        v[rows.clone()].copy_from_slice(owned);
        d.gather(&mut v, block).unwrap();
        assert_eq!(v, whole, "gather, n {n}, rank {rank} of {size}");
    }

    // reductions: sum of rank + 1 is K (K + 1) / 2, the max of the ranks K - 1, of their
    // negatives 0; a NaN on one rank is NaN everywhere
    let k = size as f64;
    assert_eq!(d.sum(rank as f64 + 1.0).unwrap(), k * (k + 1.0) / 2.0);
    assert_eq!(d.sum(0.25).unwrap(), 0.25 * k);
    assert_eq!(d.max(rank as f64).unwrap(), k - 1.0);
    assert_eq!(d.max(-(rank as f64)).unwrap(), 0.0);
    let nan = d
        .max(if rank + 1 == size { f64::NAN } else { 1.0 })
        .unwrap();
    assert!(nan.is_nan(), "max with a NaN on the last rank: {nan}");

    // typed errors before any message (every rank makes the same mistake)
    let mut out = [0.0];
    assert!(matches!(
        d.fetch(&[], 21, 3, &[0], &mut out),
        Err(SolverError::DimensionMismatch {
            quantity: "owned rows",
            ..
        })
    ));
    let owned: Vec<f64> = owned_blocks(21, 3, rank, size).map(entry).collect();
    assert!(matches!(
        d.fetch(&owned, 21, 3, &[21], &mut out),
        Err(SolverError::InvalidParameter { field: "index", .. })
    ));
    assert!(matches!(
        d.fetch(&owned, 21, 3, &[0, 1], &mut out),
        Err(SolverError::DimensionMismatch {
            quantity: "fetched entries",
            ..
        })
    ));
    // and from another thread: refused, no MPI message
    std::thread::scope(|s| {
        s.spawn(|| {
            assert!(matches!(
                d.sum(1.0),
                Err(SolverError::External {
                    backend: "petsc",
                    ..
                })
            ));
        });
    });
    drop(d);
    drop(session);
}

#[test]
fn scatter_gather_round_trip_and_reductions_on_1_2_4_ranks() {
    if std::env::var_os(CHILD).is_some() {
        rank_checks();
        return;
    }
    if Command::new("mpirun").arg("--version").output().is_err() {
        eprintln!("SKIP: mpirun not installed");
        return;
    }
    let me = std::env::current_exe().unwrap();
    for ranks in [1, 2, 4] {
        let out = Command::new("mpirun")
            .args([
                "--allow-run-as-root",
                "--oversubscribe",
                "-n",
                &ranks.to_string(),
            ])
            .arg(&me)
            .args(["--exact", TEST, "--nocapture", "--test-threads", "1"])
            .env(CHILD, "1")
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{ranks} ranks: {}\n{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        // the checks ran (mpirun's status is non-zero when any rank failed; the ranks' lines
        // may interleave, so their summaries are not counted)
        assert!(
            String::from_utf8_lossy(&out.stdout).contains("1 passed"),
            "{ranks} ranks"
        );
    }
}
