//! The contact quantities of the default scene at accuracy targets (issue 28's tolerance
//! table): for each tolerance, `capstan contact --tol TOL` through the library, and for every
//! reported quantity its value, its relative estimate, its true relative error against a
//! reference run and the ratio estimate / true error; then the wall time of each tolerance.
//!
//! # Problem
//! The paper's body on the circle (`Scene::default()`, ratio 2, `eps` regularised Coulomb).
//! Under `accuracy.tol` the ladder of `src/problem/target.rs` (Qp `p = 2 ... 6` graded toward
//! the corners, then the order-6 mesh with 2, 4, 8, ... times the elements along `x2`) refines
//! until every quantity's estimate `e_k = max(|Q_k - Q_{k-1}|, |Q_{k-1} - Q_{k-2}| / 4)` is
//! below `tol` relative (the face's measure `pi` for slip measure and stick-zone ends).
//!
//! # Reference
//! The ladder step `--reference-step K` (default: one step past the last step of the
//! tightest run), solved once with no budget: its relative difference to each run is the
//! "true error" column. A tolerance the budget cannot reach prints the typed error (which
//! quantity missed, its differences and whether they fall) in place of its row.
//!
//! Run: `cargo run --release --example contact_accuracy -- [TOL ...] [--reference-step K]`
//! (default `1e-3 1e-4 1e-5`). Look at: every true error below its tolerance and every
//! `estimate / true` between 0.5 and 10 (docs/verification.md, "Accuracy targets").

use std::collections::BTreeMap;
use std::time::Instant;

use capstan::commands::accuracy::{contact_to, probes, scaled};
use capstan::problem::Scaled;
use capstan::scene::Scene;
use capstan_elasticity::solvers::SilentObserver;

/// One tolerance's run: the chosen step, its quantities and estimates, the wall time.
struct Run {
    tol: f64,
    chosen: String,
    step: usize,
    values: BTreeMap<String, Scaled>,
    estimates: BTreeMap<String, Option<f64>>,
    seconds: f64,
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut reference_step: Option<usize> = None;
    let mut tolerances: Vec<f64> = Vec::new();
    let mut i = 0;
    while i < args.len() {
        if args[i] == "--reference-step" {
            reference_step = args.get(i + 1).and_then(|k| k.parse().ok());
            i += 2;
        } else {
            tolerances.extend(args[i].parse::<f64>().ok());
            i += 1;
        }
    }
    if tolerances.is_empty() {
        tolerances = vec![1e-3, 1e-4, 1e-5];
    }
    let mut runs: Vec<Run> = Vec::new();
    let mut failed: Vec<(f64, String, f64)> = Vec::new();
    for &tol in &tolerances {
        let mut scene = Scene::default();
        scene.accuracy.tol = Some(tol);
        let target = scene.accuracy.target()?.expect("accuracy.tol is set");
        let t = Instant::now();
        match contact_to(&scene, &target, &mut SilentObserver) {
            Ok((solved, _problem, estimate, report)) => {
                let probes = probes(&scene);
                let q = solved.quantities(&probes)?;
                let c = &report.chosen;
                runs.push(Run {
                    tol,
                    chosen: format!("p {}, {} x {}", c.order.unwrap_or(0), c.grid[0], c.grid[1]),
                    step: report.steps.len() - 1,
                    values: scaled(&q, &solved.solution),
                    estimates: estimate.quantities,
                    seconds: t.elapsed().as_secs_f64(),
                });
            }
            Err(e) => failed.push((tol, e.to_string(), t.elapsed().as_secs_f64())),
        }
    }
    let Some(last) = runs.iter().map(|r| r.step).max() else {
        for (tol, e, s) in &failed {
            println!("tol {tol:.0e}: {e} ({s:.1} s)");
        }
        return Ok(());
    };
    let k = reference_step.unwrap_or(last + 1);
    let scene = Scene::default();
    let t = Instant::now();
    let reference = scene.build()?.accuracy_step(k)?;
    let solved = reference.solve()?;
    let rq = solved.quantities(&probes(&scene))?;
    let truth = scaled(&rq, &solved.solution);
    println!(
        "reference: ladder step {k}, grid {:?}, {} unknowns ({:.1} s)",
        reference.grid(),
        reference.unknowns(),
        t.elapsed().as_secs_f64()
    );
    println!(
        "| tol | chosen (step) | wall | quantity | value | estimate (rel) | true error (rel) | estimate / true | true < tol | 0.5 <= ratio <= 10 |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for r in &runs {
        for (name, q) in &r.values {
            let est = r
                .estimates
                .get(name)
                .copied()
                .flatten()
                .map(|e| e / q.scale);
            let err = truth.get(name).map(|t| (q.value - t.value).abs() / q.scale);
            let (est_s, ratio) = match (est, err) {
                (Some(e), Some(t)) => (format!("{e:.1e}"), e / t),
                (Some(e), None) => (format!("{e:.1e}"), f64::NAN),
                _ => ("-".to_owned(), f64::NAN),
            };
            let err = err.unwrap_or(f64::NAN);
            println!(
                "| {:.0e} | {} ({}) | {:.1} s | {name} | {:.9} | {est_s} | {err:.1e} | {ratio:.1} | {} | {} |",
                r.tol,
                r.chosen,
                r.step,
                r.seconds,
                q.value,
                if err < r.tol { "yes" } else { "no" },
                if (0.5..=10.0).contains(&ratio) {
                    "yes"
                } else {
                    "no"
                },
            );
        }
    }
    for (tol, e, s) in &failed {
        println!("| {tol:.0e} | not reached ({s:.1} s): {e} |");
    }
    Ok(())
}
