//! The paper's section 3 body (circle a = b = 2, h = 1, E = 1e3, nu = 1/4, mu = 1/2,
//! eps = 1e-5, tau0 = 1) at one tension ratio: displacement extremes, stick and slip intervals.
//!
//! Run: `cargo run --release --example contact_paper -- [N2 N3 [TAU_MAX]]` (default 250 41 1).
//! Look at: max v^2 (paper: +-1.72e-3 rad), max v^3 (paper: -8.24e-4 m), stick interval
//! (paper: (-0.0201, 0.0201)) and the slip intervals (paper: beyond +-0.0694).

use capstan_elasticity::contact::{BoundarySolver, ContactSettings, EndLoads, ThickBody};
use capstan_elasticity::friction::{RegularisedCoulomb, RegularisedCoulombParams};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let (n2, n3) = match args.as_slice() {
        [a, b, ..] => (*a as usize, *b as usize),
        _ => (250, 41),
    };
    let tau_max = args.get(2).copied().unwrap_or(1.0);
    let eps = 1e-5;
    let body = ThickBody::paper(n2, n3)?;
    let t = std::time::Instant::now();
    let model = body.model(
        RegularisedCoulomb,
        RegularisedCoulombParams::new(0.5, eps)?,
        eps,
    )?;
    let solver = BoundarySolver::new(&model, ContactSettings::default())?;
    let setup = t.elapsed();
    let sol = solver.solve(EndLoads::new(1.0, tau_max))?;
    println!(
        "grid {n2} x {n3}, tau_max = {tau_max}: setup {setup:?}, total {:?}",
        t.elapsed()
    );
    println!("sliding mode: {:?}", solver.sliding());
    println!(
        "newton {} (continuation steps {}), residual {:.2e}",
        sol.stats.newton_iterations, sol.stats.continuation_steps, sol.stats.residual
    );
    println!("max v2 {:?}", sol.max_azimuthal_displacement);
    println!("max v3 {:?}", sol.max_radial_displacement);
    println!("slip fraction {:.4}", sol.slip_fraction);
    for i in &sol.intervals {
        println!(
            "  state {:+} from {:.5} to {:.5} (nodes {:.5}..{:.5}, {} nodes)",
            i.state, i.from, i.to, i.nodes[0], i.nodes[1], i.count
        );
    }
    println!("tensile contact nodes {}", sol.tensile_contact_nodes);
    Ok(())
}
