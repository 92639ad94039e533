//! The intermediate p-levels of the matrix-free V-cycle (Qp4 -> Qp2 -> Q1, issue 30): their
//! transfers compose to the direct interpolation of the vertex field, they cut the Krylov
//! counts of the Qp4 body (bulk CG and the contact Newton) without changing its answer, and the
//! smoothing interval of every matrix-free level covers the top of its spectrum.

use std::sync::Arc;

use capstan_elasticity::contact::{ContactSolution, EndLoads};
use capstan_elasticity::contact::{MatrixFreeNewton, MatrixFreeSettings};
use capstan_elasticity::finite_element::VolumetricIntegration;
use capstan_elasticity::friction::{RegularisedCoulomb, RegularisedCoulombParams};
use capstan_elasticity::solid::{
    FaceComponent, FaceCondition, HexElement, SolidBody, SolidBoundary, SolidMatrixFree,
    SolidMultigridParams,
};
use capstan_elasticity::solvers::{
    KrylovMethod, KrylovParams, LinearOperator, SilentObserver, krylov_solve_operator,
    lanczos_estimate,
};
use capstan_geometry::{EllipticalPrism, ShellChart};

/// The finite-width ellipse body (`a = 2, b = 1.5`, width 1) of `element` with the contact
/// face clamped (SPD), matrix-free, and its boundary.
fn clamped_ellipse(
    element: HexElement,
    nodes: [usize; 3],
) -> (
    SolidMatrixFree<ShellChart<EllipticalPrism<f64>>>,
    SolidBoundary,
) {
    let mut body = SolidBody::new(EllipticalPrism::new(2.0, 1.5).unwrap(), [-0.5, 0.5], nodes);
    body.order = element;
    let mut boundary = body.boundary(1.0, 1.5);
    boundary.faces[4] = FaceCondition([
        FaceComponent::fixed(),
        FaceComponent::fixed(),
        FaceComponent::fixed(),
    ]);
    let op = SolidMatrixFree::new(
        ShellChart::new(body.surface),
        body.material,
        body.grid().unwrap(),
        &boundary,
        None,
        element,
        VolumetricIntegration::Full,
    )
    .unwrap();
    (op, boundary)
}

fn multigrid(p_levels: bool) -> SolidMultigridParams {
    SolidMultigridParams {
        coarsest_unknowns: 300,
        p_levels,
        ..Default::default()
    }
}

/// A fixed-seed pseudo-random vector in `[-1, 1]`.
fn random_vector(n: usize, seed: u64) -> Vec<f64> {
    let mut s = seed;
    (0..n)
        .map(|_| {
            s = s
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            2.0 * ((s >> 11) as f64 / (1u64 << 53) as f64) - 1.0
        })
        .collect()
}

#[test]
fn qp4_p_levels_halve_to_qp2_and_compose_to_the_vertex_interpolation() {
    let (op, boundary) = clamped_ellipse(HexElement::Gll(4), [9, 33, 9]);
    let parts = multigrid(true).parts(&op, &boundary).unwrap();
    assert_eq!(parts.p_levels.len(), 1);
    assert_eq!(parts.p_levels[0].degree, 2);
    // 2 x 8 x 2 elements: Qp2 on 5 x 17 x 5 nodes, Q1 on 3 x 9 x 3
    assert_eq!(parts.p_levels[0].operator.dimension(), 3 * 5 * 17 * 5);
    assert_eq!(parts.coarse.nrows(), 3 * 3 * 9 * 3);
    let t = parts.transfers();
    assert_eq!(t.len(), 2);
    // Q1 -> Qp2 -> Qp4 equals Q1 -> Qp4 (a trilinear field is a Qp2 field: interpolated
    // exactly), the constrained dofs included
    let x = random_vector(parts.coarse.nrows(), 7);
    let mut mid = vec![0.0; t[1].nrows()];
    t[1].mul_vec(&x, &mut mid);
    let mut chained = vec![0.0; t[0].nrows()];
    t[0].mul_vec(&mid, &mut chained);
    let mut direct = vec![0.0; parts.prolongation.nrows()];
    parts.prolongation.mul_vec(&x, &mut direct);
    let d = chained
        .iter()
        .zip(&direct)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(d < 1e-14, "{d:e}"); // products of Lagrange weights: round-off only
    // Qp3 and below keep the straight transfer
    let (op3, boundary3) = clamped_ellipse(HexElement::Gll(3), [7, 25, 7]);
    let parts3 = multigrid(true).parts(&op3, &boundary3).unwrap();
    assert!(parts3.p_levels.is_empty() && parts3.p_coarse.is_none());
    assert_eq!(parts3.transfers().len(), 1);
}

/// CG iterations to 1e-8 with the matrix-free V-cycle, and the V-cycle's bounds and levels.
fn cg_iterations(element: HexElement, nodes: [usize; 3], p_levels: bool) -> usize {
    let (op, boundary) = clamped_ellipse(element, nodes);
    let op = Arc::new(op);
    let mut mg = multigrid(p_levels).build(&op, &boundary).unwrap();
    let b = op.rhs().to_vec();
    let mut x = vec![0.0; b.len()];
    let params = KrylovParams {
        method: KrylovMethod::Cg,
        tolerance: 1e-8,
        max_iterations: 300,
        ..Default::default()
    };
    krylov_solve_operator(
        op.as_ref(),
        &b,
        &mut x,
        &mut mg,
        &params,
        &mut SilentObserver,
    )
    .unwrap()
    .iterations
}

#[test]
fn qp4_p_levels_cut_the_cg_count_to_that_of_q2() {
    let nodes = [9, 33, 9];
    let straight = cg_iterations(HexElement::Gll(4), nodes, false);
    let p_levels = cg_iterations(HexElement::Gll(4), nodes, true);
    let q2 = cg_iterations(HexElement::Gll(2), nodes, true);
    println!("Qp4 straight {straight}, with p-levels {p_levels}; Q2 {q2}");
    assert!(
        3 * p_levels <= 2 * straight,
        "{p_levels} against {straight}"
    );
    assert!(2 * p_levels <= 3 * q2, "{p_levels} against Q2's {q2}");
}

#[test]
fn the_smoothing_interval_covers_the_top_of_every_qp4_level() {
    // the kept bound (MATRIX_FREE_ESTIMATE_MARGIN x 12 power iterations) against a converged
    // lambda_max(D^-1 A) (200 Lanczos steps) on the Qp4 and the Qp2 level: above it (with
    // the margin 1.0 it is below: 0.96 of it) and at most 1.25 x it
    let (op, boundary) = clamped_ellipse(HexElement::Gll(4), [9, 17, 9]);
    let op = Arc::new(op);
    let parts = multigrid(true).parts(&op, &boundary).unwrap();
    let mg = multigrid(true).build(&op, &boundary).unwrap();
    let bounds = mg.estimates();
    let levels: [&dyn LinearOperator; 2] = [op.as_ref(), parts.p_levels[0].operator.as_ref()];
    assert_eq!(bounds.len(), 2);
    for (level, (a, bound)) in levels.iter().zip(&bounds).enumerate() {
        let inv_diag: Vec<f64> = a.diagonal().iter().map(|d| 1.0 / d).collect();
        let top = lanczos_estimate(*a, &inv_diag, 200);
        println!("level {level}: bound {bound:.4}, lambda_max {top:.4}");
        assert!(*bound >= top, "level {level}: {bound} < {top}");
        assert!(
            *bound <= 1.25 * top,
            "level {level}: {bound} > 1.25 x {top}"
        );
    }
}

/// The matrix-free Newton on the Qp4 ellipse body at ratio 1.5 (Eisenstat–Walker forcing).
fn contact(p_levels: bool) -> ContactSolution {
    let mut body = SolidBody::new(
        EllipticalPrism::new(2.0, 1.5).unwrap(),
        [-0.5, 0.5],
        [9, 33, 9],
    );
    body.order = HexElement::Gll(4);
    let eps = 1e-5;
    let params = RegularisedCoulombParams::new(0.5, eps).unwrap();
    let model = body
        .matrix_free_model(RegularisedCoulomb, params, eps, multigrid(p_levels))
        .unwrap();
    let mut settings = MatrixFreeSettings::default();
    settings.continuation.tolerance = 1e-12;
    MatrixFreeNewton::new(&model, settings)
        .unwrap()
        .solve(EndLoads::ratio(1.5))
        .unwrap()
}

#[test]
fn qp4_contact_with_p_levels_gives_the_same_answer_in_fewer_krylov_iterations() {
    let (straight, p_levels) = (contact(false), contact(true));
    let scale = straight
        .displacement
        .iter()
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let d = straight
        .displacement
        .iter()
        .zip(&p_levels.displacement)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
        / scale;
    println!(
        "straight: {} Newton, {} Krylov; p-levels: {} Newton, {} Krylov; difference {d:.2e}",
        straight.stats.newton_iterations,
        straight.stats.linear_iterations,
        p_levels.stats.newton_iterations,
        p_levels.stats.linear_iterations
    );
    // both Newton solves end at 1e-12 relative residual: the answers agree to far below 1e-8
    assert!(d <= 1e-9, "{d:e}");
    // the Krylov work of the whole solve (stuck start and Newton steps): 109 against 63 when
    // this was written (the p-levels' face term P^T F P keeps the V-cycle good on the face)
    let (a, b) = (
        straight.stats.linear_iterations,
        p_levels.stats.linear_iterations,
    );
    assert!(3 * b <= 2 * a, "{b} against {a}");
}
