//! `mpirun -n K capstan contact ... --set solver.linear='"petsc"'` (feature `petsc`) gives the
//! serial full-system Newton's answer (sparse LU) to 1e-8 relative, on 1, 2 and 4 ranks
//! (oversubscribed), for a plane-strain scene (assembled whole on every rank) and a 3-D band on
//! a cone (each rank assembling its own rows, residuals gathered); rank 0 alone prints and
//! writes; the Krylov iterations reach the observers; a spent KSP budget and unilateral
//! contact on a body assembled over ranks are typed errors.
//! Skipped (with a message) when `mpirun` is not installed.
#![cfg(feature = "petsc")]

mod common;

use std::process::Command;

use common::{BIN, capstan_json, scratch_dir, succeed};

/// The plane-strain default scene on a 61 x 11 grid (1,342 unknowns), full-system Newton.
const PLANE: [&str; 6] = [
    "--set",
    "grid.n2=61",
    "--set",
    "grid.n3=11",
    "--set",
    "solver.nonlinear=\"full-newton\"",
];

/// A finite-width band on a circular cone, 9 x 33 x 5 Q1 nodes (4,455 unknowns), solved by
/// the default GMRES + GAMG with the body's six rigid motions as GAMG's near-null space
/// (without them GAMG needed twice the Krylov iterations here and, on some rank counts,
/// stalled near 1e-9 relative).
const CONE: [&str; 26] = [
    "--set",
    "body.dimension=3",
    "--set",
    "discretisation.method=fem-q1",
    "--set",
    "obstacle.shape=cone",
    "--set",
    "obstacle.ubar=0.25*sin(t)",
    "--set",
    "obstacle.vbar=0.25*cos(t)",
    "--set",
    "body.x1=1.2",
    "--set",
    "body.width=0.4",
    "--set",
    "body.thickness=0.1",
    "--set",
    "grid.n2=33",
    "--set",
    "grid.n3=5",
    "--set",
    "grid.n1=9",
    "--set",
    "loads.tau_max=1.2",
    "--set",
    "solver.nonlinear=\"full-newton\"",
];

const PETSC: [&str; 2] = ["--set", "solver.linear=\"petsc\""];

const MUMPS: [&str; 2] = [
    "--set",
    "solver.petsc_options=\"-ksp_type preonly -pc_type lu -pc_factor_mat_solver_type mumps\"",
];

fn mpirun(ranks: usize) -> Command {
    let mut c = Command::new("mpirun");
    c.args([
        "--allow-run-as-root",
        "--oversubscribe",
        "-n",
        &ranks.to_string(),
        BIN,
    ]);
    c
}

fn have_mpirun() -> bool {
    if Command::new("mpirun").arg("--version").output().is_ok() {
        return true;
    }
    eprintln!("SKIP: mpirun not installed");
    false
}

/// Every number in `v` under its path (array entries share their array's path).
fn numbers(v: &serde_json::Value, path: &str, out: &mut Vec<(String, f64)>) {
    match v {
        serde_json::Value::Object(m) => {
            for (k, x) in m {
                numbers(x, &format!("{path}.{k}"), out);
            }
        }
        serde_json::Value::Array(a) => a.iter().for_each(|x| numbers(x, path, out)),
        serde_json::Value::Number(n) => out.push((path.to_owned(), n.as_f64().unwrap())),
        _ => {}
    }
}

/// `max |a - b|` over every number of the contact surface and the extreme displacements,
/// relative to the largest displacement (fields that vanish, as `v3` at the contact, are
/// measured against it too).
fn relative_difference(serial: &serde_json::Value, parallel: &serde_json::Value) -> f64 {
    let scale = ["max_azimuthal_displacement", "max_radial_displacement"]
        .iter()
        .map(|k| serial[k]["value"].as_f64().unwrap().abs())
        .fold(0.0, f64::max);
    assert!(scale > 0.0);
    let mut worst = 0.0f64;
    for key in [
        "contact",
        "max_azimuthal_displacement",
        "max_radial_displacement",
        "solid",
    ] {
        let (mut a, mut b) = (Vec::new(), Vec::new());
        numbers(&serial[key], key, &mut a);
        numbers(&parallel[key], key, &mut b);
        assert_eq!(a.len(), b.len(), "{key}");
        let mut fields = std::collections::BTreeMap::<&str, f64>::new();
        for ((p, x), (q, _)) in a.iter().zip(&b) {
            assert_eq!(p, q);
            let m = fields.entry(p).or_insert(0.0);
            *m = m.max(x.abs());
        }
        for ((p, x), (_, y)) in a.iter().zip(&b) {
            // stresses and tractions on their own scale, displacements on the displacement's
            let own = fields[p.as_str()].max(scale);
            worst = worst.max((x - y).abs() / own);
        }
    }
    worst
}

fn json(output: &std::process::Output) -> serde_json::Value {
    // one document: only rank 0 prints
    serde_json::from_slice(&output.stdout).unwrap_or_else(|e| {
        panic!(
            "stdout is not one JSON document ({e}):\n{}",
            String::from_utf8_lossy(&output.stdout)
        )
    })
}

fn agrees_on_1_2_4_ranks(scene: &[&str], options: &[&str]) {
    let serial = capstan_json(&[&["contact"][..], scene].concat());
    assert_eq!(serial["status"], "converged");
    for ranks in [1, 2, 4] {
        let out = succeed(
            mpirun(ranks)
                .arg("contact")
                .args(scene)
                .args(PETSC)
                .args(options)
                .arg("--json"),
        );
        let parallel = json(&out);
        assert_eq!(parallel["status"], "converged", "{ranks} ranks");
        assert_eq!(parallel["slip_fraction"], serial["slip_fraction"]);
        // the Krylov iterations of every Newton step are counted
        assert!(parallel["linear_iterations"].as_u64().unwrap() > 0);
        let d = relative_difference(&serial, &parallel);
        eprintln!("{ranks} ranks: relative difference {d:.3e}");
        assert!(d < 1e-8, "{ranks} ranks: relative difference {d:.3e}");
    }
}

#[test]
fn plane_strain_on_1_2_4_ranks_matches_the_serial_solve() {
    if have_mpirun() {
        agrees_on_1_2_4_ranks(&PLANE, &[]);
    }
}

#[test]
fn plane_strain_by_mumps_on_1_2_4_ranks_matches_the_serial_solve() {
    if have_mpirun() {
        agrees_on_1_2_4_ranks(&PLANE, &MUMPS);
    }
}

#[test]
fn cone_band_on_1_2_4_ranks_matches_the_serial_solve() {
    if have_mpirun() {
        agrees_on_1_2_4_ranks(&CONE, &[]);
    }
}

/// `PETSC_OPTIONS=-log_view` on 2 ranks (the 3-D band, 9 x 33 x 9: each rank assembles its
/// rows, the residuals are gathered) with the default error estimate: once an MPI error in the first
/// gather (`MPI_ERR_TRUNCATE`) and a panic, because the coarser grid of the estimate was
/// solved on a second thread beside the fine solve and the two threads' collectives
/// interleaved differently on the two ranks. Now the coarser grid is solved after the fine
/// one on the same thread (another thread's PETSc call is a typed error), the answer is the
/// serial one, and PETSc's log goes to stderr: stdout stays one JSON document.
#[test]
fn log_view_on_2_ranks_with_the_error_estimate_gives_the_serial_answer() {
    if !have_mpirun() {
        return;
    }
    // 9 points through the thickness: the coarser grid of the estimate exists (5 x 17 x 5)
    let scene = [&CONE[..], &["--set", "grid.n3=9"]].concat();
    let serial = capstan_json(&[&["contact"][..], &scene].concat());
    let out = succeed(
        mpirun(2)
            .env("PETSC_OPTIONS", "-log_view")
            .arg("contact")
            .args(&scene)
            .args(PETSC)
            .arg("--json"),
    );
    let parallel = json(&out);
    assert_eq!(parallel["status"], "converged");
    let d = relative_difference(&serial, &parallel);
    assert!(d < 1e-8, "relative difference {d:.3e}");
    // the coarser grid was solved too: the same estimate as the serial run's
    let (a, b) = (&serial["estimated_error"], &parallel["estimated_error"]);
    assert!(a.is_object() && b.is_object(), "{a} {b}");
    let (mut ea, mut eb) = (Vec::new(), Vec::new());
    numbers(a, "estimated_error", &mut ea);
    numbers(b, "estimated_error", &mut eb);
    assert_eq!(ea.len(), eb.len());
    assert!(!ea.is_empty());
    for ((p, x), (_, y)) in ea.iter().zip(&eb) {
        assert!(
            (x - y).abs() <= 1e-6 * x.abs().max(1e-12),
            "{p}: {x} vs {y}"
        );
    }
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("Performance Summary"), "{stderr}");
}

#[test]
fn rank_0_alone_writes_and_reports_krylov_iterations() {
    if !have_mpirun() {
        return;
    }
    let dir = scratch_dir("petsc-out");
    let out = succeed(
        mpirun(2)
            .args(["-v", "contact"])
            .args(PLANE)
            .args(PETSC)
            .args(["--out", dir.to_str().unwrap()]),
    );
    for file in ["contact.json", "contact.csv", "scene.toml"] {
        assert!(dir.join(file).exists(), "{file}");
    }
    let scene = std::fs::read_to_string(dir.join("scene.toml")).unwrap();
    assert!(scene.contains("linear = \"petsc\""), "{scene}");
    let stderr = String::from_utf8_lossy(&out.stderr);
    let krylov = stderr.lines().filter(|l| l.starts_with("krylov")).count();
    let newton = stderr.lines().filter(|l| l.starts_with("newton")).count();
    // rank 1 is quiet: each Newton iterate printed once, with its Krylov iterations
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("contact.json")).unwrap()).unwrap();
    // (Newton attempts that fail and are retried by the continuation report their Krylov
    // iterations too, but are not counted in `linear_iterations`)
    assert!(
        krylov as u64 >= report["linear_iterations"].as_u64().unwrap() && krylov > 0,
        "{krylov} Krylov lines:\n{stderr}"
    );
    assert!(newton > 0);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn spent_ksp_budget_and_wrong_nonlinear_solver_are_typed_errors() {
    // one rank without mpirun (a singleton): the exit code is capstan's own
    let out = Command::new(BIN)
        .arg("contact")
        .args(PLANE)
        .args(PETSC)
        .args([
            "--set",
            "solver.petsc_options=\"-pc_type none -ksp_max_it 2\"",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(4));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("-ksp_max_it"), "{stderr}");
    let out = Command::new(BIN)
        .args(["contact", "--set", "solver.linear=\"petsc\""])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("solver.linear") && stderr.contains("full-newton"),
        "{stderr}"
    );
}

#[test]
fn unilateral_contact_on_a_body_assembled_over_ranks_is_refused_naming_the_key() {
    if !have_mpirun() {
        return;
    }
    // each rank assembles its rows of the 3-D body; the Signorini rows need whole rows of A
    let out = mpirun(2)
        .arg("contact")
        .args(CONE)
        .args(PETSC)
        .args(["--set", "contact.kind=\"unilateral\""])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("contact.kind") && stderr.contains("more than one rank"),
        "{stderr}"
    );
}

/// The stick/slip counts of every Newton iterate (`-v`): on 2 and 4 ranks each rank counts
/// the sites whose rows it owns and the counts are summed over the ranks (a collective
/// reduction), on 1 rank the whole face is counted; the same counts, iterate by iterate, on
/// the 3-D band (each rank assembling its rows).
#[test]
fn stick_slip_counts_summed_over_ranks_equal_one_rank() {
    if !have_mpirun() {
        return;
    }
    let counts = |ranks: usize| -> Vec<(u64, u64)> {
        let out = succeed(
            mpirun(ranks)
                .args(["-v", "contact"])
                .args(CONE)
                .args(PETSC)
                .args(["--set", "output.error_estimate=false", "--json"]),
        );
        let stderr = String::from_utf8_lossy(&out.stderr);
        let number = |line: &str, key: &str| -> Option<u64> {
            let mut words = line.split_whitespace();
            words.find(|w| *w == key)?;
            words.next()?.parse().ok()
        };
        stderr
            .lines()
            .filter(|l| l.starts_with("newton"))
            .filter_map(|l| Some((number(l, "stick")?, number(l, "slip")?)))
            .collect()
    };
    let one = counts(1);
    assert!(one.len() > 3, "{one:?}");
    // the band slips on all its 297 sites at the end
    assert!(one.iter().any(|&(stick, _)| stick > 0));
    assert_eq!(one.last().unwrap().0, 0);
    for ranks in [2, 4] {
        assert_eq!(counts(ranks), one, "{ranks} ranks");
    }
}

/// The full-system Newton on each rank's rows (the default: iterate, residual and update held
/// as the rank's rows plus ghosts, norms by reductions) against the same Newton on whole
/// vectors on every rank (`-capstan_owned_newton false`), the 3-D band on 2 and 4 ranks: the
/// same Newton steps and the same answer to 1e-10 (and both the serial one to 1e-8).
#[test]
fn newton_on_owned_rows_equals_newton_on_whole_vectors() {
    if !have_mpirun() {
        return;
    }
    let serial = capstan_json(&[&["contact"][..], &CONE[..]].concat());
    for ranks in [2, 4] {
        let run = |options: &[&str]| {
            json(&succeed(
                mpirun(ranks)
                    .arg("contact")
                    .args(CONE)
                    .args(PETSC)
                    .args(options)
                    .args(["--set", "output.error_estimate=false", "--json"]),
            ))
        };
        let owned = run(&[]);
        let whole = run(&[
            "--set",
            "solver.petsc_options=\"-capstan_owned_newton false\"",
        ]);
        for v in [&owned, &whole] {
            assert_eq!(v["status"], "converged", "{ranks} ranks");
        }
        assert_eq!(
            owned["newton_iterations"], whole["newton_iterations"],
            "{ranks} ranks"
        );
        let d = relative_difference(&whole, &owned);
        eprintln!("{ranks} ranks: owned rows against whole vectors {d:.3e}");
        assert!(d < 1e-10, "{ranks} ranks: {d:.3e}");
        let d = relative_difference(&serial, &owned);
        assert!(d < 1e-8, "{ranks} ranks against serial: {d:.3e}");
    }
}
