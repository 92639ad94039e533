//! The nodal recovery of the Qp operator (the Q1/Q2 nodal differences against the element
//! polynomials), the selective-reduced-integration split and the Q1/Q2 ordering.

use capstan_geometry::{EllipticalPrism, ShellChart};
use capstan_solvers::SparseCholesky;

use super::{Grading, HighOrderNavier, NodalRecovery, QpSettings};
use crate::boundary::BoundaryConditions;
use crate::continuum::{PLANE_STRAIN, divergence_coefficients, energy_matrix};
use crate::discretisation::Discretisation;
use crate::error::ElasticityError;
use crate::finite_element::{ElementOrder, VolumetricIntegration};
use crate::grid::Grid;
use crate::material::Material;
use crate::plane_problem::PlaneProblem;
use crate::shell_geometry::ShellGeometry;
use crate::verification::observed_order;

fn problem(n2: usize, n3: usize, nu: f64) -> PlaneProblem<ShellChart<EllipticalPrism<f64>>> {
    PlaneProblem {
        chart: ShellChart::new(EllipticalPrism::new(2.0, 1.0).unwrap()),
        material: Material::new(1e3, nu).unwrap(),
        grid: Grid::new([-1.2, 1.3], 0.4, n2, n3, false).unwrap(),
        boundary: BoundaryConditions::paper_clamped(1.0, 1.0),
        body_force: None,
    }
}

/// `[v^2, v^3]` of a smooth, non-polynomial field at `(x2, x3)`.
fn wavy_at([x2, x3]: [f64; 2]) -> [f64; 2] {
    [
        0.01 * (1.3 * x2 + 2.0 * x3).sin() + 0.002 * x3 * x3,
        0.02 * (0.7 * x2).cos() * (1.0 + x3) - 0.003 * x2 * x3,
    ]
}

/// The smooth field at the operator's nodes (the recovery sees only nodal values).
fn wavy<G: ShellGeometry + Sync>(op: &HighOrderNavier<G>) -> Vec<f64> {
    let g = op.grid();
    (0..op.dof_count())
        .map(|d| wavy_at(op.node_coordinates(g.node(d / 2)))[d % 2])
        .collect()
}

#[test]
fn differences_recovery_is_refused_above_order_two_and_on_graded_elements() {
    let with = |order: usize, grading: Grading| {
        let settings = QpSettings {
            order,
            grading,
            recovery: NodalRecovery::Differences,
            ..QpSettings::order(order)
        };
        HighOrderNavier::with_settings(problem(13, 7, 0.3), settings)
    };
    assert!(with(1, Grading::UNIFORM).is_ok());
    assert!(with(2, Grading::UNIFORM).is_ok());
    let refused = |r: Result<_, ElasticityError>| {
        matches!(
            r,
            Err(ElasticityError::InvalidParameter {
                field: "recovery",
                ..
            })
        )
    };
    assert!(refused(with(3, Grading::UNIFORM)));
    assert!(refused(with(2, Grading::geometric(0.5, 1).unwrap())));
}

#[test]
fn differences_recover_the_contact_face_gradient_at_second_order_where_q1_elements_give_first() {
    // d_3 v on x3 = 0 from the nodal values of a smooth field: the one-sided (-3, 4, -1) / 2h
    // difference is second order, the Q1 element derivative (v(1) - v(0)) / h first order
    let errors = |recovery: NodalRecovery| -> Vec<(f64, f64)> {
        [9, 17, 33]
            .into_iter()
            .map(|n3| {
                let settings = QpSettings {
                    recovery,
                    ..QpSettings::element(ElementOrder::Q1)
                };
                let op =
                    HighOrderNavier::with_settings(problem(2 * n3 - 1, n3, 0.3), settings).unwrap();
                let v = wavy(&op);
                let h = op.grid().dx3();
                let mut error = 0.0f64;
                for i in 0..op.grid().n2() {
                    let [x2, _]: [f64; 2] = op.node_coordinates([i, 0]);
                    let exact = 0.02 * (1.3 * x2).cos(); // d_3 v^2 of `wavy_at` on x3 = 0
                    let u = op.local([i, 0], &v);
                    error = error.max((u.gradient[1][0] - exact).abs());
                }
                (h, error)
            })
            .collect()
    };
    let differences = observed_order(&errors(NodalRecovery::Differences));
    let element = observed_order(&errors(NodalRecovery::Element));
    assert!(
        (differences - 2.0).abs() < 0.15,
        "differences: {differences}"
    );
    assert!((element - 1.0).abs() < 0.15, "element: {element}");
}

#[test]
fn contact_normal_stress_is_the_nodal_field_stress_for_both_volumetric_rules() {
    // fields() and the contact rows recover T^3_3 = T^33 g_33 on x3 = 0 the same way
    // (g_23 = 0 on the shell chart); with SRI both take lambda div v from the reduced points
    for order in [ElementOrder::Q1, ElementOrder::Q2] {
        let mut values = vec![];
        for volumetric in VolumetricIntegration::ALL {
            let op =
                HighOrderNavier::with_element(problem(13, 5, 0.49), order, volumetric).unwrap();
            let v = wavy(&op);
            let fields = op.fields(&v).unwrap();
            let mut row = vec![];
            for node in op.contact_nodes().unwrap() {
                let k = op.grid().node_index(node.node);
                let t33 = fields.stress[k][2][2] * fields.scale[k][2].powi(2);
                let own = node.normal_stress.dot(&v);
                // the same sums in another order, times lambda / mu = 49: round-off
                assert!(
                    (own - t33).abs() < 1e-11 * (1.0 + t33.abs()),
                    "{own} vs {t33}"
                );
                // the shear row is pointwise for both rules
                let t32 = fields.stress[k][2][1] * fields.scale[k][1].powi(2);
                assert!((node.shear_stress.dot(&v) - t32).abs() < 1e-11 * (1.0 + t32.abs()));
                row.push(own);
            }
            values.push(row);
        }
        // the rules differ only by lambda (div_h - div) at the node: not by round-off
        let diff = values[0]
            .iter()
            .zip(&values[1])
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(diff > 1e-3, "{order:?}: {diff}");
    }
}

#[test]
fn point_stiffness_splits_into_shear_and_divergence_parts() {
    // the split of selective reduced integration: K = K(lambda = 0) + lambda sqrt(g) t t^T
    let chart = ShellChart::new(EllipticalPrism::new(1.0, 2.0).unwrap());
    let material = Material::new(7.0, 0.3).unwrap();
    let p = chart.shell_point([0.0, 0.4, 0.3]).unwrap();
    let (lambda, mu) = (material.lambda(), material.mu());
    let full = energy_matrix(&p, &PLANE_STRAIN, lambda, mu, 0.37);
    let shear = energy_matrix(&p, &PLANE_STRAIN, 0.0, mu, 0.37);
    let t = divergence_coefficients(&p, &PLANE_STRAIN);
    let size = full.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    for a in 0..6 {
        for b in 0..6 {
            let vol = lambda * p.sqrt_g * 0.37 * t[a] * t[b];
            assert!((full[a][b] - shear[a][b] - vol).abs() <= 1e-14 * size); // round-off
        }
    }
    // d_2 v^2 and d_3 v^3 enter the divergence with weight 1, d_3 v^2 and d_2 v^3 not
    for (x, want) in [t[2], t[3], t[4], t[5]].iter().zip([1.0, 0.0, 0.0, 1.0]) {
        assert!((x - want).abs() < 1e-14, "{t:?}"); // g^22 g_22 = 1 to round-off
    }
}

#[test]
fn element_nested_dissection_solution_equals_amd() {
    use crate::samples::LameCylinder;
    use crate::studies::lame_parts;
    use crate::verification::GridLevel;
    use capstan_solvers::{ColumnOrdering, DirectParams};
    for order in [ElementOrder::Q1, ElementOrder::Q2] {
        let level = GridLevel { n2: 48, n3: 13 };
        let op = lame_parts(&LameCylinder::default(), level)
            .unwrap()
            .finite_element(order)
            .unwrap();
        assert_eq!(op.lu_ordering(), order.cholesky_ordering(op.grid()));
        let system = op.system().unwrap();
        let solve = |ordering| {
            let mut chol = SparseCholesky::new(DirectParams {
                ordering,
                ..Default::default()
            })
            .unwrap();
            let v = system.solve(&mut chol).unwrap();
            (v, chol.factor_values())
        };
        let (amd, _) = solve(ColumnOrdering::Amd);
        let (nd, fill) = solve(op.lu_ordering());
        assert!(fill > 0);
        let scale = amd.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for (a, b) in amd.iter().zip(&nd) {
            // two backward-stable factorisations of a well-conditioned system
            assert!((a - b).abs() <= 1e-12 * scale, "{order:?}: {a} vs {b}");
        }
    }
}
