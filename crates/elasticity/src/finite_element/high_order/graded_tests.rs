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

#[test]
fn contact_rows_integrate_the_one_sided_normal_stress_by_the_face_quadrature() {
    // A field with a kink at the element break between the first two layers at the x2 = 0
    // end (sizes sigma^3 H, sigma^2 H ... of ratio 0.15): v^2 = s_l (x2 - x_b) before the
    // break, s_r (x2 - x_b) after it, v^3 = 0, in the Qp space. Its one-sided T^3_3 is that
    // of the linear field of slope s_l on the left elements and s_r on the right, so the
    // face quadrature of the contact traction (elementwise GLL, `w_a L_e / 2` per element)
    // is sum_k w_k sigma_k(left) over the nodes before the break, the right ones after, and
    // at the break the share L_e / (L_l + L_r) of its weight from each side. (The plain
    // average of the two one-sided stresses, used before, gives the break the share 1/2:
    // measured on the default scene, the limiting ratio at order 6 moved by 1e-4 relative
    // with the grading ratio; with the quadrature's shares, by 1.6e-6.)
    let p = 3;
    let level = GridLevel {
        n2: 16 * p + 1,
        n3: 8 * p + 1,
    };
    let op = paper_parts(&PaperEllipse::default(), level)
        .unwrap()
        .high_order_with(settings(p, 0.15, 3, 1))
        .unwrap();
    let breaks = &op.element_breaks()[0];
    let (ll, lr) = (breaks[1] - breaks[0], breaks[2] - breaks[1]);
    assert!(lr / ll > 5.0, "graded: {ll} then {lr}");
    let xb = breaks[1];
    let field = |slope: &dyn Fn(f64) -> f64| -> Vec<f64> {
        let mut v = vec![0.0; op.dof_count()];
        for i2 in 0..level.n2 {
            for i3 in 0..level.n3 {
                let [x2, _] = op.node_coordinates([i2, i3]);
                v[op.dof([i2, i3], crate::boundary::Component::X2)] = slope(x2) * (x2 - xb);
            }
        }
        v
    };
    let (sl, sr) = (1.0, -3.0);
    let kink = field(&|x2| if x2 < xb { sl } else { sr });
    let left = field(&|_| sl);
    let right = field(&|_| sr);
    let nodes = op.contact_nodes().unwrap();
    let (mut integral, mut quadrature) = (0.0, 0.0);
    for n in &nodes {
        let w = n.traction_weight;
        integral += w * n.normal_stress.dot(&kink);
        quadrature += if (n.x2 - xb).abs() < 1e-14 {
            w * (ll * n.normal_stress.dot(&left) + lr * n.normal_stress.dot(&right)) / (ll + lr)
        } else if n.x2 < xb {
            w * n.normal_stress.dot(&left)
        } else {
            w * n.normal_stress.dot(&right)
        };
    }
    // the same sums in another order: round-off only
    assert!(
        (integral - quadrature).abs() <= 1e-12 * quadrature.abs(),
        "face integral {integral:e}, quadrature {quadrature:e}"
    );
    // the plain average of the one-sided stresses at the break differs by
    // (1/2 - L_l / (L_l + L_r)) w [T] (measured 5e-4 of the integral): far above round-off,
    // so the check discriminates
    let at_break = nodes.iter().find(|n| (n.x2 - xb).abs() < 1e-14).unwrap();
    let (tl, tr) = (
        at_break.normal_stress.dot(&left),
        at_break.normal_stress.dot(&right),
    );
    let average = at_break.traction_weight * 0.5 * (tl + tr);
    let share = at_break.traction_weight * (ll * tl + lr * tr) / (ll + lr);
    assert!(
        (average - share).abs() > 1e-6 * quadrature.abs(),
        "average {average:e}, share {share:e}, integral {quadrature:e}"
    );
}
