//! The matrix-free 3-D operator: its action equals the assembled matrix-vector product on
//! curved charts for Q1, Q2 and Qp (p = 1 ... 4), its right-hand side the assembled one, and
//! its solves (CG with the p-multigrid / semi-coarsening V-cycle) reproduce the manufactured
//! solutions at order p + 1 with iteration counts bounded under refinement.

use std::sync::Arc;

use capstan_elasticity::ShellGeometry;
use capstan_elasticity::finite_element::{ElementOrder, VolumetricIntegration};
use capstan_elasticity::solid::{
    FaceComponent, FaceCondition, HexElement, SolidBody, SolidBoundary, SolidMatrixFree,
    SolidMultigridParams, SolidNavier,
};
use capstan_elasticity::solvers::{
    CsrMatrix, KrylovMethod, KrylovParams, LinearOperator, SilentObserver, krylov_solve_operator,
};
use capstan_elasticity::studies::solid::{SolidField, SolidMms};
use capstan_elasticity::verification::observed_order;
use capstan_geometry::{EllipticalPrism, ShellChart};

/// The chart of the ellipse bodies.
type Chart = ShellChart<EllipticalPrism<f64>>;

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

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

/// `max |A_mf x - A x| / max |A x|` over three random vectors, and the same for the
/// right-hand sides.
fn action_difference<G: ShellGeometry + Sync>(
    mf: &SolidMatrixFree<G>,
    assembled: &SolidNavier<G>,
) -> (f64, f64) {
    let system = assembled.system();
    let a = CsrMatrix::from_pattern(&system.pattern, &system.values).unwrap();
    let n = a.nrows();
    assert_eq!(mf.dimension(), n);
    let mut worst: f64 = 0.0;
    for seed in [1, 2, 3] {
        let x = random_vector(n, seed);
        let (mut y, mut z) = (vec![0.0; n], vec![0.0; n]);
        a.mul_vec(&x, &mut y);
        mf.apply(&x, &mut z);
        let diff: Vec<f64> = y.iter().zip(&z).map(|(a, b)| a - b).collect();
        worst = worst.max(max_abs(&diff) / max_abs(&y));
    }
    let diag_ok = a
        .diagonal()
        .iter()
        .zip(mf.diagonal())
        .all(|(a, b)| (a - b).abs() <= 1e-12 * a.abs());
    assert!(diag_ok, "diagonal");
    let db: Vec<f64> = system
        .rhs
        .iter()
        .zip(mf.rhs())
        .map(|(a, b)| a - b)
        .collect();
    (
        worst,
        max_abs(&db) / max_abs(&system.rhs).max(f64::MIN_POSITIVE),
    )
}

/// The finite-width body on the ellipse `a = 2, b = 1.5` with the contact face's `v^3 = 0`
/// (free sides, end stresses), assembled and matrix-free.
fn ellipse_pair(
    element: HexElement,
    nodes: [usize; 3],
) -> (SolidMatrixFree<Chart>, SolidNavier<Chart>) {
    let mut body = SolidBody::new(EllipticalPrism::new(2.0, 1.5).unwrap(), [-0.5, 0.5], nodes);
    body.order = element;
    let boundary = body.boundary(1.0, 1.5);
    let mf = SolidMatrixFree::new(
        ShellChart::new(body.surface),
        body.material,
        body.grid().unwrap(),
        &boundary,
        None,
        element,
        VolumetricIntegration::Full,
    )
    .unwrap();
    (mf, body.operator(1.0, 1.5).unwrap())
}

#[test]
fn matrix_free_action_equals_the_assembled_product_on_curved_charts() {
    // (element, nodes per direction of the cones, nodes of the ellipse body)
    let cases = [
        (HexElement::Uniform(ElementOrder::Q1), [4, 5, 3], [3, 9, 4]),
        (HexElement::Uniform(ElementOrder::Q2), [5, 5, 3], [3, 9, 5]),
        (HexElement::Gll(1), [3, 4, 3], [3, 5, 3]),
        (HexElement::Gll(2), [5, 5, 3], [3, 7, 5]),
        (HexElement::Gll(3), [7, 4, 4], [4, 7, 4]),
        (HexElement::Gll(4), [5, 9, 5], [5, 9, 5]),
    ];
    for (element, n, m) in cases {
        for mms in [SolidMms::circular_cone(), SolidMms::elliptical_cone()] {
            let mf = mms.matrix_free(n, element).unwrap();
            let a = mms.operator(n, element).unwrap();
            let (action, rhs) = action_difference(&mf, &a);
            assert!(
                action < 1e-13,
                "{} {element:?}: action {action:e}",
                mms.name
            );
            assert!(rhs < 1e-12, "{} {element:?}: rhs {rhs:e}", mms.name);
        }
        let (mf, a) = ellipse_pair(element, m);
        let (action, rhs) = action_difference(&mf, &a);
        assert!(action < 1e-13, "ellipse {element:?}: action {action:e}");
        assert!(rhs < 1e-12, "ellipse {element:?}: rhs {rhs:e}");
    }
}

#[test]
fn a_chart_invariant_in_x1_is_stored_for_one_slab() {
    // the prism's chart does not depend on x1: one slab of elements is stored, for Q1 and Q2
    // (batched kernels) and Qp3 (element by element), and the action is still the assembled
    // one; the cones' charts vary with x1: every slab is stored
    for element in [
        HexElement::Uniform(ElementOrder::Q1),
        HexElement::Uniform(ElementOrder::Q2),
        HexElement::Gll(3),
    ] {
        let k = element.degree();
        let (mf, a) = ellipse_pair(element, [4 * k + 1, 2 * k + 1, k + 1]);
        assert_eq!(mf.stored_slabs(), 1, "{element:?}");
        let (action, _) = action_difference(&mf, &a);
        assert!(action < 1e-13, "{element:?}: action {action:e}");
        let cone = SolidMms::elliptical_cone()
            .matrix_free([3 * k + 1, 2 * k + 1, k + 1], element)
            .unwrap();
        assert_eq!(cone.stored_slabs(), 3, "{element:?}");
    }
}

#[test]
fn reduced_integration_is_refused_naming_the_key() {
    let mms = SolidMms::circular_cone();
    let (boundary, _) = mms.boundary();
    let grid =
        capstan_elasticity::solid::BoxGrid::new(mms.x1, mms.x2, mms.thickness, [3, 3, 3], false)
            .unwrap();
    let err = SolidMatrixFree::new(
        ShellChart::new(mms.obstacle.clone()),
        mms.material,
        grid,
        &boundary,
        None,
        HexElement::Gll(1),
        VolumetricIntegration::Reduced,
    )
    .unwrap_err();
    assert!(
        err.to_string().contains("discretisation.volumetric"),
        "{err}"
    );
}

/// CG with the matrix-free V-cycle to `tolerance`: the solution and the iterations.
fn cg_solve<G: ShellGeometry + Clone + Send + Sync + 'static>(
    op: SolidMatrixFree<G>,
    boundary: &SolidBoundary,
    tolerance: f64,
) -> (Vec<f64>, usize, Arc<SolidMatrixFree<G>>) {
    let op = Arc::new(op);
    let mut mg = SolidMultigridParams {
        coarsest_unknowns: 500,
        ..Default::default()
    }
    .build(&op, boundary)
    .unwrap();
    let b = op.rhs().to_vec();
    let mut x = vec![0.0; b.len()];
    let params = KrylovParams {
        method: KrylovMethod::Cg,
        tolerance,
        max_iterations: 300,
        ..Default::default()
    };
    let report = krylov_solve_operator(
        op.as_ref(),
        &b,
        &mut x,
        &mut mg,
        &params,
        &mut SilentObserver,
    )
    .unwrap();
    let mut r = vec![0.0; b.len()];
    op.residual(&x, &b, &mut r);
    let rel =
        r.iter().map(|v| v * v).sum::<f64>().sqrt() / b.iter().map(|v| v * v).sum::<f64>().sqrt();
    assert!(rel <= tolerance, "{rel:e}");
    (x, report.iterations, op)
}

#[test]
fn matrix_free_solves_reproduce_the_manufactured_orders() {
    // the relative L2 error of the matrix-free CG solution (to 1e-12) on m elements per
    // direction: orders p + 1 as the assembled Cholesky solves (tests/solid.rs)
    let mms = SolidMms::circular_cone();
    let (boundary, _) = mms.boundary();
    let exact = mms.exact();
    for (p, grids, finest) in [
        (1usize, [2usize, 4, 8], 2.5e-3),
        (2, [2, 4, 8], 6e-5),
        (3, [2, 3, 4], 1e-5),
        (4, [2, 3, 4], 5e-7),
    ] {
        let points: Vec<(f64, f64)> = grids
            .iter()
            .map(|&m| {
                let n = p * m + 1;
                let op = mms.matrix_free([n, n, n], HexElement::Gll(p)).unwrap();
                let (x, _, op) = cg_solve(op, &boundary, 1e-12);
                let (e, u) = op
                    .l2_errors(&x, &|y| exact.field.displacement(y).0)
                    .unwrap();
                (mms.thickness / (p * m) as f64, e / u)
            })
            .collect();
        let order = observed_order(&points);
        assert!(
            (order - (p as f64 + 1.0)).abs() < 0.15,
            "p {p}: order {order:.3} {points:?}"
        );
        assert!(points[2].1 < finest, "p {p}: {points:?}");
    }
}

/// The finite-width ellipse body with the contact face clamped (SPD), matrix-free.
fn clamped_ellipse(
    element: HexElement,
    nodes: [usize; 3],
    width: f64,
) -> (
    SolidMatrixFree<ShellChart<EllipticalPrism<f64>>>,
    SolidBoundary,
) {
    let mut body = SolidBody::new(
        EllipticalPrism::new(2.0, 1.5).unwrap(),
        [-0.5 * width, 0.5 * width],
        nodes,
    );
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

/// CG iterations to 1e-8 on the clamped ellipse body.
fn iterations(element: HexElement, nodes: [usize; 3], width: f64) -> usize {
    let (op, boundary) = clamped_ellipse(element, nodes, width);
    cg_solve(op, &boundary, 1e-8).1
}

#[test]
fn multigrid_cg_counts_stay_flat_from_1e4_to_1e5_unknowns() {
    // cells of about equal size (width 1, arc about 5.5, thickness 1); 8x the unknowns
    let q1 = [[9, 33, 9], [17, 65, 17]].map(|n| iterations(HexElement::Gll(1), n, 1.0));
    let q2 = [[9, 33, 9], [17, 65, 17]].map(|n| iterations(HexElement::Gll(2), n, 1.0));
    let q4 = [[9, 33, 9], [17, 65, 17]].map(|n| iterations(HexElement::Gll(4), n, 1.0));
    println!("Q1 {q1:?} Q2 {q2:?} Q4 {q4:?}");
    for (name, c) in [("Q1", q1), ("Q2", q2), ("Q4", q4)] {
        assert!(2 * c[1] <= 3 * c[0], "{name}: {c:?}");
        assert!(c[1] <= 60, "{name}: {c:?}");
    }
}

#[test]
fn semicoarsening_keeps_counts_flat_on_cells_of_aspect_four() {
    // width 0.25 with as many x1 cells as x3 cells: dx1 = dx3 / 4 (aspect 4)
    let c = [[9, 33, 9], [17, 65, 17]].map(|n| iterations(HexElement::Gll(1), n, 0.25));
    println!("aspect 4: {c:?}");
    assert!(2 * c[1] <= 3 * c[0], "{c:?}");
    assert!(c[1] <= 60, "{c:?}");
}

#[test]
fn qp3_contact_by_gmres_and_p_multigrid_equals_the_direct_solution() {
    use capstan_elasticity::contact::{EndLoads, FullSystemSettings, FullSystemSolver};
    use capstan_elasticity::friction::{RegularisedCoulomb, RegularisedCoulombParams};
    use capstan_solvers::{LinearBackend, MultigridParams};
    // Qp3 (GLL nodes): the Newton steps by GMRES with the V-cycle on [P_p (Q1 on the element
    // vertices), box hierarchy], refused before this transfer existed
    let mut body = SolidBody::new(
        EllipticalPrism::new(2.0, 1.5).unwrap(),
        [-0.5, 0.5],
        [7, 49, 7],
    );
    body.order = HexElement::Gll(3);
    let eps = 1e-5;
    let law = RegularisedCoulombParams::new(0.5, eps).unwrap();
    let model = body.model(RegularisedCoulomb, law, eps).unwrap();
    let loads = EndLoads::ratio(1.5);
    let solve = |multigrid: Option<MultigridParams>| {
        let mut settings = FullSystemSettings::default();
        if let Some(m) = multigrid {
            settings.newton.linear = LinearBackend::MULTIGRID;
            settings.newton.multigrid = m;
        }
        FullSystemSolver::new(&model, settings)
            .unwrap()
            .solve(loads)
            .unwrap()
    };
    let direct = solve(None);
    let iterative = solve(Some(MultigridParams {
        coarsest_unknowns: 200,
        ..Default::default()
    }));
    assert!(iterative.stats.linear_iterations > iterative.stats.newton_iterations);
    let scale = max_abs(&direct.displacement);
    let diff: Vec<f64> = direct
        .displacement
        .iter()
        .zip(&iterative.displacement)
        .map(|(a, b)| a - b)
        .collect();
    assert!(
        max_abs(&diff) <= 1e-8 * scale,
        "{:e}",
        max_abs(&diff) / scale
    );
    println!(
        "Qp3 contact: {} Newton steps, {} Krylov iterations",
        iterative.stats.newton_iterations, iterative.stats.linear_iterations
    );
}
