//! Helpers shared by the command-line tests: run a program and insist that it succeeded, the
//! project's venv Python when it has a module, fresh scratch directories.
#![allow(dead_code)] // every test crate uses a part of it

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use capstan_elasticity::contact::{
    BoundarySolver, ContactModel, ContactSettings, ContactSolution, EndLoads, ThickBody,
    ThickBodyOperator,
};
use capstan_elasticity::friction::{RegularisedCoulomb, RegularisedCoulombParams};
use capstan_elasticity::{Component, Discretisation};

/// The model of the default contact case on `body`.
pub type DefaultContact = ContactModel<ThickBodyOperator, RegularisedCoulomb>;

/// The default contact case (regularised Coulomb `mu = 0.5`, `eps = 1e-5`,
/// `tau_max / tau0 = 2`) on `body` through the boundary-only solver: its model, solution and
/// `[slip fraction, limiting ratio (NaN without a sliding mode), max |v^2| on x3 = h]`.
pub fn default_contact(body: &ThickBody) -> (DefaultContact, ContactSolution, [f64; 3]) {
    const EPS: f64 = 1e-5;
    let params = RegularisedCoulombParams::new(0.5, EPS).unwrap();
    let model = body.model(RegularisedCoulomb, params, EPS).unwrap();
    let s = BoundarySolver::new(&model, ContactSettings::default()).unwrap();
    let sol = s.solve(EndLoads::ratio(2.0)).unwrap();
    let limit = s.sliding().map_or(f64::NAN, |m| m.upper_ratio);
    let op = model.discretisation();
    let outer = (0..body.n2)
        .map(|i| sol.displacement[op.dof([i, body.n3 - 1], Component::X2)].abs())
        .fold(0.0f64, f64::max);
    let slip = sol.slip_fraction;
    (model, sol, [slip, limit, outer])
}

/// The `capstan` binary under test.
pub const BIN: &str = env!("CARGO_BIN_EXE_capstan");

/// Runs `command`; panics with the command, its stdout and its stderr unless it exits 0.
pub fn succeed(command: &mut Command) -> Output {
    let out = command.output().unwrap();
    assert!(
        out.status.success(),
        "{command:?} failed:\n{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// `capstan ARGS`, which must succeed.
pub fn capstan(args: &[&str]) -> Output {
    succeed(Command::new(BIN).args(args))
}

/// `capstan ARGS` whatever its outcome.
pub fn capstan_output(args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .output()
        .expect("the binary runs")
}

/// `capstan ARGS` whatever its outcome: exit code (`None` when killed by a signal), stdout and
/// stderr.
pub fn capstan_status(args: &[&str]) -> (Option<i32>, String, String) {
    let out = capstan_output(args);
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// `capstan ARGS --json`, which must succeed; its report.
pub fn capstan_json(args: &[&str]) -> serde_json::Value {
    serde_json::from_slice(&capstan(&[args, &["--json"]].concat()).stdout).unwrap()
}

/// `capstan ARGS --json` run in this process through the library (`capstan::cli::run`), which
/// must succeed; its report.
pub fn run_json(args: &[&str]) -> serde_json::Value {
    use clap::Parser;
    let mut argv = vec!["capstan"];
    argv.extend_from_slice(args);
    argv.push("--json");
    let out = capstan::cli::run(capstan::cli::Cli::parse_from(argv)).unwrap();
    serde_json::from_str(&out).unwrap()
}

/// The project's `.venv` Python when it can import `module`; `None` (with a skip note on
/// stderr) otherwise.
pub fn venv_python_with(module: &str) -> Option<PathBuf> {
    let python = Path::new(env!("CARGO_MANIFEST_DIR")).join(".venv/bin/python");
    let has = Command::new(&python)
        .args(["-c", &format!("import {module}")])
        .output()
        .is_ok_and(|o| o.status.success());
    if has {
        Some(python)
    } else {
        eprintln!("skipped: no .venv/bin/python with {module}");
        None
    }
}

/// The project's `.venv` Python when it has meshio; `None` (with a skip note naming `test`)
/// otherwise, unless `CI=true`, where `.ci/run` installs it and a missing meshio fails.
pub fn meshio_python(test: &str) -> Option<PathBuf> {
    let python = venv_python_with("meshio");
    if python.is_none() && std::env::var("CI").is_ok_and(|v| v == "true") {
        panic!("{test}: CI=true but meshio is unavailable: .ci/run installs it into .venv");
    }
    python
}

/// `tests/python/check_vtu.py EXPECTED` under the venv's meshio, which must succeed; its
/// stdout and stderr, or `None` when meshio is unavailable (see [`meshio_python`]).
pub fn check_vtu_with_meshio(test: &str, expected: &Path) -> Option<String> {
    let python = meshio_python(test)?;
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/python/check_vtu.py");
    let out = succeed(Command::new(python).arg(script).arg(expected));
    Some(format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    ))
}

/// The arguments of a small sweep of Poisson's ratio over `0.1..=0.4` in `steps` steps, on a
/// grid where each point takes well under a second in the test build.
pub fn small_sweep(steps: &str) -> [&str; 12] {
    [
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
        steps,
    ]
}

/// A sweep's JSON without its `"seconds"` lines: the wall time is the one field two runs of
/// the same sweep cannot share.
pub fn without_seconds(json: &str) -> String {
    json.lines()
        .filter(|l| !l.trim_start().starts_with("\"seconds\""))
        .collect::<Vec<_>>()
        .join("\n")
}

/// A fresh, empty directory `capstan-NAME-PID` under the system's temporary directory.
pub fn scratch_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("capstan-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The numbers of the JSON array `v[key]` (panics if it is not an array of numbers).
pub fn json_array(v: &serde_json::Value, key: &str) -> Vec<f64> {
    v[key]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// One cached solve's quantities of an accuracy ladder (docs/data/contact_*ladder.json: its
/// `values` and `scales` by name), with each quantity's `behaviour` along the ladder, as the
/// refinement saw them after the solve.
pub fn cached_quantities(
    s: &serde_json::Value,
    behaviour: fn(&str) -> capstan::problem::estimate::Behaviour,
) -> std::collections::BTreeMap<String, capstan::problem::Scaled> {
    s["values"]
        .as_object()
        .unwrap()
        .iter()
        .map(|(n, v)| {
            let q = capstan::problem::Scaled {
                value: v.as_f64().unwrap(),
                scale: s["scales"][n].as_f64().unwrap(),
                behaviour: behaviour(n),
            };
            (n.clone(), q)
        })
        .collect()
}
