//! Solves the default scene's accuracy ladder (`src/problem/target.rs`) step by step and caches
//! every step's converging quantities, with their scales, grid, unknowns and time, in
//! `docs/data/contact_ladder.json`: the sequences the estimator of `capstan::problem::estimate`
//! is judged on (examples/contact_accuracy.rs, tests/accuracy_estimate.rs).
//!
//! # Problem
//! The paper's body on the circle (`Scene::default()`, ratio 2, `eps` regularised Coulomb),
//! the default probes (the quarter points of the contact interval). Step `k` of the ladder is
//! `Problem::accuracy_step(k)`: Qp `p = 2 ... 6` graded toward the ends, then the order-6 mesh
//! with 2, 4, 8, ... times the elements along `x2`.
//!
//! Run: `cargo run --release --example contact_ladder -- LAST [--cache PATH]`: solves the
//! steps `0 ..= LAST` missing from the cache (a cached step is never solved again) and
//! rewrites the cache. Look at: the table of every quantity along the ladder.

use std::collections::BTreeMap;
use std::time::Instant;

use capstan::commands::accuracy::{probes, scaled};
use capstan::scene::Scene;
use serde::{Deserialize, Serialize};

/// One ladder step as cached.
#[derive(Debug, Clone, Serialize, Deserialize)]
struct CachedStep {
    step: usize,
    grid: Vec<usize>,
    unknowns: usize,
    /// Wall time of the solve, seconds.
    seconds: f64,
    /// CPU time (user + system) of the solve, seconds.
    cpu_seconds: f64,
    /// The one-minute load average when the step finished.
    load_average: f64,
    values: BTreeMap<String, f64>,
    scales: BTreeMap<String, f64>,
}

/// The cache file.
#[derive(Debug, Default, Serialize, Deserialize)]
struct Cache {
    scene: String,
    steps: Vec<CachedStep>,
}

/// User + system CPU seconds of this process (`/proc/self/stat`, clock ticks of 1/100 s).
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    // the fields after the command name in parentheses: utime and stime are fields 14, 15
    let after = stat.rsplit_once(')').map_or("", |(_, rest)| rest);
    let f: Vec<f64> = after
        .split_whitespace()
        .map(|x| x.parse().unwrap_or(0.0))
        .collect();
    (f.get(11).copied().unwrap_or(0.0) + f.get(12).copied().unwrap_or(0.0)) / 100.0
}

fn load_average() -> f64 {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next().and_then(|x| x.parse().ok()))
        .unwrap_or(f64::NAN)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let last: usize = args.first().and_then(|a| a.parse().ok()).unwrap_or(6);
    let path = args
        .iter()
        .position(|a| a == "--cache")
        .and_then(|i| args.get(i + 1).cloned())
        .unwrap_or_else(|| "docs/data/contact_ladder.json".to_owned());
    let mut cache: Cache = std::fs::read_to_string(&path)
        .ok()
        .and_then(|s| serde_json::from_str(&s).ok())
        .unwrap_or_default();
    cache.scene = "Scene::default() (the paper's body, ratio 2, default probes)".to_owned();
    let scene = Scene::default();
    let base = scene.build()?;
    let probes = probes(&scene);
    for k in 0..=last {
        if cache.steps.iter().any(|s| s.step == k) {
            continue;
        }
        let problem = base.accuracy_step(k)?;
        let (t, c) = (Instant::now(), cpu_seconds());
        let solved = problem.solve()?;
        let q = scaled(&solved.quantities(&probes)?, &solved.solution);
        let step = CachedStep {
            step: k,
            grid: problem.grid(),
            unknowns: problem.unknowns(),
            seconds: t.elapsed().as_secs_f64(),
            cpu_seconds: cpu_seconds() - c,
            load_average: load_average(),
            values: q.iter().map(|(n, v)| (n.clone(), v.value)).collect(),
            scales: q.iter().map(|(n, v)| (n.clone(), v.scale)).collect(),
        };
        eprintln!(
            "step {k}: {:?}, {} unknowns, {:.1} s wall, {:.1} s CPU, load {:.1}",
            step.grid, step.unknowns, step.seconds, step.cpu_seconds, step.load_average
        );
        cache.steps.push(step);
        cache.steps.sort_by_key(|s| s.step);
        // written after every step: a long run interrupted keeps what it solved
        std::fs::write(&path, serde_json::to_string_pretty(&cache)? + "\n")?;
    }
    let names: Vec<&String> = cache
        .steps
        .iter()
        .flat_map(|s| s.values.keys())
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .collect();
    for name in names {
        let row: Vec<String> = cache
            .steps
            .iter()
            .map(|s| {
                s.values
                    .get(name)
                    .map_or("-".to_owned(), |v| format!("{v:.10}"))
            })
            .collect();
        println!("{name}: {}", row.join(", "));
    }
    Ok(())
}
