//! The Qp operator: its condensed solve against the full one, and its convergence on the
//! manufactured solution and the Lamé cylinder.

use capstan_solvers::SparseCholesky;

use super::HighOrderNavier;
use crate::discretisation::Discretisation;
use crate::finite_element::VolumetricIntegration;
use crate::samples::{
    LameCylinder, ManufacturedField, MmsBoundaries, PrismMms, TrigonometricExact,
};
use crate::studies::{lame_parts, mms_parts};
use crate::verification::{GridLevel, observed_order};
use std::sync::Arc;

/// The rate `b` of `error ~ C exp(-b x)`: the observed order against `h = exp(-x)` (the
/// least-squares slope of `ln(error)` against `ln h = -x`).
pub(super) fn exponential_rate(points: &[(f64, f64)]) -> f64 {
    let as_h: Vec<(f64, f64)> = points.iter().map(|&(x, e)| ((-x).exp(), e)).collect();
    observed_order(&as_h)
}

/// Asserts exponential convergence of `(x, error)`: every step at most `step` times the one
/// before and the rate of [`exponential_rate`] above 1.5; returns the rate.
pub(super) fn assert_exponential(errors: &[(f64, f64)], step: f64) -> f64 {
    let rate = exponential_rate(errors);
    assert!(
        errors.windows(2).all(|w| w[1].1 < step * w[0].1),
        "{errors:?}"
    );
    assert!(rate > 1.5, "rate {rate}: {errors:?}");
    rate
}

fn mms() -> PrismMms {
    PrismMms::ellipse(0.5, MmsBoundaries::TractionContact)
}

/// The manufactured problem with `2k x k` elements of order `p`.
fn mms_qp(
    p: usize,
    k: usize,
    volumetric: VolumetricIntegration,
) -> (
    HighOrderNavier<crate::studies::SampleChart>,
    Arc<TrigonometricExact>,
) {
    let level = GridLevel {
        n2: 2 * k * p + 1,
        n3: k * p + 1,
    };
    let (parts, exact) = mms_parts(&mms(), level).unwrap();
    (parts.high_order(p, volumetric).unwrap(), exact)
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

#[test]
fn static_condensation_equals_the_full_solve() {
    for p in [2, 3, 5, 8] {
        for volumetric in VolumetricIntegration::ALL {
            let (op, _) = mms_qp(p, 2, volumetric);
            let full = op
                .full_system()
                .unwrap()
                .solve(&mut SparseCholesky::default())
                .unwrap();
            let condensed = op.solve(&mut SparseCholesky::default()).unwrap();
            let diff = full
                .iter()
                .zip(&condensed)
                .map(|(x, y)| (x - y).abs())
                .fold(0.0, f64::max);
            assert!(diff < 1e-10 * max_abs(&full), "p {p}: {diff:e}"); // round-off of two factorisations
        }
    }
}

/// `(h, L2 error)` of the manufactured Qp study ([`crate::studies::high_order::high_order_mms`]) on `2k x k`
/// elements of order `p` for each `k`.
fn mms_study(p: usize, ks: &[usize]) -> Vec<(f64, f64)> {
    ks.iter()
        .map(|&k| {
            let level = GridLevel {
                n2: 2 * k * p + 1,
                n3: k * p + 1,
            };
            let (parts, exact) =
                mms_parts(&crate::studies::high_order::high_order_mms(), level).unwrap();
            let op = parts.high_order(p, VolumetricIntegration::Full).unwrap();
            let v = op.solve(&mut SparseCholesky::default()).unwrap();
            let e = op
                .displacement_errors(&v, &|x| exact.field.displacement(x).value)
                .unwrap();
            (op.grid().thickness() / k as f64, e.rms)
        })
        .collect()
}

/// The relative L2 error of the Lamé cylinder with `4 x e3` elements of order `p`.
fn lame_error(p: usize, e3: usize) -> f64 {
    let lame = LameCylinder::default();
    let field = lame.field();
    let level = GridLevel {
        n2: 4 * p,
        n3: p * e3 + 1,
    };
    let op = lame_parts(&lame, level)
        .unwrap()
        .high_order(p, VolumetricIntegration::Full)
        .unwrap();
    let v = op.solve(&mut SparseCholesky::default()).unwrap();
    let e = op
        .displacement_errors(&v, &|x| field.displacement(x).value)
        .unwrap();
    e.l2 / e.l2_exact
}

/// Relative L2 errors `(h, error)` of the Lamé cylinder with `4 x e3` elements of order `p`
/// (the solution does not depend on `x2`: refined through the thickness only).
fn lame_h_study(p: usize, e3s: &[usize]) -> Vec<(f64, f64)> {
    let thickness = LameCylinder::default().thickness;
    e3s.iter()
        .map(|&e3| (thickness / e3 as f64, lame_error(p, e3)))
        .collect()
}

#[test]
fn manufactured_solution_converges_with_order_p_plus_1_in_l2_up_to_p_6() {
    // the oscillatory field with its exact (AD) forcing, three grids per order (2k x k
    // elements): in the asymptotic range and far above round-off (finest errors 8.7e-5 at
    // p = 1 ... 6.9e-12 at p = 6)
    for (p, ks) in (1..=6).zip(crate::studies::high_order::HIGH_ORDER_MMS_GRIDS) {
        let study = mms_study(p, &ks);
        let order = observed_order(&study);
        println!(
            "p {p}: L2 order {order:.3}, finest error {:.3e}",
            study[2].1
        );
        assert!(
            (order - (p as f64 + 1.0)).abs() < 0.15,
            "p {p}: order {order}, {study:?}"
        );
        // the constants cannot drift: measured 3.72e-10 (p = 5) and 6.93e-12 (p = 6)
        match p {
            5 => assert!(study[2].1 < 5e-10, "{study:?}"),
            6 => assert!(study[2].1 < 1e-11, "{study:?}"),
            _ => {}
        }
    }
}

#[test]
fn lame_cylinder_converges_with_order_p_plus_1_for_p_5_and_approaches_it_for_p_6() {
    // p = 5: 4 x {4, 8, 16} elements, 4.6e-9 ... 1.4e-12 (measured 5.87)
    let study = lame_h_study(5, &[4, 8, 16]);
    let order = observed_order(&study);
    assert!((order - 6.0).abs() < 0.15, "p 5: order {order}, {study:?}");
    assert!(study[2].1 < 1e-11, "{study:?}");
    // p = 6: the asymptotic range starts where the error meets the round-off floor of the
    // solve (~1e-12 relative); the local orders rise towards 7 from below (5.6, 6.3, 6.7)
    let study = lame_h_study(6, &[2, 4, 8]);
    let last = (study[2].1 / study[1].1).ln() / (study[2].0 / study[1].0).ln();
    assert!(
        last > 6.5 && last < 7.15,
        "p 6: last order {last}, {study:?}"
    );
}

#[test]
fn lame_cylinder_converges_exponentially_in_p() {
    // 4 x 1 elements
    let errors: Vec<(f64, f64)> = (2..=8).map(|p| (p as f64, lame_error(p, 1))).collect();
    assert_exponential(&errors, 0.5);
}

#[test]
fn registered_studies_report_orders_near_p_plus_1() {
    // the Lamé studies of `capstan verify` for p = 2, 3, 4 (4 x {4, 8, 16} elements)
    for study in crate::studies::high_order_studies().iter().skip(7).take(3) {
        let r = study.run(true).unwrap();
        let p = r
            .discretisation
            .trim_start_matches("fem-qp")
            .parse::<f64>()
            .unwrap();
        println!(
            "{} {}: L2 order {:.3}",
            r.name, r.discretisation, r.order_l2
        );
        assert!((r.order_l2 - (p + 1.0)).abs() < 0.15, "{}", r.table());
    }
}

#[test]
fn nodal_fields_sit_at_the_gauss_lobatto_nodes() {
    // the fields (and so the VTU and the contact columns) carry the nodes' true positions
    let (op, _) = mms_qp(4, 2, VolumetricIntegration::Full);
    let v = op.solve(&mut SparseCholesky::default()).unwrap();
    let fields = op.fields(&v).unwrap();
    let g = op.grid();
    assert_eq!((fields.x2.len(), fields.x3.len()), (g.n2(), g.n3()));
    for (i, x) in fields.x2.iter().enumerate() {
        assert_eq!(*x, op.node_coordinates([i, 0])[0]);
    }
    for (j, x) in fields.x3.iter().enumerate() {
        assert_eq!(*x, op.node_coordinates([0, j])[1]);
    }
    // inside an element the GLL points are not the uniform ones: node 1 of 4 at
    // (1 - sqrt(3/7)) / 2 of the element, not 1/4
    let element = g.x2(4) - g.x2(0);
    let t = (fields.x2[1] - fields.x2[0]) / element;
    assert!(
        (t - 0.5 * (1.0 - (3.0f64 / 7.0).sqrt())).abs() < 1e-12,
        "{t}"
    );
}

#[test]
fn contact_extremes_are_reported_at_the_gauss_lobatto_nodes() {
    use crate::contact::ContactOperator;
    let (op, _) = mms_qp(4, 2, VolumetricIntegration::Full);
    let v = op.solve(&mut SparseCholesky::default()).unwrap();
    let g = op.grid();
    for e in op.extremes(&v) {
        // the extreme sits at some node's true position
        let at_node =
            (0..g.n2()).any(|i| (0..g.n3()).any(|j| op.node_coordinates([i, j]) == [e.x2, e.x3]));
        assert!(at_node, "{e:?}");
    }
    assert_eq!(op.node_position([1, 1]), op.node_coordinates([1, 1]));
    assert_ne!(op.node_position([1, 1]), g.coordinates([1, 1]));
}
