//! The 3-D body: manufactured solutions on cones and a prism (observed L2 orders; Q1, Q2 and
//! the Qp hexahedra), and the reduction to the plane-strain operator on prisms.

use capstan_elasticity::finite_element::{ElementOrder, HighOrderNavier, VolumetricIntegration};
use capstan_elasticity::samples::{LameCylinder, PaperEllipse};
use capstan_elasticity::solid::{BoxGrid, FaceCondition, HexElement, SolidBoundary, SolidNavier};
use capstan_elasticity::solvers::SparseCholesky;
use capstan_elasticity::studies::solid::SolidMms;
use capstan_elasticity::verification::{GridLevel, observed_order};
use capstan_elasticity::{Component, Discretisation, ElasticityError};

/// `(h, relative L2 error)` on `m` elements per direction for each `m` of `grids`.
fn study(mms: &SolidMms, element: HexElement, grids: [usize; 3]) -> Vec<(f64, f64)> {
    grids
        .map(|m| mms.relative_error(m, element).unwrap())
        .to_vec()
}

fn table(points: &[(f64, f64)]) -> String {
    points
        .iter()
        .map(|(h, e)| format!("h {h:.4e} error {e:.3e}"))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn manufactured_solutions_converge_at_order_two_for_q1_and_three_for_q2() {
    // measured (release): Q1 2.7e-2, 7.3e-3, 1.9e-3 on the circular cone; Q2 2.2e-3, 2.8e-4,
    // 3.5e-5; the elliptical cone (g_12 != 0) and the prism alike
    for mms in [
        SolidMms::circular_cone(),
        SolidMms::elliptical_cone(),
        SolidMms::expression_prism(),
    ] {
        for (order, expected, finest) in [
            (ElementOrder::Q1, 2.0, 2.5e-3),
            (ElementOrder::Q2, 3.0, 6e-5),
        ] {
            assert_order(&mms, order.into(), [2, 4, 8], expected, finest);
        }
    }
}

/// Asserts the observed L2 order within 0.15 of `expected` and the finest error below
/// `finest`.
#[track_caller]
fn assert_order(
    mms: &SolidMms,
    element: HexElement,
    grids: [usize; 3],
    expected: f64,
    finest: f64,
) {
    let points = study(mms, element, grids);
    let p = observed_order(&points);
    println!("{} {element:?}: order {p:.3}\n{}", mms.name, table(&points));
    assert!(
        (p - expected).abs() < 0.15,
        "{} {element:?}: order {p:.3}\n{}",
        mms.name,
        table(&points)
    );
    assert!(
        points[2].1 < finest,
        "{} {element:?}\n{}",
        mms.name,
        table(&points)
    );
}

#[test]
fn manufactured_solutions_converge_at_order_p_plus_one_for_qp_hexahedra() {
    // measured (dev profile), circular cone: orders 1.933, 3.008, 3.885, 5.042, finest
    // 1.9e-3, 3.5e-5, 3.4e-6, 1.2e-7; elliptical cone (g_12 != 0): 1.957, 2.997, 3.880,
    // 5.023, finest 1.9e-3, 3.8e-5, 3.7e-6, 1.3e-7
    let cases: [(usize, [usize; 3], f64); 4] = [
        (1, [2, 4, 8], 2.5e-3),
        (2, [2, 4, 8], 6e-5),
        (3, [2, 3, 4], 1e-5),
        (4, [2, 3, 4], 5e-7),
    ];
    for mms in [SolidMms::circular_cone(), SolidMms::elliptical_cone()] {
        for (p, grids, finest) in cases {
            assert_order(&mms, HexElement::Gll(p), grids, p as f64 + 1.0, finest);
        }
    }
}

/// The 3-D body on a prism with plane-strain `x1` faces against the 2-D operator: max
/// difference of `(v^2, v^3)` over every node, relative to the largest displacement, and the
/// largest `|v^1|` (relative likewise).
/// The 2-D operator is Q1/Q2 for [`HexElement::Uniform`], `fem-qp` for [`HexElement::Gll`].
fn reduction_difference(
    parts: capstan_elasticity::studies::ProblemParts,
    element: HexElement,
    volumetric: VolumetricIntegration,
) -> Result<(f64, f64), ElasticityError> {
    let grid2 = parts.grid;
    let boundary2 = parts.boundary.clone();
    let chart = parts.chart.clone();
    let material = parts.material;
    let plane: Box<dyn Discretisation> = match element {
        HexElement::Uniform(order) => {
            Box::new(HighOrderNavier::with_element(parts, order, volumetric)?)
        }
        HexElement::Gll(p) => Box::new(parts.high_order(p, volumetric)?),
    };
    let v2 = plane.solve(&mut SparseCholesky::default())?;
    let n1 = element.degree() + 1;
    let grid3 = BoxGrid::new(
        [0.0, 0.3],
        grid2.theta(),
        grid2.thickness(),
        [n1, grid2.n2(), grid2.n3()],
        grid2.is_periodic(),
    )?;
    let boundary3 = SolidBoundary::extruded(&boundary2, FaceCondition::plane_strain(), n1);
    let solid = SolidNavier::new(
        chart, material, grid3, &boundary3, None, element, volumetric,
    )?;
    let v3 = solid.solve(&mut SparseCholesky::default())?;
    let scale = v2.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let (mut diff, mut v1) = (0.0f64, 0.0f64);
    for i1 in 0..n1 {
        for i2 in 0..grid2.n2() {
            for i3 in 0..grid2.n3() {
                for (c, comp) in [(1, Component::X2), (2, Component::X3)] {
                    let a = v3[solid.dof([i1, i2, i3], c)];
                    let b = v2[plane.dof([i2, i3], comp)];
                    diff = diff.max((a - b).abs());
                }
                v1 = v1.max(v3[solid.dof([i1, i2, i3], 0)].abs());
            }
        }
    }
    Ok((diff / scale, v1 / scale))
}

/// Asserts that the extrusion of the paper's clamped ellipse (`paper` nodes) and of the Lamé
/// cylinder (a full wrap, `lame` nodes, pinned at `pins` along `x2`) reproduces the 2-D
/// solution on every `x1` section, `v^1 = 0`, to round-off, with full and reduced integration.
#[track_caller]
fn assert_reduces(element: HexElement, paper: GridLevel, lame: GridLevel, pins: &[usize]) {
    for volumetric in [VolumetricIntegration::Full, VolumetricIntegration::Reduced] {
        let cases = [
            PaperEllipse::default().parts(paper).unwrap(),
            LameCylinder::default().parts_pinned(lame, pins).unwrap(),
        ];
        for parts in cases {
            let (diff, v1) = reduction_difference(parts, element, volumetric).unwrap();
            println!("{element:?} {volumetric:?}: difference {diff:.2e}, |v^1| {v1:.2e}");
            assert!(
                diff < 1e-10 && v1 < 1e-10,
                "{element:?} {volumetric:?}: {diff:e} {v1:e}"
            );
        }
    }
}

#[test]
fn a_prism_with_plane_strain_faces_reproduces_the_plane_strain_operator() {
    for order in [ElementOrder::Q1, ElementOrder::Q2] {
        assert_reduces(
            order.into(),
            GridLevel { n2: 21, n3: 5 },
            GridLevel { n2: 16, n3: 5 },
            &[0, 4, 8],
        );
    }
}

#[test]
fn qp_hexahedra_on_a_prism_with_plane_strain_faces_reproduce_the_two_dimensional_fem_qp() {
    // GLL nodes in x2, x3 (and x1) at the same true positions in 2-D and 3-D (measured:
    // 1.6e-14 .. 3.4e-13 relative for p = 3, 4)
    for p in [3, 4] {
        assert_reduces(
            HexElement::Gll(p),
            GridLevel {
                n2: 4 * p + 1,
                n3: p + 1,
            },
            GridLevel {
                n2: 4 * p,
                n3: p + 1,
            },
            &[0, p, 2 * p],
        );
    }
}

#[test]
fn a_chart_with_its_focal_surface_inside_the_body_is_a_typed_error() {
    // the cone over a counter-clockwise profile: its normal points to the axis, and a body of
    // thickness 1 on a cross-section of radius 0.5-0.75 crosses the focal surface
    let mut mms = SolidMms::circular_cone();
    mms.obstacle = capstan_geometry::Obstacle::Cone(capstan_geometry::GeneralCone::new(
        capstan_geometry::ExpressionProfile::parse("-0.5 * sin(t)", "0.5 * cos(t)").unwrap(),
    ));
    mms.thickness = 1.0;
    let err = mms.operator([3, 3, 3], ElementOrder::Q1).unwrap_err();
    println!("{err}");
    assert!(matches!(err, ElasticityError::Geometry(_)), "{err:?}");
}

/// The rigid translations of [`ContactOperator::near_null_space`] (in the contravariant
/// components of the chart) are annihilated by the assembled operator up to the interpolation
/// error of Q1: `|A z|` on the rows away from the Dirichlet faces, relative to
/// `sum_c |A_rc| |z_c|`, falls at least like `h^2` (a vector that is not a rigid motion stays
/// O(1)).
#[test]
fn rigid_body_modes_are_near_null_at_order_two() {
    use capstan_elasticity::contact::ContactOperator;
    let mms = SolidMms::elliptical_cone();
    let mut points = Vec::new();
    for m in [4, 8, 16] {
        let n = m + 1;
        let op = mms.operator([n, n, n], ElementOrder::Q1).unwrap();
        let space = op.near_null_space().unwrap();
        assert_eq!(space.block_size, 3);
        assert_eq!(space.vectors.len(), 3);
        let system = op.system();
        let (row_ptr, cols, slots) = system.pattern.row_layout();
        let mut worst = 0.0f64;
        for z in &space.vectors {
            assert_eq!(z.len(), op.dof_count());
            for i1 in 2..n - 2 {
                for i2 in 2..n - 2 {
                    for i3 in 0..n {
                        for c in 0..3 {
                            let r = op.dof([i1, i2, i3], c);
                            let (mut az, mut scale) = (0.0, 0.0);
                            for k in row_ptr[r]..row_ptr[r + 1] {
                                let a = system.values[slots[k]];
                                az += a * z[cols[k]];
                                scale += (a * z[cols[k]]).abs();
                            }
                            worst = worst.max(az.abs() / scale);
                        }
                    }
                }
            }
        }
        points.push((1.0 / m as f64, worst));
    }
    let p = observed_order(&points);
    assert!(p > 1.9 && p < 3.0, "order {p}\n{}", table(&points));
    assert!(points[2].1 < 2e-5, "{}", table(&points));
}
