//! The Qp operator on geometrically graded meshes ([`super::Grading`]): order `p + 1` on a
//! smooth manufactured solution, exponential convergence on the paper problem's corner
//! singularities, and the self-convergence of its graded references.

use capstan_solvers::SparseCholesky;

use super::tests::assert_exponential;
use super::{Grading, HighOrderNavier, QpSettings};
use crate::discretisation::Discretisation;
use crate::samples::{ManufacturedField, MmsBoundaries, PaperEllipse, PrismMms};
use crate::studies::{SampleChart, mms_parts, paper_parts};
use crate::verification::{GridLevel, observed_order};

/// Order `p`, geometric grading `sigma` with `layers`, refined by `split`.
fn settings(p: usize, sigma: f64, layers: usize, split: usize) -> QpSettings {
    QpSettings {
        grading: Grading::geometric(sigma, layers)
            .unwrap()
            .refined(split)
            .unwrap(),
        ..QpSettings::order(p)
    }
}

#[test]
fn graded_mesh_keeps_order_p_plus_1_on_the_manufactured_solution() {
    // the 4 x 4 geometric mesh (sigma = 0.3, two layers at each end of x2 and of x3, no middle
    // element) with every element split into s x s: h-refinement of a graded mesh
    let mms = PrismMms::ellipse(0.5, MmsBoundaries::TractionContact);
    for (p, splits) in [(2, [2, 4, 8]), (3, [1, 2, 4])] {
        let study: Vec<(f64, f64)> = splits
            .iter()
            .map(|&s| {
                let e = 4 * s;
                let level = GridLevel {
                    n2: e * p + 1,
                    n3: e * p + 1,
                };
                let (parts, exact) = mms_parts(&mms, level).unwrap();
                let op = parts.high_order_with(settings(p, 0.3, 2, s)).unwrap();
                let b = op.element_breaks();
                // graded: the end elements are sigma / (1 - sigma) of their neighbours
                let ratio = (b[1][1] - b[1][0]) / (b[1][s + 1] - b[1][s]);
                assert!((ratio - 0.3 / 0.7).abs() < 1e-12, "{ratio}");
                let v = op.solve(&mut SparseCholesky::default()).unwrap();
                let err = op
                    .displacement_errors(&v, &|x| exact.field.displacement(x).value)
                    .unwrap();
                (1.0 / s as f64, err.l2 / err.l2_exact)
            })
            .collect();
        let order = observed_order(&study);
        println!("graded mms p {p}: order {order:.3}, {study:?}");
        assert!(
            (order - (p as f64 + 1.0)).abs() < 0.2,
            "p {p}: order {order}, {study:?}"
        );
        assert!(study[2].1 < [2e-5, 2e-6][p - 2], "p {p}: {study:?}");
    }
}

/// The grading of the paper problem's runs: `sigma = 0.4` (with a fixed order the layer
/// elements converge like `rho^-p`, `rho` growing with `sigma`: `0.15` stalls the runs near
/// `1e-6`, see docs/high-order.md).
const SIGMA: f64 = 0.4;

/// The paper problem (`PaperEllipse`) with order `p` and `n` geometric layers (ratio `SIGMA`)
/// at each end of `x2` and `x3`, around `6 x 1` middle elements, and its solution.
fn paper_graded(p: usize, n: usize) -> (HighOrderNavier<SampleChart>, Vec<f64>) {
    let level = GridLevel {
        n2: (2 * n + 6) * p + 1,
        n3: (2 * n + 1) * p + 1,
    };
    let op = paper_parts(&PaperEllipse::default(), level)
        .unwrap()
        .high_order_with(settings(p, SIGMA, n, 1))
        .unwrap();
    let v = op.solve(&mut SparseCholesky::default()).unwrap();
    (op, v)
}

/// Relative physical L2 distance of `(op, v)` to `(reference, vr)`, by Gauss quadrature over
/// `op`'s elements.
fn distance(
    (op, v): &(HighOrderNavier<SampleChart>, Vec<f64>),
    (reference, vr): &(HighOrderNavier<SampleChart>, Vec<f64>),
) -> f64 {
    let e = op
        .displacement_errors(v, &|x| reference.displacement_at(vr, x))
        .unwrap();
    e.l2 / e.l2_exact
}

#[test]
fn graded_paper_problem_converges_exponentially_in_p() {
    // 8 layers, p = 2 ... 6 against p = 8 on the same mesh (measured 2.5e-3 ... 6.3e-7, rate
    // 2.08 per order)
    let reference = paper_graded(8, 8);
    let errors: Vec<(f64, f64)> = (2..=6)
        .map(|p| (p as f64, distance(&paper_graded(p, 8), &reference)))
        .collect();
    let rate = assert_exponential(&errors, 0.3);
    println!("graded paper, 8 layers: rate {rate:.3}, {errors:?}");
}

#[test]
fn graded_paper_solutions_self_converge_with_p_and_layers() {
    // (p, n) = (3, 4), (4, 6), (5, 8), (6, 10): each step shrinks the change (measured
    // 3.2e-4, 3.5e-5, 4.3e-6): how the bench's reference (p = 10) shows its accuracy
    let runs: Vec<_> = [(3, 4), (4, 6), (5, 8), (6, 10)]
        .into_iter()
        .map(|(p, n)| paper_graded(p, n))
        .collect();
    let changes: Vec<f64> = runs.windows(2).map(|w| distance(&w[0], &w[1])).collect();
    println!("graded paper, successive changes: {changes:?}");
    assert!(changes.windows(2).all(|w| w[1] < 0.3 * w[0]), "{changes:?}");
    assert!(changes[2] < 1e-5, "{changes:?}");
}

#[test]
fn graded_mesh_beats_the_uniform_one_on_the_paper_problem() {
    // p = 4, the same 12 x 7 elements: graded (3 layers) against uniform
    let reference = paper_graded(8, 8);
    let graded = distance(&paper_graded(4, 3), &reference);
    let level = GridLevel { n2: 49, n3: 29 };
    let op = paper_parts(&PaperEllipse::default(), level)
        .unwrap()
        .high_order_with(QpSettings::order(4))
        .unwrap();
    let v = op.solve(&mut SparseCholesky::default()).unwrap();
    let uniform = distance(&(op, v), &reference);
    println!("paper p = 4, 12 x 7 elements: graded {graded:e}, uniform {uniform:e}");
    assert!(
        graded < 0.2 * uniform,
        "graded {graded:e}, uniform {uniform:e}"
    );
}
