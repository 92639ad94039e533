//! `mpirun -n 2 capstan sweep ...` (feature `mpi`) writes the same files as the serial sweep.
//! Skipped (with a message) when `mpirun` is not installed.
#![cfg(feature = "mpi")]

mod common;

use std::process::Command;

use common::{BIN, capstan, small_sweep, succeed, without_seconds};

#[test]
fn two_ranks_write_the_serial_sweep() {
    if Command::new("mpirun").arg("--version").output().is_err() {
        eprintln!("SKIP: mpirun not installed");
        return;
    }
    let root = std::env::temp_dir().join(format!("capstan-mpi-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    let (mpi, serial) = (root.join("mpi"), root.join("serial"));
    let sweep = small_sweep("5");
    succeed(
        Command::new("mpirun")
            .args([
                "--allow-run-as-root",
                "--oversubscribe",
                "-n",
                "2",
                BIN,
                "sweep",
            ])
            .args(sweep)
            .args(["--out", mpi.to_str().unwrap()]),
    );
    capstan(&[&["sweep"], &sweep[..], &["--out", serial.to_str().unwrap()]].concat());
    let read = |d: &std::path::Path, f: &str| std::fs::read_to_string(d.join(f)).unwrap();
    assert_eq!(read(&mpi, "sweep.csv"), read(&serial, "sweep.csv"));
    assert_eq!(
        without_seconds(&read(&mpi, "sweep.json")),
        without_seconds(&read(&serial, "sweep.json"))
    );
    let _ = std::fs::remove_dir_all(root);
}
