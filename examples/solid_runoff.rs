//! The 3-D run-off ratio of the default cone (`obstacle.shape = "cone"`, `ubar = 0.5 sin t`,
//! width 1, `h = 1`, `mu = 0.5`, Q1) under unilateral or bilateral contact, by continuation in
//! the tension ratio on the full-system Newton ([`FullSystemSolver::run_off`], the loop
//! `capstan contact` and `capstan threshold` run too): from ratio 1 up, each ratio reached
//! from the last converged one by pseudo-arclength continuation in `(v, r)`
//! ([`FullSystemSolver::continue_ratio`]), the ratio step 0.05 halved on a failure until it is
//! below `1e-3`, the stop bracketed by the last converged ratio and the first failed one. When the
//! equilibrium path folds back (a limit point `r*`: no equilibrium beyond it on the path) it
//! prints "no equilibrium beyond r* in [lower, upper]" and exits with status 3. Prints per
//! converged ratio the Slip measure, `max |v|` on the contact face and the separated sites.
//!
//! Run: `cargo run --release --example solid_runoff -- N1 N2 N3 [unilateral|bilateral] [EPS]
//! [MIN_STEP]` (default 3 20 3 unilateral 1e-5 1e-3; `EPS` is `friction.eps`, `MIN_STEP` the
//! smallest ratio step, [`RunOffSettings::min_step`]). Look at: the fold ratio `r*`
//! (3 x 20 x 3 unilateral: in [1.439063, 1.440625]), and `max |v|` growing towards it.

use capstan::Scene;
use capstan_elasticity::contact::{
    ContactError, ContactSolution, FullSystemSolver, RunOffEnd, RunOffSettings, RunOffTrial,
};
use capstan_elasticity::solvers::SilentObserver;

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
    println!("| ratio | Newton iterations | Slip | max |v| on the face | separated sites |");
    println!("|---|---|---|---|---|");
    let report = |r: f64, s: &ContactSolution| {
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
    // the budget of the example: as many arclength steps as it takes (the CLI's is
    // `solver.max_continuation_steps`)
    let settings = RunOffSettings {
        max_arclength_steps: usize::MAX,
        min_step: n(5, "1e-3").parse()?,
        ..Default::default()
    };
    let mut trace = |(trial, result): RunOffTrial<'_>| match result {
        Ok(s) => report(trial, s),
        Err(ContactError::NoEquilibrium { upper, .. }) => {
            eprintln!("ratio {trial:.6}: the equilibrium path folds back at {upper:.6}");
        }
        Err(e) => eprintln!("ratio {trial:.6}: {e}"),
    };
    let run = solver.run_off(tau0, 1.0, 10.0, settings, &mut SilentObserver, &mut trace)?;
    eprintln!(
        "{} ratio steps, {} arclength steps",
        run.ratio_steps, run.arclength_steps
    );
    match run.end {
        RunOffEnd::Folded { fold, beyond } => {
            println!(
                "no equilibrium beyond r* in [{:.6}, {beyond:.6}] ({kind}: the equilibrium path \
                 folds back there; largest ratio reached on the path {fold:.6})",
                run.reached
            );
            std::process::exit(3);
        }
        RunOffEnd::Stalled { beyond, .. } => {
            println!(
                "run-off bracket ({kind}): [{:.6}, {beyond:.6}]",
                run.reached
            );
        }
        RunOffEnd::Reached => println!("reached ratio {:.6} ({kind})", run.reached),
    }
    Ok(())
}
