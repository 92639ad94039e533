//! The corner-refined Qp operator: condensed against full solve, order `p + 1` on the
//! manufactured solution, exponential convergence in `p` on the paper problem against the
//! tensor-graded reference, and fewer unknowns than whole-line grading for the same error.

use std::sync::Arc;

use capstan_solvers::SparseCholesky;

use super::{CornerRefinedNavier, CornerSettings};
use crate::discretisation::Discretisation;
use crate::finite_element::high_order::tests::assert_exponential;
use crate::finite_element::high_order::{Grading, HighOrderNavier, QpSettings};
use crate::samples::{ManufacturedField, MmsBoundaries, PaperEllipse, PrismMms};
use crate::studies::{SampleChart, mms_parts, paper_parts};
use crate::verification::{GridLevel, observed_order};

/// Coarse cells of the paper runs: `x2` cells of `pi / 12` (arc `0.52 ... 0.79` on radii
/// `2 ... 3`) against `x3` cells of `0.5`, so the corner cells are about square in physical
/// length (`6 x 2`, twice as wide, left `9e-5` in the end trapezoids whatever the layers).
const CELLS: [usize; 2] = [12, 2];

/// Any grid: the corner mesh only takes the rectangle from it.
const LEVEL: GridLevel = GridLevel { n2: 9, n3: 5 };

fn corner(p: usize, cells: [usize; 2], layers: usize, ratio: f64) -> CornerSettings {
    CornerSettings {
        order: p,
        cells,
        layers,
        ratio,
    }
}

fn paper_corner(s: CornerSettings) -> (CornerRefinedNavier<SampleChart>, Vec<f64>) {
    let parts = paper_parts(&PaperEllipse::default(), LEVEL).unwrap();
    let op = CornerRefinedNavier::new(parts, s).unwrap();
    let v = op.solve(&mut SparseCholesky::default()).unwrap();
    (op, v)
}

/// The paper problem on the tensor grid graded toward the corners: order `p`, `n` layers of
/// `0.4`, and its solution.
fn tensor_graded(p: usize, n: usize) -> (HighOrderNavier<SampleChart>, Vec<f64>) {
    let level = GridLevel {
        n2: (2 * n + 6) * p + 1,
        n3: (2 * n + 1) * p + 1,
    };
    let settings = QpSettings {
        grading: Grading::geometric(0.4, n).unwrap(),
        ..QpSettings::order(p)
    };
    let op = paper_parts(&PaperEllipse::default(), level)
        .unwrap()
        .high_order_with(settings)
        .unwrap();
    let v = op.solve(&mut SparseCholesky::default()).unwrap();
    (op, v)
}

/// The tensor-graded paper reference of `graded_tests` (`p = 8`, 8 layers of `0.4`).
fn graded_reference() -> (HighOrderNavier<SampleChart>, Vec<f64>) {
    tensor_graded(8, 8)
}

fn distance(
    (op, v): &(CornerRefinedNavier<SampleChart>, Vec<f64>),
    (reference, vr): &(HighOrderNavier<SampleChart>, Vec<f64>),
) -> f64 {
    let e = op
        .displacement_errors(v, &|x| reference.displacement_at(vr, x))
        .unwrap();
    e.l2 / e.l2_exact
}

#[test]
fn condensed_solve_equals_the_full_solve() {
    let parts = paper_parts(&PaperEllipse::default(), LEVEL).unwrap();
    let op = CornerRefinedNavier::new(parts, corner(4, [3, 2], 3, 0.3)).unwrap();
    let condensed = op.solve(&mut SparseCholesky::default()).unwrap();
    let full = op
        .full_system()
        .unwrap()
        .solve(&mut SparseCholesky::default())
        .unwrap();
    let scale = full.iter().fold(0.0f64, |s, x| s.max(x.abs()));
    let diff = condensed
        .iter()
        .zip(&full)
        .fold(0.0f64, |s, (a, b)| s.max((a - b).abs()));
    assert!(diff < 1e-10 * scale, "{diff:e} of {scale:e}"); // round-off of two factorisations
    assert_eq!(op.dof_count(), full.len());
}

#[test]
fn corner_mesh_keeps_order_p_plus_1_on_the_manufactured_solution() {
    // cells 2s x 2s (s = 2, 4, 8: from s = 1 every cell is a corner cell, pre-asymptotic),
    // two layers of 0.3 in each corner cell: every element shrinks with 1/s
    let mms = PrismMms::ellipse(0.5, MmsBoundaries::TractionContact);
    for (p, splits) in [(2, [2, 4, 8]), (3, [2, 4, 8])] {
        let study: Vec<(f64, f64)> = splits
            .iter()
            .map(|&s| {
                let (parts, exact) = mms_parts(&mms, LEVEL).unwrap();
                let op =
                    CornerRefinedNavier::new(parts, corner(p, [2 * s, 2 * s], 2, 0.3)).unwrap();
                let v = op.solve(&mut SparseCholesky::default()).unwrap();
                let exact = Arc::clone(&exact);
                let err = op
                    .displacement_errors(&v, &|x| exact.field.displacement(x).value)
                    .unwrap();
                (1.0 / s as f64, err.l2 / err.l2_exact)
            })
            .collect();
        let order = observed_order(&study);
        println!("corner mms p {p}: order {order:.3}, {study:?}");
        assert!(
            (order - (p as f64 + 1.0)).abs() < 0.2,
            "p {p}: order {order}, {study:?}"
        );
        assert!(study[2].1 < [4e-5, 1e-6][p - 2], "p {p}: {study:?}");
    }
}

#[test]
fn corner_mesh_converges_exponentially_in_p_on_the_paper_problem() {
    // the bench's cells (12 x 2: corner cells about square in physical length), 6 layers of
    // 0.3; p = 2 ... 7 against the tensor-graded p = 8 reference (another mesh: the distance
    // includes the reference's own error, ~1e-7)
    let reference = graded_reference();
    let errors: Vec<(f64, f64)> = (2..=7)
        .map(|p| {
            let run = paper_corner(corner(p, CELLS, 6, 0.3));
            (p as f64, distance(&run, &reference))
        })
        .collect();
    let rate = assert_exponential(&errors, 0.5);
    println!("corner paper, 6 layers: rate {rate:.3}, {errors:?}");
}

#[test]
fn corner_mesh_needs_fewer_unknowns_than_whole_line_grading() {
    // the tensor mesh, p = 6 with 6 layers of 0.4 (18 x 13 elements), against the corner mesh,
    // p = 7 with 5 layers of 0.3 (12 x 2 cells): the corner mesh is more accurate with under
    // half the unknowns
    let reference = graded_reference();
    let (p, n) = (6, 6);
    let (tensor, vt) = tensor_graded(p, n);
    let et = tensor
        .displacement_errors(&vt, &|x| reference.0.displacement_at(&reference.1, x))
        .unwrap();
    let tensor_error = et.l2 / et.l2_exact;
    let run = paper_corner(corner(7, CELLS, 5, 0.3));
    let corner_error = distance(&run, &reference);
    println!(
        "tensor p {p}, {n} layers: {} unknowns {tensor_error:e}; corner p 7: {} unknowns {corner_error:e}",
        tensor.dof_count(),
        run.0.dof_count()
    );
    assert!(2 * run.0.dof_count() < tensor.dof_count());
    assert!(
        corner_error < 1.5 * tensor_error,
        "{corner_error:e} {tensor_error:e}"
    );
}

#[test]
fn periodic_grids_and_pins_are_refused_naming_the_key() {
    use crate::ElasticityError;
    use crate::studies::lame_parts;
    let lame = lame_parts(
        &crate::samples::LameCylinder::default(),
        GridLevel { n2: 16, n3: 5 },
    )
    .unwrap();
    match CornerRefinedNavier::new(lame, corner(2, [2, 2], 1, 0.3)) {
        Err(ElasticityError::InvalidParameter { field, .. }) => assert_eq!(field, "grid.periodic"),
        other => panic!("{other:?}"),
    }
}
