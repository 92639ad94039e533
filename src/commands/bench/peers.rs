//! The peer FEM libraries of `capstan bench work-precision`: scripts in `bench/peers/` run by
//! the project's `.venv/bin/python` on the Lamé cylinder, one JSON object per line per grid.
//!
//! # Protocol
//! `SCRIPT --order P --levels m1,m2,... [BACKEND_FLAG B] --repeat-min .. --repeat-max ..
//! --repeat-budget ..`, each output line a JSON object with at least `method`, `backend`,
//! `n2`, `n3`, `dofs`, `setup_seconds`, `assemble_seconds`, `solve_seconds`, `seconds`,
//! `error`, `peak_mib`. A peer runs with one thread.

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

/// A peer library: its script, the module that must import, its orders and linear solvers.
/// The script names its methods `MODULE-...` (see `is_peer_method`).
#[derive(Debug, Clone, Copy)]
pub struct Peer {
    /// Display name.
    pub name: &'static str,
    /// The Python module the venv must import.
    pub module: &'static str,
    /// The script, relative to the repository root.
    pub script: &'static str,
    /// The orders run, with their grids.
    pub orders: &'static [PeerOrder],
    /// The flag choosing the linear solver and its values (every order runs each), if any.
    pub backends: Option<(&'static str, &'static [&'static str])>,
}

const fn order(order: usize, levels: &'static str, quick_levels: &'static str) -> PeerOrder {
    PeerOrder {
        order,
        levels,
        quick_levels,
    }
}

/// The peers, run in this order. Levels: scikit-fem `m` of its `4m x m` structured grid;
/// NGSolve `m` of `maxh = h / m` (unstructured), chosen so that the errors span `1e-3` to
/// `1e-11` with the last run of each order under about 4 s (orders 5, 6, 8 reach `1e-11`;
/// `p = 1` and `2` stop at `7e-4` and `9e-7`, where the meshing alone takes seconds).
pub const PEERS: [Peer; 2] = [
    Peer {
        name: "scikit-fem",
        module: "skfem",
        script: "bench/peers/skfem_lame.py",
        orders: &[order(1, "4,8,16,32", "4,8"), order(2, "4,8,16,32", "4,8")],
        backends: None,
    },
    Peer {
        name: "ngsolve",
        module: "ngsolve",
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
        backends: Some(("--inverse", &["sparsecholesky", "umfpack"])),
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

/// The venv Python and the script of `peer`: the working directory first, then the
/// repository this binary was built from.
fn locate(peer: &Peer) -> Result<(PathBuf, PathBuf), String> {
    for root in [Path::new("."), Path::new(env!("CARGO_MANIFEST_DIR"))] {
        let python = root.join(".venv/bin/python");
        let script = root.join(peer.script);
        if python.exists() && script.exists() {
            return Ok((python, script));
        }
    }
    Err(format!(
        "skipped: no .venv/bin/python and {} in the working directory or {}",
        peer.script,
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

/// Runs every order of `peer` that `keep_order` keeps, with each backend (the quick grids if
/// `quick`); the runs and the peer's status. A failing series is reported in the status and skipped.
pub fn run_peer(
    peer: &Peer,
    quick: bool,
    keep_order: &dyn Fn(usize) -> bool,
) -> (Vec<Run>, PeerStatus) {
    let mut status = PeerStatus {
        name: peer.name,
        version: None,
        status: "ran".to_owned(),
    };
    let (python, script) = match locate(peer) {
        Ok(found) => found,
        Err(why) => {
            status.status = why;
            return (vec![], status);
        }
    };
    match version(&python, peer) {
        Ok(v) => status.version = Some(v),
        Err(why) => {
            status.status = why;
            return (vec![], status);
        }
    }
    let backends: Vec<Option<(&str, &str)>> = match peer.backends {
        None => vec![None],
        Some((flag, values)) => values.iter().map(|v| Some((flag, *v))).collect(),
    };
    let mut runs = vec![];
    for o in peer.orders.iter().filter(|o| keep_order(o.order)) {
        for backend in &backends {
            let levels = if quick { o.quick_levels } else { o.levels };
            let mut command = Command::new(&python);
            command
                .arg(&script)
                .args(["--order", &o.order.to_string(), "--levels", levels])
                .args(REPEAT_RULE.peer_args());
            if let Some((flag, value)) = backend {
                command.args([flag, value]);
            }
            match run_script(&mut command) {
                Ok(r) => runs.extend(r),
                Err(e) => status.status = format!("order {}: {e}", o.order),
            }
        }
    }
    (runs, status)
}

fn run_script(command: &mut Command) -> Result<Vec<Run>, String> {
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
        .map(parse_line)
        .collect()
}

/// One line of a peer's output as a [`Run`] of problem `lame`, one thread.
fn parse_line(line: &str) -> Result<Run, String> {
    let v: serde_json::Value =
        serde_json::from_str(line).map_err(|e| format!("peer output: {e}"))?;
    let num = |k: &str| v[k].as_f64().unwrap_or(f64::NAN);
    let text = |k: &str| {
        v[k].as_str()
            .map(str::to_owned)
            .ok_or_else(|| format!("peer output: no `{k}` in {line}"))
    };
    Ok(Run {
        problem: "lame",
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
        error: num("error"),
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

    #[test]
    fn parse_line_reads_the_protocol_and_requires_method_and_backend() {
        let r = parse_line(
            r#"{"method": "ngsolve-p4", "backend": "umfpack", "n2": 292, "n3": 0, "dofs": 4976,
            "setup_seconds": 0.001, "assemble_seconds": 0.01, "solve_seconds": 0.02,
            "seconds": 0.031, "error": 2.3e-6, "peak_mib": 1.5}"#,
        )
        .unwrap();
        assert_eq!(
            (r.method.as_str(), r.backend.as_str()),
            ("ngsolve-p4", "umfpack")
        );
        assert_eq!((r.threads, r.dofs), (1, 4976));
        assert_eq!(r.error, 2.3e-6);
        assert!(parse_line(r#"{"backend": "umfpack"}"#).is_err());
        assert!(is_peer_method(&r.method) && !is_peer_method("fem-q2"));
    }
}
