//! LU vs Cholesky vs Jacobi vs Gauss–Seidel on the 2-D Poisson problem (5-point stencil).
//!
//! Each measurement is one Newton-step's worth of linear work on an analysed pattern:
//! `factor` + `solve_in_place` (the symbolic analysis is done once, outside the loop).
//! Groups are `solvers/linear/lu_vs_jacobi/<n>` for an `n x n` grid.
//!
//! Run: `cargo bench -p capstan-solvers --bench linear`. After the criterion groups, a short
//! summary prints the time ratios of each backend to LU from a few extra timed runs.
//! `cargo test -p capstan-solvers --benches` runs every benchmark once, as a smoke test.

use std::hint::black_box;
use std::time::{Duration, Instant};

use capstan_solvers::samples::{LinearSystem, Poisson2d};
use capstan_solvers::{IterativeParams, LinearBackend, LinearSettings, LinearSolver};
use criterion::{Criterion, criterion_group};

/// The registered backends that need nothing from the caller (`multigrid` needs a hierarchy).
const STANDALONE: [LinearBackend; 4] = [
    LinearBackend::LU,
    LinearBackend::CHOLESKY,
    LinearBackend::JACOBI,
    LinearBackend::GAUSS_SEIDEL,
];

const SIZES: [usize; 2] = [32, 64];

/// Relative residual 1e-8 for the iterative backends; the cap is raised because Jacobi needs
/// about `2 ln(1e8) / (pi h)^2` sweeps (~16,000 at n = 64).
fn iterative() -> IterativeParams {
    IterativeParams {
        tolerance: 1e-8,
        max_iterations: 100_000,
        ..Default::default()
    }
}

fn prepared(system: &LinearSystem, backend: LinearBackend) -> Box<dyn LinearSolver<f64> + Send> {
    let mut solver = backend
        .build(
            &LinearSettings {
                iterative: iterative(),
                ..Default::default()
            },
            &(),
        )
        .expect("valid settings");
    solver.analyse(&system.pattern).expect("square pattern");
    solver
}

fn step(solver: &mut dyn LinearSolver<f64>, system: &LinearSystem, x: &mut [f64]) {
    solver.factor(&system.values).expect("nonsingular");
    x.copy_from_slice(&system.rhs);
    solver.solve_in_place(x).expect("converges");
}

fn linear(c: &mut Criterion) {
    for n in SIZES {
        let system = Poisson2d::new(n).system();
        let mut group = c.benchmark_group(format!("solvers/linear/lu_vs_jacobi/{n}"));
        group
            .sample_size(10)
            .warm_up_time(Duration::from_millis(500))
            .measurement_time(Duration::from_secs(3));
        for backend in STANDALONE {
            let mut solver = prepared(&system, backend);
            let mut x = vec![0.0; system.dimension()];
            group.bench_function(backend.name(), |b| {
                b.iter(|| {
                    step(solver.as_mut(), black_box(&system), &mut x);
                    black_box(&x);
                })
            });
        }
        group.finish();
    }
}

/// Median wall time of a few factor + solve steps.
fn median_step(system: &LinearSystem, backend: LinearBackend) -> Duration {
    let mut solver = prepared(system, backend);
    let mut x = vec![0.0; system.dimension()];
    let mut times: Vec<Duration> = (0..5)
        .map(|_| {
            let start = Instant::now();
            step(solver.as_mut(), system, &mut x);
            start.elapsed()
        })
        .collect();
    times.sort();
    times[2]
}

fn summary() {
    println!("\nsolvers/linear/lu_vs_jacobi: median factor+solve time, ratio to LU");
    for n in SIZES {
        let system = Poisson2d::new(n).system();
        let lu = median_step(&system, LinearBackend::LU);
        for backend in STANDALONE {
            let t = median_step(&system, backend);
            println!(
                "  n = {n:3} ({:5} unknowns) {:>13}: {:>10.3} ms  x{:.2}",
                n * n,
                backend.name(),
                t.as_secs_f64() * 1e3,
                t.as_secs_f64() / lu.as_secs_f64()
            );
        }
    }
}

criterion_group!(benches, linear);

fn main() {
    benches();
    Criterion::default().configure_from_args().final_summary();
    // only in a real benchmark run: `cargo test --benches` passes no `--bench`
    if std::env::args().any(|a| a == "--bench") {
        summary();
    }
}
