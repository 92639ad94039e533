//! `capstan export-system` writes a Matrix Market system that sprs (and scipy, when the venv
//! has it) read back, with `A x = b` holding for our solution to round-off.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::{capstan_json, scratch_dir, succeed, venv_python_with};

fn export(state: &str, sets: &[&str]) -> (PathBuf, serde_json::Value) {
    let dir = scratch_dir(&format!("export-{state}"));
    let set_grid = ["export-system", "--set", "grid.n2=30", "--set", "grid.n3=7"];
    let state_out = ["--state", state, "--out", dir.to_str().unwrap()];
    let report = capstan_json(&[&set_grid[..], sets, &state_out].concat());
    let file: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("system.json")).unwrap()).unwrap();
    assert_eq!(report, file);
    (dir, report)
}

/// A `matrix array real general` column, read by hand (sprs reads only the coordinate form).
fn read_array(path: &Path) -> Vec<f64> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('%'));
    let size: Vec<usize> = lines
        .next()
        .unwrap()
        .split_whitespace()
        .map(|s| s.parse().unwrap())
        .collect();
    assert_eq!(size[1], 1);
    let v: Vec<f64> = lines.map(|l| l.trim().parse().unwrap()).collect();
    assert_eq!(v.len(), size[0]);
    v
}

/// `max|A x - b| / max(1, max|b|)` with `A` read by sprs.
fn check(dir: &Path, report: &serde_json::Value) -> f64 {
    let a: sprs::TriMat<f64> = sprs::io::read_matrix_market(dir.join("A.mtx")).unwrap();
    let a: sprs::CsMat<f64> = a.to_csr();
    let b = read_array(&dir.join("b.mtx"));
    let x = read_array(&dir.join("x.mtx"));
    let n = report["unknowns"].as_u64().unwrap() as usize;
    assert_eq!((a.rows(), a.cols(), b.len(), x.len()), (n, n, n, n));
    assert_eq!(a.nnz() as u64, report["nonzeros"].as_u64().unwrap());
    let mut r = vec![0.0; n];
    for (row, vec) in a.outer_iterator().enumerate() {
        r[row] = vec.iter().map(|(c, v)| v * x[c]).sum::<f64>() - b[row];
    }
    let max = |v: &[f64]| v.iter().fold(0.0f64, |m, y| m.max(y.abs()));
    max(&r) / max(&b).max(1.0)
}

#[test]
fn exported_jacobian_at_the_solution_holds_our_solution() {
    let (dir, report) = export("solution", &[]);
    // sparse LU on a 420-unknown system: round-off only
    assert!(check(&dir, &report) < 1e-12, "{report}");
    assert!(
        report["state_residual"].as_f64().unwrap() < 1e-8,
        "{report}"
    ); // Newton tolerance
    assert!(
        report["step_from_state"].as_f64().unwrap() < 1e-6,
        "{report}"
    ); // x is v
    let dofs = &report["dofs"];
    assert_eq!(dofs["x2_dofs"].as_array().unwrap().len(), 30 * 7);
    python_check(&dir);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn exported_system_at_zero_is_the_first_newton_step() {
    // On an ellipse the body cannot slide rigidly, so `J(0)` is regular.
    let ellipse = ["--set", "obstacle.shape=ellipse", "--set", "obstacle.b=0.7"];
    let (dir, report) = export("zero", &ellipse);
    assert!(check(&dir, &report) < 1e-12, "{report}"); // round-off only
    assert_eq!(report["state"], "zero");
    let _ = std::fs::remove_dir_all(dir);
    // On the default circle it is singular (rigid rotation): exported without `x`.
    let (dir, report) = export("zero", &[]);
    assert!(report["singular"].is_string(), "{report}");
    assert!(dir.join("A.mtx").exists() && !dir.join("x.mtx").exists());
    let _ = std::fs::remove_dir_all(dir);
}

/// scipy's reader and solver on the same files, when the project's venv has scipy.
fn python_check(dir: &Path) {
    let Some(python) = venv_python_with("scipy") else {
        return;
    };
    let code = r#"
import sys, numpy as np, scipy.io, scipy.sparse.linalg as sl
d = sys.argv[1]
A = scipy.io.mmread(d + "/A.mtx").tocsc()
b = scipy.io.mmread(d + "/b.mtx").ravel()
x = scipy.io.mmread(d + "/x.mtx").ravel()
y = sl.spsolve(A, b)
print(np.abs(y - x).max() / max(1.0, np.abs(x).max()))
"#;
    let out = succeed(Command::new(&python).args(["-c", code, dir.to_str().unwrap()]));
    let diff: f64 = String::from_utf8_lossy(&out.stdout).trim().parse().unwrap();
    assert!(diff < 1e-10, "scipy's SuperLU vs our LU: {diff}"); // two pivoted LUs: round-off
}
