//! Benchmark: Q1/Q2 elements (`fem-q1`, `fem-q2`) against the Qp family at `p = 1, 2`
//! (`fem-qp`, GLL nodes, which at `p = 1, 2` are the same nodes), on the paper's body (circle
//! `a = b = 2`, `h = 1`, `E = 1e3`, `nu = 1/4`), clamped on `x3 = 0`, end tractions 1 and
//! 1.5 (`BoundaryConditions::paper_clamped`: the bulk solve of the contact problem without
//! its rigid mode).
//!
//! ```text
//! cargo run --release -p capstan-elasticity --example bench_qp_vs_qk -- 250 41 257 33 5
//! ```
//! Arguments: the Q1 grid `n2 n3`, the Q2 grid `n2 n3`, repetitions (default 250 41 257 33 5).
//! For each pair, the minimum over the repetitions of: building the operator (geometry
//! caches), assembling the system (`Discretisation::system`), and one sparse LU factorisation
//! and solve with the operator's ordering, as the contact solvers do; then the ratio Qp / Qk.
//! Prints one JSON line per pair, with the max relative difference of the two solutions.

use capstan_elasticity::contact::ThickBody;
use capstan_elasticity::finite_element::{
    ElementOrder, FiniteElementNavier, HighOrderNavier, VolumetricIntegration,
};
use capstan_elasticity::solvers::{DirectParams, LinearSolver, SparseLu};
use capstan_elasticity::{BoundaryConditions, Discretisation};

/// User + system CPU seconds of this process (`/proc/self/stat`, 100 ticks a second): the
/// work done, whatever share of the cores the machine's load leaves this process.
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let after = stat.rsplit_once(')').map_or("", |(_, rest)| rest);
    let fields: Vec<&str> = after.split_whitespace().collect();
    let tick = |i: usize| {
        fields
            .get(i)
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(0.0)
    };
    (tick(11) + tick(12)) / 100.0
}

/// CPU seconds per repetition of `[build, first system (pattern and values), second system
/// (values), factor + solve]`, each stage run `reps` times in a row (so the 10 ms ticks
/// divide by `reps`), and the solution.
fn time(op: impl Fn() -> Box<dyn Discretisation>, reps: usize) -> ([f64; 4], Vec<f64>) {
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
    ([build, first, second, per(cpu_seconds() - t)], v)
}

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("a whole number"))
        .collect();
    let arg = |i: usize, d: usize| args.get(i).copied().unwrap_or(d);
    let reps = arg(4, 20);
    for (name, order, n2, n3) in [
        ("q1", 1, arg(0, 250), arg(1, 41)),
        ("q2", 2, arg(2, 257), arg(3, 33)),
    ] {
        let order = if order == 1 {
            ElementOrder::Q1
        } else {
            ElementOrder::Q2
        };
        let body = ThickBody::paper(n2, n3).expect("body");
        let mut problem = body.problem(1.0, 1.5).expect("problem");
        problem.boundary = BoundaryConditions::paper_clamped(1.0, 1.5); // no rigid mode to pin
        let full = VolumetricIntegration::Full;
        let qk = || -> Box<dyn Discretisation> {
            Box::new(
                FiniteElementNavier::with_volumetric(problem.clone(), order, full).expect("qk"),
            )
        };
        let qp = || -> Box<dyn Discretisation> {
            Box::new(
                HighOrderNavier::with_volumetric(problem.clone(), order.degree(), full)
                    .expect("qp"),
            )
        };
        let (best_k, vk) = time(qk, reps);
        let (best_p, vp) = time(qp, reps);
        let scale = vk.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let diff = vk
            .iter()
            .zip(&vp)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
            / scale;
        let sum = |t: &[f64; 4]| t[0] + t[1] + t[3];
        let (sk, sp) = (sum(&best_k), sum(&best_p));
        println!(
            "{{\"pair\": \"{name}\", \"grid\": [{n2}, {n3}], \"qk_seconds\": {best_k:?}, \"qp_seconds\": {best_p:?}, \"ratio_total\": {:.3}, \"ratio_assembly\": {:.3}, \"ratio_refill\": {:.3}, \"max_relative_difference\": {diff:.3e}}}",
            sp / sk,
            (best_p[0] + best_p[1]) / (best_k[0] + best_k[1]),
            best_p[2] / best_k[2],
        );
    }
}
