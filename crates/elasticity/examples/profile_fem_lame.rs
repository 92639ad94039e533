//! Stage profile of one Lamé-cylinder finite-element solve with the sparse Cholesky, as timed by
//! `capstan bench work-precision` (grid `4m x (m + 1)`, full wrap, exact solution).
//!
//! ```text
//! cargo run --release -p capstan-elasticity --example profile_fem_lame -- 64 [--q1] [--reps 10]
//!     [--ordering amd|nd|end] [--seq]
//! ```
//! Prints, per stage, the fastest of `--reps` repetitions (wall clock, ms): setup (the
//! discretisation: geometry at the quadrature points, loads, pattern), assembly (`system()`),
//! analyse (ordering + symbolic factor), factor, solve (with the residual check), total; and the
//! stored values of `L`. `--seq` makes faer sequential (`Par::Seq`; the element loops keep
//! rayon's pool, `RAYON_NUM_THREADS=1` for a sequential process); `--ordering` picks the
//! Cholesky ordering: `amd` (the default: AMD on the node quotient graph), `nd` (nested
//! dissection with separators `degree` lines wide), `end` (nested dissection along element
//! boundaries, 1-line separators).

mod common;

use std::time::Instant;

use capstan_elasticity::finite_element::ElementOrder;
use capstan_elasticity::samples::{LameCylinder, ManufacturedField};
use capstan_elasticity::solvers::{
    ColumnOrdering, DirectParams, GridShape, LinearSolver, SparseCholesky,
};
use capstan_elasticity::studies::lame_parts;
use capstan_elasticity::verification::GridLevel;
use capstan_elasticity::{Discretisation, ElasticityError};
use common::ExampleArgs;

fn main() -> Result<(), ElasticityError> {
    let args = ExampleArgs::from_env();
    let m: usize = args.positional(0, 64);
    let order = if args.flag("--q1") {
        ElementOrder::Q1
    } else {
        ElementOrder::Q2
    };
    let reps: usize = args
        .option("--reps")
        .and_then(|s| s.parse().ok())
        .unwrap_or(10);
    let ordering = args.option("--ordering").unwrap_or("amd");
    if args.flag("--seq") {
        faer::set_global_parallelism(faer::Par::Seq);
    }
    let level = GridLevel {
        n2: 4 * m,
        n3: m + 1,
    };
    let lame = LameCylinder::default();
    let field = lame.field();
    let exact = move |x: [f64; 2]| field.displacement(x).value;
    let mut best = [f64::INFINITY; 6];
    let mut l_values = 0;
    let mut error = 0.0;
    for _ in 0..reps {
        let parts = lame_parts(&lame, level)?;
        let grid = GridShape {
            n2: parts.grid.n2(),
            n3: parts.grid.n3(),
            dofs_per_node: 2,
            periodic: parts.grid.is_periodic(),
        };
        let params = DirectParams {
            ordering: match ordering {
                "nd" => ColumnOrdering::NestedDissection {
                    grid,
                    separator_width: order.degree(),
                },
                "end" => ColumnOrdering::ElementNestedDissection {
                    grid,
                    degree: order.degree(),
                },
                _ => ColumnOrdering::Auto,
            },
            ..Default::default()
        };
        let mut chol = SparseCholesky::new(params)?;
        let start = Instant::now();
        let op = parts.finite_element(order)?;
        let t_setup = start.elapsed().as_secs_f64();
        let t = Instant::now();
        let system = op.system()?;
        let t_assemble = t.elapsed().as_secs_f64();
        let t = Instant::now();
        chol.analyse(&system.pattern)?;
        let t_analyse = t.elapsed().as_secs_f64();
        let t = Instant::now();
        chol.factor(&system.values)?;
        let t_factor = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let mut v = system.rhs.clone();
        chol.solve_in_place(&mut v)?;
        let t_solve = t.elapsed().as_secs_f64();
        let total = start.elapsed().as_secs_f64();
        for (b, x) in best
            .iter_mut()
            .zip([t_setup, t_assemble, t_analyse, t_factor, t_solve, total])
        {
            *b = b.min(x);
        }
        l_values = chol.factor_values();
        let e = op.displacement_errors(&v, &exact)?;
        error = e.l2 / e.l2_exact;
    }
    let ms = best.map(|x| x * 1e3);
    println!(
        "{{\"m\":{m},\"order\":\"{}\",\"dofs\":{},\"ordering\":\"{ordering}\",\"seq\":{},\"setup_ms\":{:.2},\"assemble_ms\":{:.2},\"analyse_ms\":{:.2},\"factor_ms\":{:.2},\"solve_ms\":{:.2},\"total_ms\":{:.2},\"l_values\":{l_values},\"error\":{error:.3e}}}",
        order.method_name(),
        2 * level.n2 * level.n3,
        args.flag("--seq"),
        ms[0],
        ms[1],
        ms[2],
        ms[3],
        ms[4],
        ms[5]
    );
    Ok(())
}
