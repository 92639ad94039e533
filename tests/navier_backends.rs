//! The assembled Navier system through every linear backend, and the contact-row API.

use capstan_elasticity::samples::{
    LameCylinder, MmsBoundaries, PaperEllipse, PrismMms, SampleChart,
};
use capstan_elasticity::solvers::{
    IterativeParams, LinearBackend, LinearSolver, SparseLu, max_abs_difference,
};
use capstan_elasticity::verification::GridLevel;
use capstan_elasticity::{
    BoundaryFunction, Component, ComponentCondition, Discretisation, FiniteDifferenceNavier,
    PlaneProblem,
};

#[test]
fn lu_jacobi_and_gauss_seidel_agree_on_the_paper_ellipse() {
    let op = PaperEllipse::default()
        .operator(GridLevel { n2: 25, n3: 5 })
        .unwrap();
    let system = op.system().unwrap();
    let lu = system.solve(&mut SparseLu::default()).unwrap();
    assert!(system.relative_residual(&lu) < 1e-12);
    // Undamped Jacobi diverges on this operator (the mixed-derivative and Christoffel terms
    // break diagonal dominance); damped Jacobi (relaxation 1/2) and Gauss-Seidel converge.
    let tolerance = 1e-10;
    for (backend, relaxation, iterations) in [
        (LinearBackend::JACOBI, 0.5, 2393),
        (LinearBackend::GAUSS_SEIDEL, 1.0, 606),
    ] {
        let params = IterativeParams {
            tolerance,
            max_iterations: 100_000,
            relaxation,
        };
        let mut solver = backend
            .build(
                &capstan_elasticity::solvers::LinearSettings {
                    iterative: params,
                    ..Default::default()
                },
                &(),
            )
            .unwrap();
        let v = system.solve(&mut *solver).unwrap();
        assert_eq!(solver.last_iterations(), Some(iterations), "{backend}");
        let scale = lu.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        // relative residual 1e-10 and a condition number ~1e3 on this grid
        assert!(
            max_abs_difference(&v, &lu) < 1e-6 * scale,
            "{backend}: {}",
            max_abs_difference(&v, &lu)
        );
    }
    let params = IterativeParams {
        tolerance,
        max_iterations: 20_000,
        relaxation: 1.0,
    };
    let mut jacobi = LinearBackend::JACOBI
        .build(
            &capstan_elasticity::solvers::LinearSettings {
                iterative: params,
                ..Default::default()
            },
            &(),
        )
        .unwrap();
    assert!(
        system.solve(&mut *jacobi).is_err(),
        "undamped Jacobi is expected to diverge"
    );
}

#[test]
fn refill_reproduces_the_first_assembly() {
    let (op, _) = PrismMms::ellipse(0.5, MmsBoundaries::BilateralContact)
        .operator(GridLevel { n2: 13, n3: 7 })
        .unwrap();
    let mut system = op.system().unwrap();
    let (values, rhs) = (system.values.clone(), system.rhs.clone());
    op.refill(&mut system).unwrap();
    assert_eq!(system.values, values);
    assert_eq!(system.rhs, rhs);
    assert_eq!(system.dimension(), op.dof_count());
    assert_eq!(op.dof([3, 2], Component::X3), 2 * (3 * 7 + 2) + 1);
}

#[test]
fn contact_rows_carry_the_traction_exactly() {
    // Bilateral contact with the exact tangential traction on x3 = 0, assembled either as a
    // boundary condition or added by hand through `ContactNode::traction_weight`.
    let study = PrismMms::ellipse(2.0, MmsBoundaries::BilateralContact);
    let level = GridLevel { n2: 17, n3: 9 };
    let (op, exact) = study.operator(level).unwrap();
    let reference = op.solve(&mut SparseLu::default()).unwrap();

    let (op0, _) = study.operator(level).unwrap();
    let mut boundary = op0.boundary().clone();
    boundary.x3_min.0[0] = ComponentCondition::Traction(BoundaryFunction::zero());
    let without = FiniteDifferenceNavier::new(PlaneProblem {
        chart: op0.chart().clone(),
        material: *op0.material(),
        grid: *op0.grid(),
        boundary,
        body_force: Some(std::sync::Arc::new(move |x| exact.forcing(x).unwrap())),
    })
    .unwrap();
    let mut system = without.system().unwrap();
    let (_, exact) = study.operator(level).unwrap();
    for node in without.contact_nodes().unwrap() {
        if let Some(row) = node.tangential_row {
            let t = exact
                .traction(capstan_elasticity::Side::X3Min, [node.x2, 0.0])
                .unwrap();
            system.rhs[row] += node.traction_weight * t[0];
            // the friction Jacobian's columns are in the pattern of the tangential row
            for &c in node
                .normal_stress
                .columns
                .iter()
                .chain(&node.shear_stress.columns)
            {
                assert!(system.pattern.slot(row, c).is_some());
            }
        }
    }
    let v = system.solve(&mut SparseLu::default()).unwrap();
    assert!(max_abs_difference(&v, &reference) < 1e-12);
}

/// The Lamé cylinder's operator on `n2 x n3` nodes and its LU solution.
fn lame_solution(
    n2: usize,
    n3: usize,
) -> (LameCylinder, FiniteDifferenceNavier<SampleChart>, Vec<f64>) {
    let lame = LameCylinder::default();
    let op = lame.operator(GridLevel { n2, n3 }).unwrap();
    let v = op.solve(&mut SparseLu::default()).unwrap();
    (lame, op, v)
}

#[test]
fn contact_normal_stress_row_matches_fields_and_lame_pressure() {
    let (lame, op, v) = lame_solution(32, 33);
    let fields = op.fields(&v).unwrap();
    for node in op.contact_nodes().unwrap() {
        let k = op.grid().node_index(node.node);
        let t33 = node.normal_stress.dot(&v);
        // g_33 = 1, g_23 = 0: T^3_3 = T^33
        assert!((t33 - fields.stress[k][2][2]).abs() < 1e-12);
        // sigma_rr(R) = -p, second order in dx3 = 1/32
        assert!((t33 + lame.pressure).abs() < 5e-3, "{t33}");
        assert!(node.shear_stress.dot(&v).abs() < 1e-9);
        assert!((node.sqrt_g22 - lame.radius).abs() < 1e-12);
    }
}

#[test]
fn fields_give_physical_and_cartesian_components() {
    let (lame, op, v) = lame_solution(16, 9);
    let f = op.fields(&v).unwrap();
    let k = op.grid().node_index([4, 8]); // x2 = pi/2, x3 = h: the point (0, 2, 0)
    let [_, ur] = f.physical_displacement(k);
    let u = f.cartesian_displacement[k];
    assert!((u[1] - ur).abs() < 1e-12 && u[2].abs() < 1e-12);
    let exact = lame.field();
    let r = lame.radius + lame.thickness;
    assert!(
        (ur - (exact.a * r + exact.b / r)).abs() < 1e-2 * ur.abs(),
        "{ur}"
    ); // 9 nodes in x3
    // sigma_rr(R + h) = 0 (physical): second-order small
    assert!(f.physical_stress(k)[2][2].abs() < 2e-2 * lame.pressure);
}
