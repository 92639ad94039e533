//! `mpirun -n 2 capstan sweep ...` (feature `mpi`) writes the same files as the serial sweep.
//! Skipped (with a message) when `mpirun` is not installed.
#![cfg(feature = "mpi")]

use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_capstan");
const SWEEP: [&str; 12] = [
    "--set",
    "grid.n2=30",
    "--set",
    "grid.n3=7",
    "--param",
    "body.poisson",
    "--from",
    "0.1",
    "--to",
    "0.4",
    "--steps",
    "5",
];

#[test]
fn two_ranks_write_the_serial_sweep() {
    if Command::new("mpirun").arg("--version").output().is_err() {
        eprintln!("SKIP: mpirun not installed");
        return;
    }
    let root = std::env::temp_dir().join(format!("capstan-mpi-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    let (mpi, serial) = (root.join("mpi"), root.join("serial"));
    let out = Command::new("mpirun")
        .args([
            "--allow-run-as-root",
            "--oversubscribe",
            "-n",
            "2",
            BIN,
            "sweep",
        ])
        .args(SWEEP)
        .args(["--out", mpi.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let out = Command::new(BIN)
        .arg("sweep")
        .args(SWEEP)
        .args(["--out", serial.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let read = |d: &std::path::Path, f: &str| std::fs::read_to_string(d.join(f)).unwrap();
    assert_eq!(read(&mpi, "sweep.csv"), read(&serial, "sweep.csv"));
    let strip = |s: String| {
        s.lines()
            .filter(|l| !l.trim_start().starts_with("\"seconds\"")) // wall time
            .collect::<Vec<_>>()
            .join("\n")
    };
    assert_eq!(
        strip(read(&mpi, "sweep.json")),
        strip(read(&serial, "sweep.json"))
    );
    let _ = std::fs::remove_dir_all(root);
}
