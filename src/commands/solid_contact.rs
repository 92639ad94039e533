//! The outputs of `capstan contact` for a 3-D body (`body.dimension = 3`): the body on the
//! box `[x1 - width/2, x1 + width/2] x [theta0, theta_max] x [0, h]` of any obstacle (prisms
//! and cones), its contact surface table and its hexahedra with their nodal fields. The solve
//! itself is the one of every body ([`crate::Problem::solve_observed`]).

use capstan_elasticity::contact::ContactSolution;
use capstan_elasticity::solid::{SolidFields, SolidOutput};

use crate::error::CliError;
use crate::output::QuadGrid;
use crate::output::solid_body::{solid_grid, write_solid_body};
use crate::scene::Scene;

/// The 3-D body's hexahedra, nodal fields and node coordinates `(x1, x2, x3)` for the
/// solution: the box grid's tensor product, or a mesh's own nodes and linear sub-hexahedra
/// ([`SolidOutput::output_mesh`]: `fem-qp-corner`).
///
/// # Errors
/// Geometry failures.
pub fn body_fields(
    scene: &Scene,
    body: &dyn SolidOutput,
    solution: &ContactSolution,
) -> Result<(QuadGrid, SolidFields, Vec<[f64; 3]>), CliError> {
    let fields = body.nodal_fields(&solution.displacement)?;
    if let Some(mesh) = body.output_mesh() {
        // a mesh (fem-qp-corner): its own nodes and linear sub-hexahedra
        let chart = capstan_geometry::ShellChart::new(scene.obstacle.build()?);
        let mut points = Vec::with_capacity(mesh.nodes.len());
        let mut bases = Vec::with_capacity(mesh.nodes.len());
        for &x in &mesh.nodes {
            let p = chart.point(x).map_err(crate::output::OutputError::from)?;
            points.push(p.position);
            bases.push(p.covariant_basis);
        }
        let hexahedra = QuadGrid::hexahedra(points, Some(bases), mesh.hexahedra)?;
        return Ok((hexahedra, fields, mesh.nodes));
    }
    let grid = body.box_grid();
    let [n1, n2, n3] = grid.counts();
    let axis = |a: usize, n: usize| -> Vec<f64> {
        (0..n)
            .map(|i| {
                let mut node = [0; 3];
                node[a] = i;
                grid.coordinates(node)[a]
            })
            .collect()
    };
    let (x1, x2, x3) = (axis(0, n1), axis(1, n2), axis(2, n3));
    let hexahedra = solid_grid(&scene.obstacle.build()?, &x1, &x2, &x3)?;
    let coordinates: Vec<[f64; 3]> = (0..grid.node_count())
        .map(|k| grid.coordinates(grid.node(k)))
        .collect();
    Ok((hexahedra, fields, coordinates))
}

/// Writes `body.vtu`: the 3-D body's fields on its hexahedra
/// ([`crate::output::body::VTU_ARRAYS`] and
/// [`crate::output::solid_body::SOLID_EXTRA_VTU_ARRAYS`]); under unilateral contact also
/// `body_separated.{svg,png}` ([`crate::output::solid_body::separated_face_map`]).
///
/// # Errors
/// Geometry or output errors.
pub fn write_body(
    out: &crate::output::OutputDir,
    scene: &Scene,
    body: &dyn SolidOutput,
    solution: &ContactSolution,
) -> Result<(), CliError> {
    let (hexahedra, fields, coordinates) = body_fields(scene, body, solution)?;
    write_solid_body(
        out,
        "body",
        &hexahedra,
        &fields,
        &coordinates,
        &solution.contact,
        scene.output.vtu_compression,
    )?;
    if let Some(map) = crate::output::solid_body::separated_face_map(&solution.contact)? {
        out.write_plot("body_separated", &map)?;
    }
    Ok(())
}
