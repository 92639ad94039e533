//! The peer FEM libraries of `capstan bench work-precision`: scripts in `bench/peers/` run by
//! the project's `.venv/bin/python` on the bench's problems (each peer says which: [`Peer`]),
//! one JSON object per line per grid.
//!
//! # Protocol
//! `SCRIPT --order P --levels m1,m2,... [BACKEND_FLAG B] --repeat-min .. --repeat-max ..
//! --repeat-budget .. [--error-points DIR]`, each output line a JSON object with at least
//! `method`, `backend`, `n2`, `n3`, `dofs`, `setup_seconds`, `assemble_seconds`,
//! `solve_seconds`, `seconds`, `peak_mib` and either `error` (the peer's own relative L2 error
//! against an exact solution) or, with `--error-points`, `error_points`: a file of
//! little-endian f64 rows `(x, y, w, u_x, u_y)`, the peer's quadrature points on its own
//! elements, their weights and its solution there, from which capstan forms the error against
//! its reference ([`super::peer_error`]). A peer runs with one thread.

use std::path::{Path, PathBuf};
use std::process::Command;

use serde::Serialize;

use super::run::{REPEAT_RULE, Run};

/// One order of a peer with its grids: `--levels` of the full and of the quick benchmark.
#[derive(Debug, Clone, Copy)]
pub struct PeerOrder {
    /// `--order`.
    pub order: usize,
    /// `--levels` of the full benchmark.
    pub levels: &'static str,
    /// `--levels` of `--quick`.
    pub quick_levels: &'static str,
}

/// The peer's runs on one problem: its script, its orders and linear solvers.
#[derive(Debug, Clone, Copy)]
pub struct PeerProblem {
    /// The bench's problem (`lame`, `mms`, `paper`).
    pub problem: &'static str,
    /// The script, relative to the repository root.
    pub script: &'static str,
    /// The orders run, with their grids.
    pub orders: &'static [PeerOrder],
    /// The flag choosing the linear solver and its values (every order runs each), if any.
    pub backends: Option<(&'static str, &'static [&'static str])>,
    /// Whether the script leaves the error to capstan: it is given `--error-points DIR` and
    /// names in each line's `error_points` a file of its quadrature points, weights and
    /// solution values (`peer_error::points_error`), for problems measured against capstan's
    /// own reference (`paper`).
    pub error_points: bool,
}

/// A peer library: the module that must import and the problems it runs. The scripts name
/// their methods `MODULE-...` (see `is_peer_method`).
#[derive(Debug, Clone, Copy)]
pub struct Peer {
    /// Display name.
    pub name: &'static str,
    /// The Python module the venv must import.
    pub module: &'static str,
    /// The problems it runs, each with its script.
    pub problems: &'static [PeerProblem],
}

const fn order(order: usize, levels: &'static str, quick_levels: &'static str) -> PeerOrder {
    PeerOrder {
        order,
        levels,
        quick_levels,
    }
}

const NGSOLVE_INVERSES: (&str, &[&str]) = ("--inverse", &["sparsecholesky", "umfpack"]);

/// The peers, run in this order, and their problems.
///
/// Levels: scikit-fem `m` of its `4m x m` structured grid; NGSolve on `lame` and `mms` `m` of
/// `maxh = h / m` (unstructured; on `lame` chosen so that the errors span `1e-3` to `1e-11`
/// with the last run of each order under about 4 s: orders 5, 6, 8 reach `1e-11`, `p = 1`
/// and `2` stop at `7e-4` and `9e-7`, where the meshing alone takes seconds); NGSolve on
/// `paper` `m` levels of `RefineHP` toward the four corners of a mesh with `maxh = 0.5` and
/// `0.5 / m` at the corners (`bench/peers/ngsolve_paper.py`).
pub const PEERS: [Peer; 2] = [
    Peer {
        name: "scikit-fem",
        module: "skfem",
        problems: &[PeerProblem {
            problem: "lame",
            script: "bench/peers/skfem_lame.py",
            orders: &[order(1, "4,8,16,32", "4,8"), order(2, "4,8,16,32", "4,8")],
            backends: None,
            error_points: false,
        }],
    },
    Peer {
        name: "ngsolve",
        module: "ngsolve",
        problems: &[
            PeerProblem {
                problem: "lame",
                script: "bench/peers/ngsolve_lame.py",
                orders: &[
                    order(1, "2,4,8,16,32", "2,4"),
                    order(2, "2,4,8,16,32", "2,4"),
                    order(3, "1,2,4,8,16", "2,4"),
                    order(4, "1,2,4,8,16", "2,4"),
                    order(5, "1,2,4,8,16", "1,2"),
                    order(6, "1,2,4,8", "1,2"),
                    order(8, "1,2,4,8", "1,2"),
                ],
                backends: Some(NGSOLVE_INVERSES),
                error_points: false,
            },
            PeerProblem {
                problem: "mms",
                script: "bench/peers/ngsolve_mms.py",
                orders: &[
                    order(2, "2,4,8,16,32", "2,4"),
                    order(3, "1,2,4,8,16", "1,2"),
                    order(4, "1,2,4,8,16", "1,2"),
                    order(5, "1,2,4,8", "1,2"),
                    order(6, "1,2,4,8", "1,2"),
                    order(8, "1,2,4", "1,2"),
                ],
                backends: Some(("--inverse", &["sparsecholesky"])),
                error_points: false,
            },
            PeerProblem {
                problem: "paper",
                script: "bench/peers/ngsolve_paper.py",
                orders: &[
                    order(4, "0,1,2,3,4,6,8,10,12", "0,2"),
                    order(5, "0,1,2,3,4,6,8,10,12", "0,2"),
                    order(6, "0,1,2,3,4,6,8,10,12", "0,2"),
                    order(8, "0,1,2,3,4,6,8,10,12", "0,2"),
                ],
                backends: Some(("--inverse", &["sparsecholesky"])),
                error_points: true,
            },
        ],
    },
];

/// What happened to one peer.
#[derive(Debug, Clone, Serialize)]
pub struct PeerStatus {
    /// [`Peer::name`].
    pub name: &'static str,
    /// The library's `__version__`, when it imported.
    pub version: Option<String>,
    /// `ran`, or why (part of) it did not.
    pub status: String,
}

/// The venv Python and `script`: the working directory first, then the repository this
/// binary was built from.
fn locate(script: &str) -> Result<(PathBuf, PathBuf), String> {
    for root in [Path::new("."), Path::new(env!("CARGO_MANIFEST_DIR"))] {
        let python = root.join(".venv/bin/python");
        let script = root.join(script);
        if python.exists() && script.exists() {
            return Ok((python, script));
        }
    }
    Err(format!(
        "skipped: no .venv/bin/python and {script} in the working directory or {}",
        env!("CARGO_MANIFEST_DIR")
    ))
}

/// The peer's version if the venv imports its module.
fn version(python: &Path, peer: &Peer) -> Result<String, String> {
    let code = format!("import {0}; print({0}.__version__)", peer.module);
    match Command::new(python).args(["-c", &code]).output() {
        Ok(o) if o.status.success() => Ok(String::from_utf8_lossy(&o.stdout).trim().to_owned()),
        _ => Err(format!(
            "skipped: {} cannot import {} (.venv/bin/pip install {})",
            python.display(),
            peer.module,
            peer.name
        )),
    }
}

/// The error of a peer's run from its points file: `(problem, file) -> relative L2 error`
/// (`peer_error::points_error` against the problem's reference).
pub type PointsError<'a> = &'a dyn Fn(&str, &Path) -> Result<f64, String>;

/// What to run of a peer: the quick grids or all, which orders and problems, and how the
/// errors left to capstan are measured.
pub struct PeerSelection<'a> {
    /// The quick grids.
    pub quick: bool,
    /// Whether an order is run.
    pub keep_order: &'a dyn Fn(usize) -> bool,
    /// Whether a problem is run.
    pub keep_problem: &'a dyn Fn(&str) -> bool,
    /// The error of a run that names an `error_points` file.
    pub points_error: PointsError<'a>,
}

/// Runs every selected problem and order of `peer` with each backend; the runs and the
/// peer's status. A failing series is reported in the status and skipped.
pub fn run_peer(peer: &Peer, selection: &PeerSelection<'_>) -> (Vec<Run>, PeerStatus) {
    let mut status = PeerStatus {
        name: peer.name,
        version: None,
        status: "ran".to_owned(),
    };
    let mut runs = vec![];
    for problem in peer
        .problems
        .iter()
        .filter(|p| (selection.keep_problem)(p.problem))
    {
        let (python, script) = match locate(problem.script) {
            Ok(found) => found,
            Err(why) => {
                status.status = why;
                continue;
            }
        };
        if status.version.is_none() {
            match version(&python, peer) {
                Ok(v) => status.version = Some(v),
                Err(why) => {
                    status.status = why;
                    return (runs, status);
                }
            }
        }
        let points_dir = std::env::temp_dir().join(format!(
            "capstan-peer-points-{}-{}",
            std::process::id(),
            problem.problem
        ));
        if problem.error_points
            && let Err(e) = std::fs::create_dir_all(&points_dir)
        {
            status.status = format!("{}: {}: {e}", problem.problem, points_dir.display());
            continue;
        }
        let backends: Vec<Option<(&str, &str)>> = match problem.backends {
            None => vec![None],
            Some((flag, values)) => values.iter().map(|v| Some((flag, *v))).collect(),
        };
        for o in problem
            .orders
            .iter()
            .filter(|o| (selection.keep_order)(o.order))
        {
            for backend in &backends {
                let levels = if selection.quick {
                    o.quick_levels
                } else {
                    o.levels
                };
                let mut command = Command::new(&python);
                command
                    .arg(&script)
                    .args(["--order", &o.order.to_string(), "--levels", levels])
                    .args(REPEAT_RULE.peer_args());
                if let Some((flag, value)) = backend {
                    command.args([flag, value]);
                }
                if problem.error_points {
                    command.arg("--error-points").arg(&points_dir);
                }
                let measure = |file: &Path| (selection.points_error)(problem.problem, file);
                match run_script(&mut command, problem.problem, &measure) {
                    Ok(r) => runs.extend(r),
                    Err(e) => {
                        status.status = format!("{} order {}: {e}", problem.problem, o.order);
                    }
                }
            }
        }
        if problem.error_points {
            let _ = std::fs::remove_dir_all(&points_dir); // best effort: a temporary directory
        }
    }
    (runs, status)
}

fn run_script(
    command: &mut Command,
    problem: &'static str,
    measure: &dyn Fn(&Path) -> Result<f64, String>,
) -> Result<Vec<Run>, String> {
    let out = command
        .output()
        .map_err(|e| format!("peer failed to start: {e}"))?;
    if !out.status.success() {
        return Err(format!(
            "peer failed: {}",
            String::from_utf8_lossy(&out.stderr)
                .lines()
                .last()
                .unwrap_or("")
        ));
    }
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|line| parse_line(line, problem, measure))
        .collect()
}

/// One line of a peer's output as a [`Run`] of `problem`, one thread. A line naming an
/// `error_points` file gets its error from `measure` (the file is removed afterwards).
fn parse_line(
    line: &str,
    problem: &'static str,
    measure: &dyn Fn(&Path) -> Result<f64, String>,
) -> Result<Run, String> {
    let v: serde_json::Value =
        serde_json::from_str(line).map_err(|e| format!("peer output: {e}"))?;
    let num = |k: &str| v[k].as_f64().unwrap_or(f64::NAN);
    let text = |k: &str| {
        v[k].as_str()
            .map(str::to_owned)
            .ok_or_else(|| format!("peer output: no `{k}` in {line}"))
    };
    let error = match v["error_points"].as_str() {
        Some(file) => {
            let file = Path::new(file);
            let e = measure(file);
            let _ = std::fs::remove_file(file); // best effort: a temporary file
            e?
        }
        None => v["error"]
            .as_f64()
            .ok_or_else(|| format!("peer output: no `error` or `error_points` in {line}"))?,
    };
    Ok(Run {
        problem,
        method: text("method")?,
        backend: text("backend")?,
        threads: 1,
        n2: num("n2") as usize,
        n3: num("n3") as usize,
        dofs: num("dofs") as usize,
        setup_seconds: num("setup_seconds"),
        assemble_seconds: num("assemble_seconds"),
        solve_seconds: num("solve_seconds"),
        seconds: num("seconds"),
        error,
        peak_mib: num("peak_mib"),
    })
}

/// Whether a method name is a peer's: the scripts name their methods after the module
/// (`skfem-q2`, `ngsolve-p4`).
pub fn is_peer_method(method: &str) -> bool {
    PEERS.iter().any(|p| method.starts_with(p.module))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn no_points(_: &Path) -> Result<f64, String> {
        Err("no points expected".to_owned())
    }

    #[test]
    fn parse_line_reads_the_protocol_and_requires_method_backend_and_error() {
        let r = parse_line(
            r#"{"method": "ngsolve-p4", "backend": "umfpack", "n2": 292, "n3": 0, "dofs": 4976,
            "setup_seconds": 0.001, "assemble_seconds": 0.01, "solve_seconds": 0.02,
            "seconds": 0.031, "error": 2.3e-6, "peak_mib": 1.5}"#,
            "mms",
            &no_points,
        )
        .unwrap();
        assert_eq!(
            (r.method.as_str(), r.backend.as_str(), r.problem),
            ("ngsolve-p4", "umfpack", "mms")
        );
        assert_eq!((r.threads, r.dofs), (1, 4976));
        assert_eq!(r.error, 2.3e-6);
        assert!(
            parse_line(
                r#"{"backend": "umfpack", "error": 1.0}"#,
                "lame",
                &no_points
            )
            .is_err()
        );
        assert!(
            parse_line(
                r#"{"method": "ngsolve-p4", "backend": "umfpack"}"#,
                "lame",
                &no_points
            )
            .is_err()
        );
        assert!(is_peer_method(&r.method) && !is_peer_method("fem-q2"));
    }

    #[test]
    fn parse_line_measures_an_error_points_file_and_removes_it() {
        let file =
            std::env::temp_dir().join(format!("capstan-parse-line-{}.f64", std::process::id()));
        std::fs::write(&file, [0u8; 8]).unwrap();
        let line = format!(
            r#"{{"method": "ngsolve-p6", "backend": "sparsecholesky", "n2": 98, "n3": 0,
            "dofs": 5558, "seconds": 0.05, "error": null, "error_points": "{}"}}"#,
            file.display()
        );
        let seen = std::cell::Cell::new(false);
        let measure = |f: &Path| {
            seen.set(f == file.as_path() && f.exists());
            Ok(4.5e-7)
        };
        let r = parse_line(&line, "paper", &measure).unwrap();
        assert!(seen.get());
        assert_eq!((r.problem, r.error, r.dofs), ("paper", 4.5e-7, 5558));
        assert!(!file.exists());
        // a failing measurement is the run's error
        std::fs::write(&file, [0u8; 8]).unwrap();
        let failing = |_: &Path| Err("bad points".to_owned());
        assert_eq!(
            parse_line(&line, "paper", &failing).unwrap_err(),
            "bad points"
        );
        assert!(!file.exists());
    }

    #[test]
    fn every_peer_problem_is_a_bench_problem_with_increasing_levels() {
        for peer in &PEERS {
            for p in peer.problems {
                assert!(
                    ["lame", "mms", "paper"].contains(&p.problem),
                    "{}",
                    p.problem
                );
                assert!(p.script.starts_with("bench/peers/") && p.script.ends_with(".py"));
                for o in p.orders {
                    for levels in [o.levels, o.quick_levels] {
                        let m: Vec<usize> = levels.split(',').map(|s| s.parse().unwrap()).collect();
                        assert!(m.windows(2).all(|w| w[0] < w[1]), "{levels}");
                    }
                }
            }
        }
    }
}
