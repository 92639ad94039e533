//! The Qp operator on geometrically graded meshes ([`super::Grading`]): order `p + 1` on a
//! smooth manufactured solution, exponential convergence on the paper problem's corner
//! singularities, and the self-convergence of its graded references.

use capstan_solvers::SparseCholesky;

use super::{Grading, HighOrderNavier, QpSettings};
use crate::discretisation::Discretisation;
use crate::finite_element::{SampleChart, mms_parts, paper_parts};
use crate::samples::{ManufacturedField, MmsBoundaries, PaperEllipse, PrismMms};
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

/// Least-squares slope of `ln(error)` against `x`.
fn log_slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let mx = points.iter().map(|e| e.0).sum::<f64>() / n;
    let my = points.iter().map(|e| e.1.ln()).sum::<f64>() / n;
    let sxy: f64 = points.iter().map(|e| (e.0 - mx) * (e.1.ln() - my)).sum();
    let sxx: f64 = points.iter().map(|e| (e.0 - mx).powi(2)).sum();
    sxy / sxx
}

#[test]
fn graded_mesh_keeps_order_p_plus_1_on_the_manufactured_solution() {
    // the 4 x 4 geometric mesh (sigma = 0.3, two layers at each end of x2 and of x3, no middle
    // element) with every element split into s x s: h-refinement of a graded mesh; above the
    // forcing's round-off floor (~1e-12, a Richardson difference)
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

/// The paper problem (`PaperEllipse`) with `2n x 2n` elements of order `p`, graded with
/// `sigma = 0.15` (`n` layers at each end of `x2` and `x3`), and its solution.
fn paper_graded(p: usize, n: usize) -> (HighOrderNavier<SampleChart>, Vec<f64>) {
    let level = GridLevel {
        n2: 2 * n * p + 1,
        n3: 2 * n * p + 1,
    };
    let op = paper_parts(&PaperEllipse::default(), level)
        .unwrap()
        .high_order_with(settings(p, 0.15, n, 1))
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
fn graded_paper_problem_converges_exponentially_in_p_and_layers() {
    // p = n = 2 ... 5 against p = n = 8 (whose own distance to p = n = 7 bounds its error)
    let reference = paper_graded(8, 8);
    let errors: Vec<(f64, f64)> = (2..=5)
        .map(|k| (k as f64, distance(&paper_graded(k, k), &reference)))
        .collect();
    let rate = -log_slope(&errors);
    let check = distance(&paper_graded(7, 7), &reference);
    println!("graded paper: rate {rate:.3}, {errors:?}, p = n = 7: {check:e}");
    assert!(
        errors.windows(2).all(|w| w[1].1 < 0.4 * w[0].1),
        "{errors:?}"
    );
    assert!(rate > 1.2, "rate {rate}: {errors:?}");
    assert!(check < 0.1 * errors[3].1, "{check:e}: {errors:?}");
}

#[test]
fn uniform_paper_problem_converges_algebraically_only() {
    // the same p = 4, the same elements (8 x 8): uniform is far behind graded at the corners
    let reference = paper_graded(8, 8);
    let graded = distance(&paper_graded(4, 4), &reference);
    let level = GridLevel { n2: 33, n3: 33 };
    let op = paper_parts(&PaperEllipse::default(), level)
        .unwrap()
        .high_order_with(QpSettings::order(4))
        .unwrap();
    let v = op.solve(&mut SparseCholesky::default()).unwrap();
    let uniform = distance(&(op, v), &reference);
    println!("paper p = 4, 8 x 8 elements: graded {graded:e}, uniform {uniform:e}");
    assert!(
        graded < 0.1 * uniform,
        "graded {graded:e}, uniform {uniform:e}"
    );
}

#[test]
#[ignore]
fn explore() {
    let run = |p: usize, n: usize, m: [usize; 2]| {
        let level = GridLevel {
            n2: (2 * n + m[0]) * p + 1,
            n3: (2 * n + m[1]) * p + 1,
        };
        let op = paper_parts(&PaperEllipse::default(), level)
            .unwrap()
            .high_order_with(settings(p, 0.15, n, 1))
            .unwrap();
        let v = op.solve(&mut SparseCholesky::default()).unwrap();
        (op, v)
    };
    let reference = run(10, 7, [4, 1]);
    println!("ref dofs {}", reference.0.dof_count());
    for m in [[0, 0], [2, 0], [4, 0], [4, 1], [6, 1]] {
        for k in 2..=8 {
            let r = run(k, k, m);
            println!(
                "m {m:?} p = n = {k}: dofs {} dist {:e}",
                r.0.dof_count(),
                distance(&r, &reference)
            );
        }
    }
}
