//! The finite-element discretisation behind the `Discretisation` trait: symmetry, Cholesky
//! against LU, reproducible parallel assembly, contact rows, and agreement with the finite
//! differences on the paper's linear stand-in.

use capstan_elasticity::finite_element::{
    DiscretisationMethod, ElementOrder, VolumetricIntegration,
};
use capstan_elasticity::samples::{ManufacturedField, MmsBoundaries, PaperEllipse, PrismMms};
use capstan_elasticity::solvers::{SparseCholesky, SparseLu};
use capstan_elasticity::studies::{mms_parts, paper_parts};
use capstan_elasticity::verification::GridLevel;
use capstan_elasticity::{Component, Discretisation, ElasticityError};

fn level(n2: usize, n3: usize) -> GridLevel {
    GridLevel { n2, n3 }
}

#[test]
fn stiffness_is_bitwise_symmetric_and_cholesky_matches_lu() {
    for order in [ElementOrder::Q1, ElementOrder::Q2] {
        let mms = PrismMms::ellipse(2.0, MmsBoundaries::BilateralContact);
        let (parts, _) = mms_parts(&mms, level(13, 7)).unwrap();
        let op = parts.finite_element(order).unwrap();
        let system = op.system().unwrap();
        let p = &system.pattern;
        for (k, (r, c)) in p.entries().enumerate() {
            let mirror = p.slot(c, r).map_or(0.0, |s| system.values[s]);
            assert_eq!(system.values[k], mirror, "({r}, {c})"); // exact: symmetrised elements
        }
        let lu = system.solve(&mut SparseLu::default()).unwrap();
        let chol = system.solve(&mut SparseCholesky::default()).unwrap();
        let scale = lu.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for (a, b) in lu.iter().zip(&chol) {
            assert!((a - b).abs() < 1e-10 * scale); // two direct solves: round-off
        }
        assert!(system.relative_residual(&chol) < 1e-12);
    }
}

#[test]
fn refill_is_bitwise_reproducible() {
    let (parts, _) = mms_parts(
        &PrismMms::expression_prism(MmsBoundaries::TractionContact),
        level(49, 25),
    )
    .unwrap();
    let op = parts.finite_element(ElementOrder::Q2).unwrap();
    let mut a = op.system().unwrap();
    let b = a.clone();
    op.refill(&mut a).unwrap();
    assert_eq!(a.values, b.values); // parallel element matrices, sequential scatter
    assert_eq!(a.rhs, b.rhs);
}

#[test]
fn contact_rows_recover_the_exact_normal_and_shear_stress() {
    // The bilateral MMS has v^3 = 0 on x3 = 0; its exact T^3_j are known pointwise.
    let mms = PrismMms::ellipse(2.0, MmsBoundaries::BilateralContact);
    let mut errors = vec![];
    for m in [12, 24] {
        let (parts, exact) = mms_parts(&mms, level(2 * m + 1, m + 1)).unwrap();
        for order in [ElementOrder::Q1, ElementOrder::Q2] {
            let op = parts.clone().finite_element(order).unwrap();
            let v = op.solve(&mut SparseCholesky::default()).unwrap();
            let nodes = op.contact_nodes().unwrap();
            assert_eq!(nodes.len(), 2 * m + 1);
            let system = op.system().unwrap();
            let mut err: f64 = 0.0;
            for n in &nodes {
                let t = exact.mixed_stress([n.x2, 0.0]).unwrap();
                err = err.max((n.normal_stress.dot(&v) - t[2][2]).abs());
                err = err.max((n.shear_stress.dot(&v) - t[2][1]).abs());
                assert_eq!(n.normal_dof, op.dof(n.node, Component::X3));
                // free tangential rows (x2 = theta0 has a stress condition, theta1 Dirichlet);
                // the rows' own columns are in the bulk pattern, the stress columns beyond the
                // element (Q1's one-sided x3 difference reaches node line 2) are added by the
                // contact solvers' extended pattern (contact/pattern.rs), not by the operator
                let row = n.tangential_row;
                assert_eq!(row.is_some(), n.node[0] < 2 * m);
                if let Some(r) = row {
                    assert!(system.pattern.slot(r, n.tangential_dof).is_some(), "({r})");
                }
                assert!(n.traction_weight > 0.0);
            }
            errors.push(err);
            // lumped boundary weights sum to int sqrt(g) sqrt(g^33) dx2 (= arc length here)
            let total: f64 = nodes.iter().map(|n| n.traction_weight).sum();
            let chart = capstan_geometry::ShellChart::new(mms.obstacle.clone());
            let reference: f64 = (0..2000)
                .map(|i| {
                    let x2 =
                        mms.theta[0] + (i as f64 + 0.5) * (mms.theta[1] - mms.theta[0]) / 2000.0;
                    let p = chart.point([0.0, x2, 0.0]).unwrap();
                    p.sqrt_g * p.inverse_metric[2][2].sqrt() * (mms.theta[1] - mms.theta[0])
                        / 2000.0
                })
                .sum();
            assert!(
                (total - reference).abs() < 2e-3 * reference,
                "{total} {reference}"
            ); // lumping: O(h^2)
        }
    }
    // second-order recovery: the error falls by about 4 per refinement (Q1 and Q2)
    for order in 0..2 {
        let ratio = errors[order] / errors[2 + order];
        assert!(ratio > 3.0, "{errors:?}");
    }
    let scale = 1.0; // stresses of the field are O(1) (E = 10, strains ~0.1)
    assert!(
        errors[2] < 2e-2 * scale && errors[3] < 2e-2 * scale,
        "{errors:?}"
    );
}

#[test]
fn method_names_and_scene_spelling() {
    assert_eq!(
        DiscretisationMethod::ALL.map(|m| m.name()),
        ["fd", "fem-q1", "fem-q2", "fem-qp"]
    );
    assert_eq!(DiscretisationMethod::default(), DiscretisationMethod::Fd);
    assert!(DiscretisationMethod::FemQ1.is_symmetric() && !DiscretisationMethod::Fd.is_symmetric());
}

#[test]
fn fill_checks_the_right_hand_side_length_for_every_method() {
    let parts = paper_parts(&PaperEllipse::default(), level(25, 5)).unwrap();
    for method in DiscretisationMethod::ALL {
        let op = method.build(parts.clone()).unwrap();
        let n = op.dof_count();
        let mut rhs = vec![0.0; n - 1];
        match op.fill(&mut |_, _| {}, &mut rhs) {
            Err(ElasticityError::DimensionMismatch {
                quantity: "rhs",
                expected,
                found,
            }) => assert_eq!((expected, found), (n, n - 1), "{method}"),
            other => panic!("{method}: {other:?}"),
        }
        let mut rhs = vec![0.0; n];
        op.fill(&mut |_, _| {}, &mut rhs).unwrap();
        assert_eq!(rhs, op.system().unwrap().rhs, "{method}"); // the same right-hand side
    }
}

#[test]
fn displacement_errors_check_the_length_for_q1_and_qp() {
    let parts = paper_parts(&PaperEllipse::default(), level(25, 5)).unwrap();
    let exact = |_: [f64; 2]| [0.0; 2];
    let q1 = parts.clone().finite_element(ElementOrder::Q1).unwrap();
    let qp = parts.high_order(4, VolumetricIntegration::Full).unwrap();
    let short = vec![0.0; 2 * 25 * 5 - 1];
    for result in [
        q1.displacement_errors(&short, &exact),
        qp.displacement_errors(&short, &exact),
    ] {
        assert!(
            matches!(
                result,
                Err(ElasticityError::DimensionMismatch {
                    quantity: "displacement",
                    expected: 250,
                    found: 249,
                })
            ),
            "{result:?}"
        );
    }
    let zero = vec![0.0; 2 * 25 * 5];
    assert_eq!(q1.displacement_errors(&zero, &exact).unwrap().max, 0.0);
    assert_eq!(qp.displacement_errors(&zero, &exact).unwrap().max, 0.0);
}

#[test]
fn q2_rejects_even_node_counts() {
    let parts = paper_parts(&PaperEllipse::default(), level(24, 9)).unwrap();
    assert!(parts.clone().finite_element(ElementOrder::Q2).is_err());
    assert!(parts.finite_element(ElementOrder::Q1).is_ok());
}

/// The paper's default linear stand-in: the tangential displacement at the outer midpoint and
/// the total contact shear from FD, Q1 and Q2 converge to the same limit.
#[test]
fn fd_and_fem_agree_on_the_paper_stand_in() {
    let paper = PaperEllipse::default();
    let outer = |op: &dyn Discretisation, v: &[f64]| {
        let g = op.grid();
        let node = [(g.n2() - 1) / 2, g.n3() - 1];
        v[op.dof(node, Component::X2)]
    };
    let mut table = vec![];
    for m in [8, 16, 32] {
        let lv = level(4 * m + 1, m + 1);
        let parts = paper_parts(&paper, lv).unwrap();
        let fd = parts.clone().finite_difference().unwrap();
        let v = fd.solve(&mut SparseLu::default()).unwrap();
        let mut row = vec![outer(&fd, &v)];
        for order in [ElementOrder::Q1, ElementOrder::Q2] {
            let op = parts.clone().finite_element(order).unwrap();
            let v = op.solve(&mut SparseCholesky::default()).unwrap();
            row.push(outer(&op, &v));
        }
        table.push(row);
    }
    println!("{table:?}");
    let reference = table[2][2]; // finest Q2
    let diff = |k: usize, j: usize| (table[k][j] - reference).abs() / reference.abs();
    // each method's distance to the reference shrinks under refinement, and on the finest
    // grid all three agree to 1%
    for j in 0..2 {
        assert!(diff(2, j) < diff(0, j), "{table:?}");
        assert!(diff(2, j) < 1e-2, "{table:?}");
    }
    assert!(diff(1, 2) < 1e-2, "{table:?}");
}

#[test]
fn fem_solution_matches_exact_field_at_the_nodes() {
    // a direct check of one MMS solve, independent of the study machinery
    let mms = PrismMms::ellipse(0.5, MmsBoundaries::TractionContact);
    let (parts, exact) = mms_parts(&mms, level(25, 13)).unwrap();
    let op = parts.finite_element(ElementOrder::Q2).unwrap();
    let v = op.solve(&mut SparseCholesky::default()).unwrap();
    let g = *op.grid();
    let mut err: f64 = 0.0;
    for k in 0..g.node_count() {
        let u = exact.field.displacement(g.coordinates(g.node(k))).value;
        err = err
            .max((v[2 * k] - u[0]).abs())
            .max((v[2 * k + 1] - u[1]).abs());
    }
    assert!(err < 2e-5, "{err}"); // Q2 on 25 x 13: observed ~9e-6 (Cartesian max)
}
