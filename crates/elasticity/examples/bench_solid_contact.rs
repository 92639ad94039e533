//! Benchmark of the 3-D contact problem: a body of finite width (free sides) on the elliptical
//! prism `a = 2`, `b = 1.5` (the paper's body otherwise: `h = 1`, `E = 1e3`, `nu = 1/4`,
//! `x2 in [-pi/2, pi/2]`, width 1), regularised Coulomb `mu = 0.5`, `eps = 1e-5`, tension
//! ratio 1.5, Q1 hexahedra.
//!
//! Run one size per process so the peak memory (VmHWM) belongs to that size:
//! ```text
//! cargo run --release -p capstan-elasticity --example bench_solid_contact -- 11 201 15 full
//! cargo run --release -p capstan-elasticity --example bench_solid_contact -- 5 41 5 condensed --sweep
//! ```
//! Prints one JSON line: grid, unknowns, contact unknowns, solver, seconds of the model
//! (assembly), the solver set-up, the solve (and a 26-point ratio sweep from 1.0 to 2.0 with
//! `--sweep`, warm-started), Newton iterations, relative residual, max `|v^2|`, VmHWM in MiB.

use std::time::Instant;

use capstan_elasticity::contact::{
    BoundarySolver, ContactSettings, EndLoads, FullSystemSettings, FullSystemSolver,
};
use capstan_elasticity::friction::{RegularisedCoulomb, RegularisedCoulombParams};
use capstan_elasticity::solid::SolidBody;
use capstan_elasticity::verification::peak_memory_mib;
use capstan_geometry::{EllipticalPrism, Obstacle};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let n = |i: usize, d: usize| args.get(i).and_then(|a| a.parse().ok()).unwrap_or(d);
    let nodes = [n(0, 5), n(1, 41), n(2, 5)];
    let solver = args.get(3).map_or("full", String::as_str);
    let sweep = args.iter().any(|a| a == "--sweep");
    let obstacle = Obstacle::Ellipse(EllipticalPrism::new(2.0, 1.5).expect("valid"));
    let body = SolidBody::new(obstacle, [-0.5, 0.5], nodes);
    let eps = 1e-5;
    let params = RegularisedCoulombParams::new(0.5, eps).expect("valid");
    let t = Instant::now();
    let model = body
        .model(RegularisedCoulomb, params, eps)
        .expect("a valid model");
    let model_seconds = t.elapsed().as_secs_f64();
    let ratios: Vec<f64> = if sweep {
        (0..26).map(|i| 1.0 + i as f64 / 25.0).collect()
    } else {
        vec![1.5]
    };
    let t = Instant::now();
    let (setup_seconds, results) = match solver {
        "condensed" => {
            let s = BoundarySolver::new(&model, ContactSettings::default()).expect("set-up");
            let setup = t.elapsed().as_secs_f64();
            let mut warm: Option<Vec<f64>> = None;
            let out: Vec<_> = ratios
                .iter()
                .map(|&r| {
                    let sol = s
                        .solve_from(EndLoads::ratio(r), warm.as_deref())
                        .expect("a solution");
                    warm = Some(sol.unknowns.clone());
                    sol
                })
                .collect();
            (setup, out)
        }
        _ => {
            let s = FullSystemSolver::new(&model, FullSystemSettings::default()).expect("set-up");
            let setup = t.elapsed().as_secs_f64();
            let out: Vec<_> = ratios
                .iter()
                .map(|&r| s.solve(EndLoads::ratio(r)).expect("a solution"))
                .collect();
            (setup, out)
        }
    };
    let total = t.elapsed().as_secs_f64();
    let last = results.last().expect("one solve at least");
    let iterations: usize = results.iter().map(|s| s.stats.newton_iterations).sum();
    println!(
        "{{\"nodes\":{nodes:?},\"unknowns\":{},\"contact_unknowns\":{},\"solver\":\"{solver}\",\"solves\":{},\"model_seconds\":{model_seconds:.3},\"setup_seconds\":{setup_seconds:.3},\"solve_seconds\":{:.3},\"newton_iterations\":{iterations},\"residual\":{:.2e},\"max_v2\":{:.6e},\"vm_hwm_mib\":{:.0}}}",
        model.dof_count(),
        model.active().len(),
        results.len(),
        total - setup_seconds,
        last.stats.residual,
        last.max_azimuthal_displacement.value,
        peak_memory_mib()
    );
}
