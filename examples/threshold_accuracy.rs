//! The threshold ratio of the default scene at accuracy targets (issue 28's must-show table):
//! for each tolerance, `capstan threshold --tol TOL` through the library, its estimate, its
//! true error against the tightest run and against the limit extrapolated from the tightest
//! run's ladder, and the time.
//!
//! # Problem
//! The paper's body on the circle (`Scene::default()`), the tension ratio `tau_max / tau0` at
//! which the whole contact face slides. Under `accuracy.tol` the hp ladder of
//! `src/problem/target.rs` (Qp `p = 2 ... 6`, `p` layers of ratio 0.15 toward the corners)
//! refines until the estimate `e_k = max(|Q_k - Q_{k-1}|, |Q_{k-1} - Q_{k-2}| / 4)` is below
//! `tol` relative. The ladder converges geometrically (a factor `q` per step), so the limit is
//! extrapolated from the tightest run's last two values as
//! ```text
//! Q_inf = Q_k + (Q_k - Q_{k-1}) / (q - 1),   q = (Q_{k-1} - Q_{k-2}) / (Q_k - Q_{k-1})
//! ```
//!
//! Run: `cargo run --release --example threshold_accuracy -- [TOL ...]` (default
//! `1e-3 1e-4 1e-5`, tightest last). Look at: every true error below its tolerance and every
//! `estimate / true` between 0.5 and 10 (docs/verification.md, "Accuracy targets").

use std::time::Instant;

use capstan::commands::threshold;
use capstan::scene::Scene;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut tolerances: Vec<f64> = std::env::args()
        .skip(1)
        .filter_map(|x| x.parse().ok())
        .collect();
    if tolerances.is_empty() {
        tolerances = vec![1e-3, 1e-4, 1e-5];
    }
    let mut runs = Vec::new();
    for &tol in &tolerances {
        let mut scene = Scene::default();
        scene.accuracy.tol = Some(tol);
        let t = Instant::now();
        let report = threshold::report(&scene)?;
        runs.push((tol, report, t.elapsed().as_secs_f64()));
    }
    let (_, tightest, _) = runs
        .iter()
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .expect("at least one tolerance");
    let ladder: Vec<f64> = tightest
        .accuracy
        .as_ref()
        .map(|a| {
            a.steps
                .iter()
                .filter_map(|s| s.values.get("threshold_ratio").copied())
                .collect()
        })
        .unwrap_or_default();
    println!("ladder of the tightest run: {ladder:?}");
    let limit = match ladder[..] {
        [.., a, b, c] if (c - b) != 0.0 => {
            let q = (b - a) / (c - b);
            // the remaining differences d / q + d / q^2 + ... = d / (q - 1), d = c - b
            Some(c + (c - b) / (q - 1.0))
        }
        _ => None,
    };
    if let Some(l) = limit {
        println!("extrapolated limit: {l:.8}");
    }
    println!(
        "| tol | threshold | estimate (rel) | chosen | true error vs tightest | vs limit | estimate / true | wall |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for (tol, r, seconds) in &runs {
        let estimate = r
            .estimated_error
            .as_ref()
            .and_then(|e| e.quantities["threshold_ratio"])
            .unwrap_or(f64::NAN);
        let chosen = r
            .accuracy
            .as_ref()
            .map(|a| {
                format!(
                    "p {}, {} x {}",
                    a.chosen.order.unwrap_or(0),
                    a.chosen.grid[0],
                    a.chosen.grid[1]
                )
            })
            .unwrap_or_default();
        let truth = (r.threshold_ratio - tightest.threshold_ratio).abs();
        let to_limit = limit.map_or(f64::NAN, |l| (r.threshold_ratio - l).abs());
        println!(
            "| {tol:.0e} | {:.8} | {:.1e} | {chosen} | {truth:.2e} | {to_limit:.2e} | {:.1} / {:.1} | {seconds:.2} s |",
            r.threshold_ratio,
            estimate / r.threshold_ratio,
            estimate / truth,
            estimate / to_limit,
        );
    }
    Ok(())
}
