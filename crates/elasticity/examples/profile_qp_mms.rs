//! Stage profile of one `fem-qpP` run of `capstan bench work-precision`'s `mms` problem (the
//! manufactured solution on the ellipse `b/a = 2`, traction-contact boundary set, grid
//! `(2m + 1) x (m + 1)` with `m = k p`: `2k x k` elements of order `p`), as the bench times it:
//! build (geometry and manufactured loads at the quadrature points), condensation (element
//! matrices, interior Cholesky, Schur complements, skeleton assembly), skeleton solve (sparse
//! Cholesky: analyse, factor, solve) with the interior recovery, and, not timed by the bench,
//! the error norm.
//!
//! ```text
//! GLIBC_TUNABLES=glibc.malloc.mmap_threshold=33554432:glibc.malloc.trim_threshold=536870912 \
//!   cargo run --release -p capstan-elasticity --example profile_qp_mms -- 9 1 [--reps 200] [--threads 1]
//! ```
//! (the allocator setting is the one the `capstan` binary makes at start; without it every
//! repetition faults in fresh pages.)
//! Arguments: the order `p` and the elements through the thickness `k` (default 9 1), `--reps`
//! repetitions (default 200), in a rayon pool of `--threads` (default 1) as the bench runs. Prints the fastest of the repetitions per stage and their total
//! (wall clock, ms) with the unknowns and the relative L2 error, as one JSON line; run under
//! `perf record` or `valgrind --tool=callgrind` for the split below the stages.

mod common;

use std::time::Instant;

use capstan_elasticity::finite_element::VolumetricIntegration;
use capstan_elasticity::samples::{ManufacturedField, MmsBoundaries, PrismMms, TrigonometricField};
use capstan_elasticity::solvers::SparseCholesky;
use capstan_elasticity::studies::mms_parts;
use capstan_elasticity::verification::GridLevel;
use capstan_elasticity::{Discretisation, ElasticityError};
use common::ExampleArgs;

fn main() -> Result<(), ElasticityError> {
    let args = ExampleArgs::from_env();
    let threads: usize = args
        .option("--threads")
        .and_then(|s| s.parse().ok())
        .unwrap_or(1);
    // as the bench runs a series: inside a rayon pool of that size (no cross-thread hand-off)
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a rayon pool");
    pool.install(|| profile(&args))
}

fn profile(args: &ExampleArgs) -> Result<(), ElasticityError> {
    let p: usize = args.positional(0, 9);
    let k: usize = args.positional(1, 1);
    let reps: usize = args
        .option("--reps")
        .and_then(|s| s.parse().ok())
        .unwrap_or(200);
    // `--elements E2 E3`: any element split (the bench's is `2k x k`)
    let e2: usize = args
        .option("--e2")
        .and_then(|s| s.parse().ok())
        .unwrap_or(2 * k);
    let e3: usize = args
        .option("--e3")
        .and_then(|s| s.parse().ok())
        .unwrap_or(k);
    let level = GridLevel {
        n2: e2 * p + 1,
        n3: e3 * p + 1,
    };
    let mms = PrismMms::ellipse(2.0, MmsBoundaries::TractionContact);
    // stages: build, condense, solve + recover, error (not timed by the bench)
    let mut best = [f64::INFINITY; 5];
    let (mut dofs, mut error) = (0, 0.0);
    for _ in 0..reps {
        let start = Instant::now();
        let (parts, _) = mms_parts(&mms, level)?;
        let op = parts.high_order(p, VolumetricIntegration::Full)?;
        let build = start.elapsed().as_secs_f64();
        let t = Instant::now();
        let condensed = op.condensed_system()?;
        let condense = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let u = condensed.system.solve(&mut SparseCholesky::default())?;
        let v = op.recover(&condensed, &u)?;
        let solve = t.elapsed().as_secs_f64();
        let total = start.elapsed().as_secs_f64();
        let t = Instant::now();
        let e = op.displacement_errors(&v, &|x| TrigonometricField.displacement(x).value)?;
        let norm = t.elapsed().as_secs_f64();
        for (b, x) in best.iter_mut().zip([build, condense, solve, total, norm]) {
            *b = b.min(x);
        }
        dofs = op.dof_count();
        error = e.l2 / e.l2_exact;
    }
    let ms = best.map(|s| s * 1e3);
    println!(
        "{{\"p\": {p}, \"elements\": [{e2}, {e3}], \"dofs\": {dofs}, \"build_ms\": {:.4}, \"condense_ms\": {:.4}, \"solve_ms\": {:.4}, \"total_ms\": {:.4}, \"error_norm_ms\": {:.4}, \"error\": {error:.6e}}}",
        ms[0], ms[1], ms[2], ms[3], ms[4]
    );
    Ok(())
}
