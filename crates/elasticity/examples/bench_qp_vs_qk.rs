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

use std::time::Instant;

use capstan_elasticity::contact::ThickBody;
use capstan_elasticity::finite_element::DiscretisationMethod;
use capstan_elasticity::solvers::{DirectParams, LinearSolver, SparseLu};
use capstan_elasticity::{BoundaryConditions, Discretisation};

/// `[build, assemble, factor + solve]` seconds and the solution.
fn time(body: &ThickBody) -> ([f64; 3], Vec<f64>) {
    let t = Instant::now();
    let mut problem = body.problem(1.0, 1.5).expect("problem");
    problem.boundary = BoundaryConditions::paper_clamped(1.0, 1.5); // no rigid mode to pin
    let op = body
        .scheme()
        .expect("scheme")
        .build(problem)
        .expect("operator");
    let build = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let system = op.system().expect("system");
    let assemble = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let params = DirectParams {
        ordering: op.lu_ordering(),
        ..Default::default()
    };
    let mut lu = SparseLu::new(params).expect("lu");
    lu.analyse(&system.pattern).expect("analyse");
    lu.factor(&system.values).expect("factor");
    let mut v = system.rhs.clone();
    lu.solve_in_place(&mut v).expect("solve");
    ([build, assemble, t.elapsed().as_secs_f64()], v)
}

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("a whole number"))
        .collect();
    let arg = |i: usize, d: usize| args.get(i).copied().unwrap_or(d);
    let reps = arg(4, 5);
    for (name, order, n2, n3) in [
        ("q1", 1, arg(0, 250), arg(1, 41)),
        ("q2", 2, arg(2, 257), arg(3, 33)),
    ] {
        let mut qk = ThickBody::paper(n2, n3).expect("body");
        qk.method = if order == 1 {
            DiscretisationMethod::FemQ1
        } else {
            DiscretisationMethod::FemQ2
        };
        let qp = ThickBody {
            method: DiscretisationMethod::FemQp,
            order,
            ..qk.clone()
        };
        let (mut best_k, mut best_p) = ([f64::INFINITY; 3], [f64::INFINITY; 3]);
        let (mut vk, mut vp) = (vec![], vec![]);
        for _ in 0..reps {
            let (tk, v) = time(&qk);
            vk = v;
            let (tp, v) = time(&qp);
            vp = v;
            for i in 0..3 {
                best_k[i] = best_k[i].min(tk[i]);
                best_p[i] = best_p[i].min(tp[i]);
            }
        }
        let scale = vk.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let diff = vk
            .iter()
            .zip(&vp)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
            / scale;
        let (sk, sp): (f64, f64) = (best_k.iter().sum(), best_p.iter().sum());
        println!(
            "{{\"pair\": \"{name}\", \"grid\": [{n2}, {n3}], \"qk_seconds\": {best_k:?}, \"qp_seconds\": {best_p:?}, \"ratio_total\": {:.3}, \"ratio_assembly\": {:.3}, \"max_relative_difference\": {diff:.3e}}}",
            sp / sk,
            (best_p[0] + best_p[1]) / (best_k[0] + best_k[1]),
        );
    }
}
