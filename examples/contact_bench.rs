//! Benchmark of the contact solvers on the paper's body (circle a = b = 2, mu = 1/2, eps =
//! 1e-5, tau0 = 1, tau_max = 2): boundary-only (condensed) Newton against the full-system LU
//! Newton (refactorised every step) and the paper's Jacobi–Newton (damped Jacobi, relaxation
//! 1/2: undamped Jacobi diverges on this operator), and the 26-point slip-versus-ratio sweep
//! (ratios 1.0 .. 3.5) with one factorisation.
//!
//! Run: `cargo run --release --example contact_bench -- [N2 N3 [JACOBI_N2 JACOBI_N3]]`
//! (default 250 41, Jacobi–Newton on 40 9; `0 0` skips Jacobi–Newton). Look at: the time ratios and the peak memory.

use std::time::Instant;

use capstan_elasticity::contact::{
    BoundarySolver, ContactSettings, EndLoads, FullSystemSettings, FullSystemSolver, ThickBody,
};
use capstan_elasticity::friction::{RegularisedCoulomb, RegularisedCoulombParams};
use capstan_elasticity::solvers::NonlinearMethod;
use capstan_elasticity::verification::peak_memory_mib;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let a: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|x| x.parse().ok())
        .collect();
    let (n2, n3) = (
        a.first().copied().unwrap_or(250),
        a.get(1).copied().unwrap_or(41),
    );
    let (j2, j3) = (
        a.get(2).copied().unwrap_or(40),
        a.get(3).copied().unwrap_or(9),
    );
    let eps = 1e-5;
    let params = RegularisedCoulombParams::new(0.5, eps)?;
    let loads = EndLoads::ratio(2.0);

    let body = ThickBody::paper(n2, n3)?;
    let model = body.model(RegularisedCoulomb, params, eps)?;
    let t = Instant::now();
    let condensed = BoundarySolver::new(&model, ContactSettings::default())?;
    let setup = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let a = condensed.solve(loads)?;
    let solve = t.elapsed().as_secs_f64();
    println!(
        "grid {n2} x {n3}: condensed setup {setup:.3} s ({} bulk solves), solve {solve:.3} s, {} Newton iterations, Slip {:.4}",
        condensed.setup().bulk_solves,
        a.stats.newton_iterations,
        a.slip_fraction
    );
    let t = Instant::now();
    let full = FullSystemSolver::new(&model, FullSystemSettings::default())?;
    let b = full.solve(loads)?;
    let full_time = t.elapsed().as_secs_f64();
    let diff = a
        .displacement
        .iter()
        .zip(&b.displacement)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    println!(
        "full-system LU Newton: {full_time:.3} s, {} Newton iterations, {} factorisations; max |v_condensed - v_full| = {diff:.2e}; ratio full/condensed {:.1}",
        b.stats.newton_iterations,
        b.stats.factorisations,
        full_time / (setup + solve)
    );
    let t = Instant::now();
    let ratios: Vec<f64> = (0..26).map(|i| 1.0 + 0.1 * f64::from(i)).collect();
    let mut slips = Vec::new();
    let mut warm: Option<Vec<f64>> = None;
    for &r in &ratios {
        match condensed.solve_from(EndLoads::ratio(r), warm.as_deref()) {
            Ok(s) => {
                slips.push(format!("{r:.1}:{:.3}", s.slip_fraction));
                warm = Some(s.unknowns.clone());
            }
            Err(e) => slips.push(format!("{r:.1}:{}", e.status())),
        }
    }
    println!(
        "26-point sweep (one factorisation, warm starts): {:.3} s\n  {}",
        t.elapsed().as_secs_f64(),
        slips.join(" ")
    );
    println!("peak memory (VmHWM) so far: {:.1} MiB", peak_memory_mib());

    // Jacobi-Newton against LU Newton on a small grid (Jacobi needs ~n^2 sweeps); 0 0 skips it.
    if j2 == 0 || j3 == 0 {
        return Ok(());
    }
    let small = ThickBody::paper(j2, j3)?.model(RegularisedCoulomb, params, eps)?;
    let t = Instant::now();
    let lu = FullSystemSolver::new(&small, FullSystemSettings::default())?.solve(loads)?;
    let lu_time = t.elapsed().as_secs_f64();
    let mut settings = FullSystemSettings {
        method: NonlinearMethod::JacobiNewton,
        ..Default::default()
    };
    settings.newton.iterative.relaxation = 0.5;
    settings.newton.iterative.max_iterations = 50_000_000;
    settings.newton.iterative.tolerance = 1e-12;
    settings.continuation.tolerance = 1e-9;
    let t = Instant::now();
    let jn = FullSystemSolver::new(&small, settings)?.solve(loads)?;
    let jn_time = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let small_condensed = BoundarySolver::new(&small, ContactSettings::default())?.solve(loads)?;
    let c_time = t.elapsed().as_secs_f64();
    println!(
        "grid {j2} x {j3}: LU Newton {lu_time:.4} s ({} its), Jacobi-Newton {jn_time:.3} s ({} its, {} Jacobi sweeps), condensed {c_time:.4} s; Jacobi/LU = {:.0}, Jacobi/condensed = {:.0}; Slip {:.4} {:.4} {:.4}",
        lu.stats.newton_iterations,
        jn.stats.newton_iterations,
        jn.stats.linear_iterations,
        jn_time / lu_time,
        jn_time / c_time,
        lu.slip_fraction,
        jn.slip_fraction,
        small_condensed.slip_fraction
    );
    Ok(())
}
