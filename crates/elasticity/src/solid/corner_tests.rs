//! Verification of [`SolidCornerNavier`]: manufactured solutions at order `p + 1` in L2 on
//! the extruded corner mesh, the tensor-grid operator reproduced with no layers, typed errors.

use std::collections::HashMap;

use capstan_geometry::ShellChart;
use capstan_solvers::SparseCholesky;

use super::{
    BoxGrid, Face, FaceComponent, FaceCondition, FaceFunction, HexElement, SolidBoundary,
    SolidCornerNavier, SolidNavier,
};
use crate::error::ElasticityError;
use crate::finite_element::VolumetricIntegration;
use crate::finite_element::high_order::CornerSettings;
use crate::studies::SampleChart;
use crate::studies::solid::{SolidField, SolidMms};

/// The manufactured problem of `mms` with natural conditions on one face of each direction:
/// the exact tractions on `x1 = x1a`, `x2 = x2b` and both `x3` faces, the exact displacement
/// on `x1 = x1b` and `x2 = x2a`.
fn mixed_boundary(mms: &SolidMms) -> SolidBoundary {
    let (mut boundary, _) = mms.boundary();
    let exact = mms.exact();
    let traction = |face: Face| {
        FaceCondition([0, 1, 2].map(|c| {
            let ex = exact.clone();
            FaceComponent::Traction(FaceFunction::new(move |x| {
                ex.traction(face, x).map_or(f64::NAN, |t| t[c])
            }))
        }))
    };
    boundary.faces[0] = traction(Face::X1Min);
    boundary.faces[3] = traction(Face::X2Max);
    boundary
}

fn corner_operator(
    mms: &SolidMms,
    n1: usize,
    settings: CornerSettings,
) -> Result<SolidCornerNavier<SampleChart>, ElasticityError> {
    let grid = BoxGrid::new(mms.x1, mms.x2, mms.thickness, [n1, 2, 2], false)?;
    let (_, force) = mms.boundary();
    SolidCornerNavier::new(
        ShellChart::new(mms.obstacle.clone()),
        mms.material,
        grid,
        &mixed_boundary(mms),
        Some(&force),
        settings,
    )
}

/// Relative L2 error on `m` elements along `x1` and `m x m` cells of the corner layout.
fn relative_error(mms: &SolidMms, p: usize, m: usize, layers: usize) -> f64 {
    let settings = CornerSettings {
        order: p,
        cells: [m, m],
        layers,
        ratio: 0.3,
    };
    let op = corner_operator(mms, p * m + 1, settings).unwrap();
    let v = op.solve(&mut SparseCholesky::default()).unwrap();
    let exact = mms.exact();
    let (e, u) = op
        .l2_errors(&v, &|x| exact.field.displacement(x).0)
        .unwrap();
    e / u
}

#[test]
fn manufactured_solutions_converge_at_order_p_plus_one_on_the_corner_mesh() {
    // two charts (g_12 != 0 on the cone), two layers at every corner edge, natural
    // conditions on trapezoid edges of the x2 and x3 faces and on the x1 faces. The layers
    // make the coarse levels more accurate, so the observed order reaches p + 1 from above
    // m = 4 (p 3, prism: 3.71 from m = 4 to 6, 3.90 from 6 to 8; without layers 3.93, 4.00)
    for (mms, p, ms) in [
        (SolidMms::elliptical_cone(), 2, [4, 8]),
        (SolidMms::expression_prism(), 3, [6, 8]),
    ] {
        let errors = ms.map(|m| relative_error(&mms, p, m, 2));
        let order = (errors[0] / errors[1]).ln() / (ms[1] as f64 / ms[0] as f64).ln();
        println!(
            "3-D corner mms {} p {p}: m {ms:?}, errors {errors:?}, order {order:.3}",
            mms.name
        );
        assert!(
            (order - (p as f64 + 1.0)).abs() < 0.25,
            "{} p {p}: errors {errors:?}, order {order}",
            mms.name
        );
        assert!(errors[1] < 1e-3, "{errors:?}");
    }
}

#[test]
fn no_layers_reproduce_the_tensor_grid_operator() {
    let mms = SolidMms::elliptical_cone();
    let (p, ne) = (3, [2, 2, 3]);
    let n = ne.map(|e| p * e + 1);
    let settings = CornerSettings {
        order: p,
        cells: [ne[1], ne[2]],
        layers: 0,
        ratio: 0.5,
    };
    let corner = corner_operator(&mms, n[0], settings).unwrap();
    let grid = BoxGrid::new(mms.x1, mms.x2, mms.thickness, n, false).unwrap();
    let (_, force) = mms.boundary();
    let tensor = SolidNavier::new(
        ShellChart::new(mms.obstacle.clone()),
        mms.material,
        grid,
        &mixed_boundary(&mms),
        Some(&force),
        HexElement::Gll(p),
        VolumetricIntegration::Full,
    )
    .unwrap();
    assert_eq!(corner.dof_count(), tensor.dof_count());
    let vc = corner.solve(&mut SparseCholesky::default()).unwrap();
    let vt = tensor.solve(&mut SparseCholesky::default()).unwrap();
    // the tensor grid's nodes by position
    let key = |x: [f64; 3]| x.map(|c| (c * 1e9).round() as i64);
    let placed = grid.with_gll_lines(p).unwrap();
    let index: HashMap<[i64; 3], usize> = (0..placed.node_count())
        .map(|m| (key(placed.coordinates(placed.node(m))), m))
        .collect();
    let scale = vt.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let mut worst = 0.0f64;
    for m in 0..corner.node_count() {
        let t = index[&key(corner.node_position(m))];
        for c in 0..3 {
            worst = worst.max((vc[3 * m + c] - vt[3 * t + c]).abs());
        }
    }
    assert!(worst < 1e-12 * scale, "{worst} against {scale}");
    let exact = mms.exact();
    let u = |x: [f64; 3]| exact.field.displacement(x).0;
    let (ec, uc) = corner.l2_errors(&vc, &u).unwrap();
    let (et, ut) = tensor.l2_errors(&vt, &u).unwrap();
    assert!((ec - et).abs() < 1e-12 * ut, "{ec} {et}");
    assert!((uc - ut).abs() < 1e-12 * ut, "{uc} {ut}");
    println!(
        "3-D corner, no layers: nodal values {worst:.2e} of {scale:.2e}, L2 errors {ec:.6e} {et:.6e}"
    );
    // the nodal fields of the outputs: the element gradients averaged over the hexahedra
    // holding a node are the tensor grid's line averages
    let (fc, ft) = (corner.fields(&vc).unwrap(), tensor.fields(&vt).unwrap());
    let stress_scale = ft
        .stress
        .iter()
        .flatten()
        .flatten()
        .fold(0.0f64, |a, s| a.max(s.abs()));
    let mut worst_stress = 0.0f64;
    for m in 0..corner.node_count() {
        let t = index[&key(corner.node_position(m))];
        for (a, b) in fc.stress[m]
            .iter()
            .flatten()
            .zip(ft.stress[t].iter().flatten())
        {
            worst_stress = worst_stress.max((a - b).abs());
        }
        for (a, b) in fc.cartesian_displacement[m]
            .iter()
            .zip(&ft.cartesian_displacement[t])
        {
            assert!((a - b).abs() < 1e-12 * scale);
        }
    }
    assert!(
        worst_stress < 1e-10 * stress_scale,
        "{worst_stress} against {stress_scale}"
    );
}

#[test]
fn output_hexahedra_cover_the_layered_mesh_with_positive_volume() {
    use crate::solid::SolidOutput;
    let mms = SolidMms::circular_cone();
    let (p, layers) = (2, 3);
    let settings = CornerSettings {
        order: p,
        cells: [3, 2],
        layers,
        ratio: 0.3,
    };
    let op = corner_operator(&mms, 2 * p + 1, settings).unwrap();
    let mesh = op.output_mesh().unwrap();
    assert_eq!(mesh.nodes.len(), op.node_count());
    assert_eq!(op.node_count(), (2 * p + 1) * settings.node_count());
    // every hexahedron, every layer: p^3 sub-hexahedra of each of the 2 x1 elements times
    // the 3 x 2 cells with 2 trapezoids per layer at each of the four corners
    let quads = 3 * 2 + 4 * 2 * layers;
    assert_eq!(mesh.hexahedra.len(), 2 * quads * p * p * p);
    // volumes in the parameters (x2, x3, x1) (VTK's bottom quad, then the top): positive
    // and summing to the box
    let mut total = 0.0;
    for h in &mesh.hexahedra {
        let x = h.map(|k| {
            let [a, b, c] = mesh.nodes[k];
            [b, c, a]
        });
        let d = |i: usize, j: usize| -> [f64; 3] { core::array::from_fn(|c| x[j][c] - x[i][c]) };
        // the parallelepiped at corner 0 of the (affine in x1, bilinear in x2, x3) cell
        let (u, v, w) = (d(0, 1), d(0, 3), d(0, 4));
        let det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
            + u[2] * (v[0] * w[1] - v[1] * w[0]);
        assert!(det > 0.0, "{h:?}: {det}");
        // the cell's exact volume: affine in x1 times the bilinear quad's area
        let q = [x[0], x[1], x[2], x[3]];
        let area = 0.5
            * ((q[0][0] - q[2][0]) * (q[1][1] - q[3][1])
                - (q[1][0] - q[3][0]) * (q[0][1] - q[2][1]))
                .abs();
        total += area * w[2];
    }
    let box_volume = (mms.x1[1] - mms.x1[0]) * (mms.x2[1] - mms.x2[0]) * mms.thickness;
    assert!(
        (total - box_volume).abs() < 1e-12 * box_volume,
        "{total} {box_volume}"
    );
}

#[test]
fn bad_settings_and_grids_are_typed_errors_naming_the_key() {
    let mms = SolidMms::circular_cone();
    let good = CornerSettings {
        order: 2,
        cells: [2, 2],
        layers: 1,
        ratio: 0.3,
    };
    let field = |r: Result<SolidCornerNavier<SampleChart>, ElasticityError>| match r {
        Err(ElasticityError::InvalidParameter { field, .. }) => field,
        other => panic!("{other:?}"),
    };
    assert_eq!(field(corner_operator(&mms, 4, good)), "grid.n1");
    let layers = CornerSettings { layers: 17, ..good };
    assert_eq!(field(corner_operator(&mms, 5, layers)), "layers");
    let ratio = CornerSettings { ratio: 1.0, ..good };
    assert_eq!(field(corner_operator(&mms, 5, ratio)), "ratio");
    let cells = CornerSettings {
        cells: [1, 2],
        ..good
    };
    assert_eq!(field(corner_operator(&mms, 5, cells)), "cells");
    let grid = BoxGrid::new(mms.x1, mms.x2, mms.thickness, [5, 3, 3], false).unwrap();
    let mut pinned = mixed_boundary(&mms);
    pinned.pinned.push(([0, 0, 0], 0, 0.0));
    let build = |b: &SolidBoundary, g: BoxGrid| {
        SolidCornerNavier::new(
            ShellChart::new(mms.obstacle.clone()),
            mms.material,
            g,
            b,
            None,
            good,
        )
    };
    assert_eq!(field(build(&pinned, grid)), "boundary.pinned");
    let periodic = BoxGrid::new(mms.x1, mms.x2, mms.thickness, [5, 4, 3], true).unwrap();
    assert_eq!(
        field(build(&mixed_boundary(&mms), periodic)),
        "grid.periodic"
    );
}
