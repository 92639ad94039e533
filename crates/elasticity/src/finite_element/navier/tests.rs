//! Unit tests of the Q1/Q2 operator: stiffness, pattern, SRI recovery.

use super::*;
use crate::boundary::{BoundaryConditions, Component};
use crate::finite_element::element::{gauss_rule, lagrange_weights};
use crate::grid::Grid;
use capstan_geometry::{EllipticalPrism, ExpressionProfile, GeneralPrism, ShellChart};

/// `K_q` by the definition: the mixed stress coefficients `C_k^i_j` contracted with
/// `D_l^i_j = nabla_i w^j`, then symmetrised.
#[allow(clippy::needless_range_loop)] // index loops mirror the tensor formulas
fn stiffness_by_definition(p: &ShellPoint<f64>, material: &Material, scale: f64) -> [f64; 21] {
    let c = mixed_stress_coefficients(p, material);
    let mut k = [[0.0; 6]; 6];
    for trial in 0..6 {
        for test in 0..6 {
            k[trial][test] = if test < 2 {
                let m = test + 1;
                let mut s = 0.0;
                for i in 0..3 {
                    for j in 0..3 {
                        s += c[trial][i][j] * p.christoffel[j][i][m];
                    }
                }
                s
            } else {
                c[trial][test / 2][test % 2 + 1]
            };
        }
    }
    let mut packed = [0.0; 21];
    for a in 0..6 {
        for b in a..6 {
            packed[PACK[a][b]] = 0.5 * (k[a][b] + k[b][a]) * p.sqrt_g * scale;
        }
    }
    packed
}

fn energy_form_equals_definition<G: ShellGeometry>(chart: &G) {
    let material = Material::new(7.0, 0.3).unwrap();
    for x2 in [-2.0, -0.7, 0.0, 0.4, 1.3] {
        for x3 in [0.0, 0.15, 0.6] {
            let p = chart.shell_point([0.0, x2, x3]).unwrap();
            let fast = packed_stiffness(&p, &material, 0.37);
            let reference = stiffness_by_definition(&p, &material, 0.37);
            let size = reference.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            for (a, b) in fast.iter().zip(&reference) {
                // the same sums in another order: round-off only
                assert!((a - b).abs() <= 1e-13 * size, "x2 {x2} x3 {x3}: {a} vs {b}");
            }
        }
    }
}

/// The pattern by brute force: every pair of nodes of an element (a prescribed row keeps
/// its diagonal only, a prescribed column is dropped) and the contact columns of every free
/// tangential row on `x3 = 0`, through `SparsityPattern::from_entries` (the sort).
fn pattern_by_definition<G: ShellGeometry + Sync>(op: &FiniteElementNavier<G>) -> SparsityPattern {
    let nen = op.nodes_per_element();
    let mut entries = vec![];
    let mut nodes = [0; 9];
    for e in 0..op.elements[0] * op.elements[1] {
        op.element_nodes(e, &mut nodes);
        for &a in &nodes[..nen] {
            for &b in &nodes[..nen] {
                for (r, c) in (0..4).map(|k| (2 * a + k / 2, 2 * b + k % 2)) {
                    let keep = match op.dirichlet[r] {
                        Some(_) => r == c,
                        None => op.dirichlet[c].is_none(),
                    };
                    if keep {
                        entries.push((r, c));
                    }
                }
            }
        }
    }
    for i in 0..op.problem.grid.n2() {
        let d = op.dof([i, 0], Component::X2);
        if op.dirichlet[d].is_none() {
            for row in op.contact_rows(i) {
                entries.extend(row.columns.iter().map(|&c| (d, c)));
            }
        }
    }
    let n = op.dof_count();
    SparsityPattern::from_entries(n, n, &entries).unwrap().0
}

#[test]
fn direct_pattern_and_system_equal_the_entries_path() {
    use crate::samples::{LameCylinder, PaperEllipse};
    use crate::studies::{lame_parts, paper_parts};
    use crate::verification::GridLevel;
    for order in [ElementOrder::Q1, ElementOrder::Q2] {
        let parts = [
            lame_parts(&LameCylinder::default(), GridLevel { n2: 16, n3: 5 }).unwrap(),
            paper_parts(&PaperEllipse::default(), GridLevel { n2: 17, n3: 5 }).unwrap(),
        ];
        for parts in parts {
            let op = parts.finite_element(order).unwrap();
            assert_eq!(op.pattern, pattern_by_definition(&op), "{order:?}");
            // the default `system()`: entries, sort, fill through the slots
            let entries = op.entries().unwrap();
            let mut reference = LinearSystem::from_entries(op.dof_count(), &entries).unwrap();
            op.refill(&mut reference).unwrap();
            let direct = op.system().unwrap();
            assert_eq!(direct.pattern, reference.pattern);
            // the same sums in the same order: bitwise equal
            assert_eq!(direct.values, reference.values);
            assert_eq!(direct.rhs, reference.rhs);
        }
    }
}

#[test]
fn element_nested_dissection_solution_equals_amd() {
    use crate::samples::LameCylinder;
    use crate::studies::lame_parts;
    use crate::verification::GridLevel;
    use capstan_solvers::{ColumnOrdering, DirectParams, SparseCholesky};
    for order in [ElementOrder::Q1, ElementOrder::Q2] {
        let level = GridLevel { n2: 48, n3: 13 };
        let op = lame_parts(&LameCylinder::default(), level)
            .unwrap()
            .finite_element(order)
            .unwrap();
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
        let (nd, fill) = solve(order.cholesky_ordering(op.grid()));
        assert!(fill > 0);
        let scale = amd.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for (a, b) in amd.iter().zip(&nd) {
            // two backward-stable factorisations of a well-conditioned system
            assert!((a - b).abs() <= 1e-12 * scale, "{order:?}: {a} vs {b}");
        }
    }
}

#[test]
fn point_stiffness_splits_into_shear_and_divergence_parts() {
    // the split of selective reduced integration: K = K(lambda = 0) + lambda sqrt(g) t t^T
    let chart = ShellChart::new(EllipticalPrism::new(1.0, 2.0).unwrap());
    let material = Material::new(7.0, 0.3).unwrap();
    let p = chart.shell_point([0.0, 0.4, 0.3]).unwrap();
    let full = packed_stiffness(&p, &material, 0.37);
    let shear = packed_energy(&p, 0.0, material.mu(), 0.37);
    let t = divergence_coefficients(&p, &PLANE_STRAIN);
    let size = full.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for a in 0..6 {
        for b in a..6 {
            let vol = material.lambda() * p.sqrt_g * 0.37 * t[a] * t[b];
            let k = PACK[a][b];
            assert!((full[k] - shear[k] - vol).abs() <= 1e-14 * size); // round-off
        }
    }
    // d_2 v^2 and d_3 v^3 enter the divergence with weight 1, d_3 v^2 and d_2 v^3 not
    for (x, want) in [t[2], t[3], t[4], t[5]].iter().zip([1.0, 0.0, 0.0, 1.0]) {
        assert!((x - want).abs() < 1e-14, "{t:?}"); // g^22 g_22 = 1 to round-off
    }
}

#[test]
fn lagrange_weights_extrapolate_from_the_gauss_points() {
    assert_eq!(lagrange_weights(&[0.0], -1.0), vec![1.0]);
    let (gp, _) = gauss_rule(2);
    let s3 = 3.0f64.sqrt();
    for (s, want) in [
        (-1.0, [0.5 * (1.0 + s3), 0.5 * (1.0 - s3)]),
        (0.0, [0.5, 0.5]),
        (1.0, [0.5 * (1.0 - s3), 0.5 * (1.0 + s3)]),
    ] {
        let w = lagrange_weights(&gp, s);
        for (a, b) in w.iter().zip(want) {
            assert!((a - b).abs() < 1e-15, "{s}: {w:?}"); // closed form: round-off
        }
    }
}

/// A smooth, non-polynomial displacement at the nodes (the recovery sees only nodal
/// values).
fn wavy<G: ShellGeometry + Sync>(op: &FiniteElementNavier<G>) -> Vec<f64> {
    let g = op.grid();
    (0..op.dof_count())
        .map(|d| {
            let [x2, x3]: [f64; 2] = g.coordinates(g.node(d / 2));
            if d % 2 == 0 {
                0.01 * (1.3 * x2 + 2.0 * x3).sin() + 0.002 * x3 * x3
            } else {
                0.02 * (0.7 * x2).cos() * (1.0 + x3) - 0.003 * x2 * x3
            }
        })
        .collect()
}

#[test]
fn contact_normal_stress_is_the_nodal_field_stress_for_both_volumetric_rules() {
    // fields() and the contact rows recover T^3_3 = T^33 g_33 on x3 = 0 the same way
    // (g_23 = 0 on the shell chart); with SRI both take lambda div v from the reduced points
    let chart = ShellChart::new(EllipticalPrism::new(2.0, 1.0).unwrap());
    let material = Material::new(1e3, 0.49).unwrap();
    for order in [ElementOrder::Q1, ElementOrder::Q2] {
        let mut values = vec![];
        for volumetric in VolumetricIntegration::ALL {
            let grid = Grid::new([-1.2, 1.3], 0.4, 13, 5, false).unwrap();
            let bc = BoundaryConditions::paper_clamped(1.0, 1.0);
            let problem = PlaneProblem {
                chart: chart.clone(),
                material,
                grid,
                boundary: bc,
                body_force: None,
            };
            let op = FiniteElementNavier::with_volumetric(problem, order, volumetric).unwrap();
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
fn point_stiffness_equals_stress_coefficient_contraction() {
    energy_form_equals_definition(&ShellChart::new(EllipticalPrism::new(1.0, 2.0).unwrap()));
    energy_form_equals_definition(&ShellChart::new(EllipticalPrism::new(2.0, 0.5).unwrap()));
    let profile =
        ExpressionProfile::parse("3 * sin(t) - 0.2 * sin(3 * t)", "2 * cos(t) + 0.1 * t^2")
            .unwrap();
    energy_form_equals_definition(&ShellChart::new(GeneralPrism::new(profile)));
}
