//! The 3-D run-off ratio of the default cone (`obstacle.shape = "cone"`, `ubar = 0.5 sin t`,
//! width 1, `h = 1`, `mu = 0.5`, Q1) under unilateral or bilateral contact, by continuation in
//! the tension ratio on the full-system Newton: from ratio 1 up, each ratio reached from the
//! last converged one by pseudo-arclength continuation in `(v, r)`
//! ([`FullSystemSolver::continue_ratio`]), the ratio step halved on a failure until it is below
//! `1e-3`, the stop bracketed by the last converged ratio and the first failed one. When the
//! equilibrium path folds back (a limit point `r*`: no equilibrium beyond it on the path) it
//! prints "no equilibrium beyond r* in [lower, upper]" and exits with status 3. Prints per
//! converged ratio the Slip measure, `max |v|` on the contact face and the separated sites.
//!
//! Run: `cargo run --release --example solid_runoff -- N1 N2 N3 [unilateral|bilateral] [EPS]`
//! (default 3 20 3 unilateral 1e-5; `EPS` is `friction.eps`). Look at: the fold ratio `r*`
//! (3 x 20 x 3 unilateral: in [1.439063, 1.440625]), and `max |v|` growing towards it.

use capstan::Scene;
use capstan_elasticity::contact::{ContactError, EndLoads, FullSystemSolver};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let n = |i: usize, d: &str| args.get(i).cloned().unwrap_or_else(|| d.to_owned());
    let kind = n(3, "unilateral");
    let mut scene = Scene::default();
    for (key, value) in [
        ("body.dimension", "3".to_owned()),
        ("discretisation.method", "\"fem-q1\"".to_owned()),
        ("obstacle.shape", "\"cone\"".to_owned()),
        ("grid.n1", n(0, "3")),
        ("grid.n2", n(1, "20")),
        ("grid.n3", n(2, "3")),
        ("contact.kind", format!("\"{kind}\"")),
        ("solver.nonlinear", "\"full-newton\"".to_owned()),
        ("friction.eps", n(4, "1e-5")),
    ] {
        scene = scene.with_raw(key, &value, "runoff")?;
    }
    let problem = scene.build()?;
    let model = problem.model()?;
    let solver = FullSystemSolver::new(&model, problem.solver.full_settings())?;
    let tau0 = problem.loads.tau0;
    let (mut ratio, mut step) = (1.0, 0.05);
    let mut last = solver.solve(EndLoads::new(tau0, tau0 * ratio))?;
    let mut failed = f64::INFINITY;
    let mut fold = None;
    println!("| ratio | Newton iterations | Slip | max |v| on the face | separated sites |");
    println!("|---|---|---|---|---|");
    let report = |r: f64, s: &capstan_elasticity::contact::ContactSolution| {
        let p = &s.contact;
        let vmax =
            p.v2.iter()
                .zip(&p.v3)
                .map(|(a, b)| a.hypot(*b))
                .fold(0.0f64, f64::max);
        let separated = p
            .separated
            .as_ref()
            .map_or(0, |s| s.iter().filter(|&&x| x).count());
        println!(
            "| {r:.6} | {} | {:.4} | {vmax:.6e} | {separated} |",
            s.stats.newton_iterations, s.slip_fraction
        );
    };
    report(ratio, &last);
    while step >= 1e-3 && ratio < 10.0 {
        let trial = ratio + step;
        match solver.continue_ratio(tau0, ratio, &last.displacement, trial) {
            Ok(s) => {
                ratio = trial;
                if failed <= ratio {
                    // an earlier attempt from another start failed here: not the stop
                    failed = f64::INFINITY;
                }
                report(ratio, &s);
                last = s;
            }
            Err(ContactError::NoEquilibrium { upper, .. }) => {
                // the path folds back before `trial`: bracket the fold with a smaller step
                eprintln!("ratio {trial:.6}: the equilibrium path folds back at {upper:.6}");
                fold = Some(fold.map_or(upper, |f: f64| f.max(upper)));
                failed = failed.min(trial);
                step /= 2.0;
            }
            Err(e) => {
                failed = failed.min(trial);
                eprintln!("ratio {trial:.6}: {e}");
                step /= 2.0;
            }
        }
    }
    if let Some(upper) = fold {
        println!(
            "no equilibrium beyond r* in [{ratio:.6}, {failed:.6}] ({kind}: the equilibrium path \
             folds back there; largest ratio reached on the path {upper:.6})"
        );
        std::process::exit(3);
    }
    println!("run-off bracket ({kind}): [{ratio:.6}, {failed:.6}]");
    Ok(())
}
