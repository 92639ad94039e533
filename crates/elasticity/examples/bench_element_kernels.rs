//! Benchmark: the element kernels of the Qp family at low order, and the Q1/Q2 pipeline.
//!
//! Q1 and Q2 are orders 1 and 2 of `HighOrderNavier`; for `p <= 2` its element matrices come
//! from the direct quadrature loop (`add_element_matrix_direct`) instead of the sum
//! factorisation (`add_element_matrix`), which at these sizes spends more on bookkeeping
//! than it saves in products. Part 1 times both kernels on the same point matrices for
//! `p = 1, 2` (and the sum factorisation at `p = 3` for scale); part 2 times the stages of
//! `fem-q1` and `fem-q2` on the paper's body (circle `a = b = 2`, `h = 1`, `E = 1e3`,
//! `nu = 1/4`, clamped on `x3 = 0`, end tractions 1 and 1.5: the bulk solve of the contact
//! problem without its rigid mode) as the contact solvers run them: build (geometry caches),
//! first `system()` (pattern and values), second `system()` (values), LU factor and solve.
//!
//! ```text
//! RAYON_NUM_THREADS=1 cargo run --release -p capstan-elasticity --example bench_element_kernels -- 250 41 257 33 20
//! ```
//! Arguments: the Q1 grid `n2 n3`, the Q2 grid `n2 n3`, repetitions (default 250 41 257 33
//! 20). Times are CPU seconds of the process (`/proc/self/stat`) per repetition, each stage
//! run `reps` times in a row: the work done, whatever share of the cores the machine's load
//! leaves (run with one rayon thread to count no idle spinning). Prints one JSON line per
//! kernel order and per element.

mod common;

use capstan_elasticity::contact::ThickBody;
use capstan_elasticity::finite_element::high_order::{
    DIRECT_KERNEL_ORDERS, ElementTables, add_element_matrix, add_element_matrix_direct,
    gauss_legendre, gll_rule,
};
use capstan_elasticity::finite_element::{ElementOrder, HighOrderNavier, VolumetricIntegration};
use capstan_elasticity::solvers::{DirectParams, LinearSolver, SparseLu};
use capstan_elasticity::{BoundaryConditions, Discretisation};
use common::{ExampleArgs, cpu_seconds};

/// An element kernel: tables, point matrices, element matrix (added to).
type Kernel = fn(&ElementTables, &[[[f64; 6]; 6]], &mut [f64]);

/// CPU seconds per element of `kernel` over `elements` deterministic symmetric point
/// matrices on the tables of order `p`, and the element matrices' sum (so that nothing is
/// optimised away).
fn time_kernel(p: usize, elements: usize, kernel: Kernel) -> (f64, f64) {
    let (x, _) = gll_rule(p);
    let (g, _) = gauss_legendre(p + 1);
    let tables = ElementTables::new(&x, &g, [2.0, 2.0]);
    let nq2 = g.len() * g.len();
    let kq: Vec<[[f64; 6]; 6]> = (0..64 * nq2)
        .map(|q| {
            core::array::from_fn(|a| {
                core::array::from_fn(|b| {
                    let (i, j) = (a.min(b) as f64, a.max(b) as f64);
                    (1.0 + q as f64 * 0.1 + i * 0.7 + j * 0.3).sin()
                })
            })
        })
        .collect();
    let l = 2 * (p + 1) * (p + 1);
    let mut out = vec![0.0; l * l];
    let mut sum = 0.0;
    let t = cpu_seconds();
    for e in 0..elements {
        out.fill(0.0);
        let k = e % 64;
        kernel(&tables, &kq[k * nq2..(k + 1) * nq2], &mut out);
        sum += out[e % (l * l)];
    }
    ((cpu_seconds() - t) / elements as f64, sum)
}

/// CPU seconds per repetition of `[build, first system (pattern and values), second system
/// (values), factor + solve]`, each stage run `reps` times in a row (so the 10 ms ticks
/// divide by `reps`), and the max |v|.
fn time_pipeline(op: impl Fn() -> Box<dyn Discretisation>, reps: usize) -> ([f64; 4], f64) {
    let per = |t: f64| t / reps as f64;
    let t = cpu_seconds();
    let ops: Vec<_> = (0..reps).map(|_| op()).collect();
    let build = per(cpu_seconds() - t);
    let t = cpu_seconds();
    let systems: Vec<_> = ops.iter().map(|op| op.system().expect("system")).collect();
    let first = per(cpu_seconds() - t);
    let t = cpu_seconds();
    for op in &ops {
        let again = op.system().expect("system");
        assert_eq!(again.values, systems[0].values);
    }
    let second = per(cpu_seconds() - t);
    let system = &systems[0];
    let params = DirectParams {
        ordering: ops[0].lu_ordering(),
        ..Default::default()
    };
    let t = cpu_seconds();
    let mut v = vec![];
    for _ in 0..reps {
        let mut lu = SparseLu::new(params).expect("lu");
        lu.analyse(&system.pattern).expect("analyse");
        lu.factor(&system.values).expect("factor");
        v = system.rhs.clone();
        lu.solve_in_place(&mut v).expect("solve");
    }
    let max = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    ([build, first, second, per(cpu_seconds() - t)], max)
}

fn main() {
    let args = ExampleArgs::from_env();
    let arg = |i: usize, d: usize| args.positional(i, d);
    let reps = arg(4, 20).max(1);
    for (order, n2, n3) in [
        (ElementOrder::Q1, arg(0, 250), arg(1, 41)),
        (ElementOrder::Q2, arg(2, 257), arg(3, 33)),
    ] {
        let body = ThickBody::paper(n2, n3).expect("body");
        let mut problem = body.problem(1.0, 1.5).expect("problem");
        problem.boundary = BoundaryConditions::paper_clamped(1.0, 1.5); // no rigid mode to pin
        let full = VolumetricIntegration::Full;
        let op = || -> Box<dyn Discretisation> {
            Box::new(HighOrderNavier::with_element(problem.clone(), order, full).expect("operator"))
        };
        let ([build, first, refill, solve], max) = time_pipeline(op, reps);
        println!(
            "{{\"element\": \"{}\", \"grid\": [{n2}, {n3}], \"build_seconds\": {build:.4}, \"first_system_seconds\": {first:.4}, \"refill_seconds\": {refill:.4}, \"factor_solve_seconds\": {solve:.4}, \"max_abs_v\": {max:.6e}}}",
            order.method_name()
        );
    }
    for p in 1..=3 {
        let elements = 20_000 * reps;
        let (factorised, s1) = time_kernel(p, elements, add_element_matrix);
        let direct = (p <= DIRECT_KERNEL_ORDERS)
            .then(|| time_kernel(p, elements, add_element_matrix_direct));
        let (direct_seconds, ratio, difference) = match direct {
            Some((t, s2)) => (
                format!("{t:.3e}"),
                format!("{:.3}", factorised / t),
                format!("{:.1e}", (s1 - s2).abs() / s1.abs()),
            ),
            None => ("null".into(), "null".into(), "null".into()),
        };
        println!(
            "{{\"kernel_order\": {p}, \"elements\": {elements}, \"sum_factorised_seconds_per_element\": {factorised:.3e}, \"direct_seconds_per_element\": {direct_seconds}, \"ratio_factorised_over_direct\": {ratio}, \"relative_difference_of_sums\": {difference}}}"
        );
    }
}
