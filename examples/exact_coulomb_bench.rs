//! Exact Coulomb against regularised Coulomb on the default scene (`capstan contact`: the
//! paper's body, FD 250 x 41, ratio 2): Newton iterations and wall times of the default run
//! (`friction.eps` = 1e-5), `eps = 1e-5` named, `eps = 1e-6`, exact Coulomb (regularised start
//! and semismooth Newton on the condensed contact face, what `auto` runs) and exact Coulomb on
//! the full-system semismooth Newton (`solver.nonlinear = "full-newton"`, the route before),
//! in interleaved rounds; the best wall time of each over the rounds.
//!
//! Run: `cargo run --release --example exact_coulomb_bench -- [ROUNDS]` (default 5). Look at:
//! the ratios of the best times (the machine is shared: give `uptime` with them).

use std::time::Instant;

use capstan::Scene;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let rounds: usize = std::env::args()
        .nth(1)
        .and_then(|x| x.parse().ok())
        .unwrap_or(5);
    let runs: [(&str, &[(&str, &str)]); 5] = [
        ("default (eps = 1e-5)", &[]),
        ("eps = 1e-5 named", &[("friction.eps", "1e-5")]),
        ("eps = 1e-6", &[("friction.eps", "1e-6")]),
        (
            "exact, condensed face",
            &[("friction.law", "\"exact-coulomb\"")],
        ),
        (
            "exact, full system",
            &[
                ("friction.law", "\"exact-coulomb\""),
                ("solver.nonlinear", "\"full-newton\""),
            ],
        ),
    ];
    let mut best = vec![(f64::INFINITY, [0.0; 2]); runs.len()];
    let mut answers = vec![(0usize, String::new(), 0.0, 0.0); runs.len()];
    for round in 0..rounds {
        for (i, (_, sets)) in runs.iter().enumerate() {
            let mut scene = Scene::default();
            for (key, value) in *sets {
                scene = scene.with_raw(key, value, "bench")?;
            }
            let t = Instant::now();
            let solved = scene.build()?.solve()?;
            let wall = t.elapsed().as_secs_f64();
            if wall < best[i].0 {
                best[i] = (wall, solved.times);
            }
            let s = &solved.solution;
            answers[i] = (
                s.stats.newton_iterations,
                s.stats.method.to_owned(),
                s.slip_fraction,
                s.max_azimuthal_displacement.value,
            );
        }
        eprintln!("round {} of {rounds} done", round + 1);
    }
    println!(
        "| run | method | Newton iterations | best wall (s) | set-up + solve (s) | / default | Slip | max v2 |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for (i, (name, _)) in runs.iter().enumerate() {
        let (wall, [setup, solve]) = best[i];
        let (it, method, slip, v2) = &answers[i];
        println!(
            "| {name} | {method} | {it} | {wall:.3} | {setup:.3} + {solve:.3} | {:.2} | {slip:.4} | {v2:.6e} |",
            wall / best[0].0
        );
    }
    Ok(())
}
