//! The 3-D body's fields as a VTU of hexahedra on the curved body (`capstan contact --out`
//! with `body.dimension = 3`).

use capstan_elasticity::contact::ContactProfile;
use capstan_elasticity::solid::SolidFields;
use capstan_geometry::{Obstacle, ShellChart};

use super::body::body_arrays_vtu;
use crate::output::{OutputDir, OutputError, QuadGrid, Vtu, VtuCompression};

/// The VTU point arrays a 3-D body has beyond those of the plane-strain body
/// ([`super::body::VTU_ARRAYS`], with `v^1` now non-zero), with their component counts (a
/// public contract, documented in `docs/solid.md`).
pub const SOLID_EXTRA_VTU_ARRAYS: [(&str, usize); 2] = [("contact_slip_1", 1), ("x1", 1)];

/// The body's nodes `Theta(x1, x2, x3)` as hexahedra (node `(i1 n2 + i2) n3 + i3`).
///
/// # Errors
/// Geometry failures at a node.
pub fn solid_grid(
    obstacle: &Obstacle,
    x1: &[f64],
    x2: &[f64],
    x3: &[f64],
) -> Result<QuadGrid, OutputError> {
    let chart = ShellChart::new(obstacle);
    let layers = x1
        .iter()
        .map(|&a| QuadGrid::from_chart(&chart, a, x2, x3, false))
        .collect::<Result<Vec<_>, _>>()?;
    QuadGrid::layered(layers)
}

/// Writes `STEM.vtu`: [`super::body::VTU_ARRAYS`] and [`SOLID_EXTRA_VTU_ARRAYS`] on `grid` (`n3` nodes through the thickness;
/// `coordinates[k] = (x1, x2, x3)` of node `k`), the contact state and physical slips of the
/// contact node below each node, compressed as `compression` says.
///
/// # Errors
/// Output errors.
pub fn write_solid_body(
    out: &OutputDir,
    stem: &str,
    grid: &QuadGrid,
    fields: &SolidFields,
    coordinates: &[[f64; 3]],
    contact: &ContactProfile,
    compression: VtuCompression,
) -> Result<(), OutputError> {
    let vtu = solid_vtu(grid, fields, coordinates, contact).encoding(compression.encoding());
    out.write_vtu(&format!("{stem}.vtu"), &vtu)?;
    Ok(())
}

/// The VTU of [`write_solid_body`] (its point arrays are also what the Python package returns
/// as the whole-body fields).
pub fn solid_vtu<'g>(
    grid: &'g QuadGrid,
    fields: &SolidFields,
    coordinates: &[[f64; 3]],
    contact: &ContactProfile,
) -> Vtu<'g> {
    let n = fields.displacement.len();
    let n3 = grid.n3();
    let solid = contact.solid.as_ref();
    // contact node (i1, i2) is entry i1 n2 + i2 of the profile: the column of node k
    let column = |k: usize| k / n3;
    let per_node =
        |f: &dyn Fn(usize) -> f64| -> Vec<f64> { (0..n).map(|k| f(column(k))).collect() };
    let state = per_node(&|c| contact.state.get(c).map_or(0.0, |&s| f64::from(s)));
    let slip = per_node(&|c| contact.slip.get(c).copied().unwrap_or(0.0));
    let slip_1 = per_node(&|c| solid.and_then(|s| s.slip_1.get(c)).copied().unwrap_or(0.0));
    let coordinate = |j: usize| -> Vec<f64> { coordinates.iter().map(|x| x[j]).collect() };
    let physical: Vec<[f64; 3]> = (0..n).map(|k| fields.physical_displacement(k)).collect();
    body_arrays_vtu(
        grid,
        [
            &fields.cartesian_displacement,
            &fields.displacement,
            &physical,
        ],
        fields,
        [state, slip, coordinate(1), coordinate(2)],
    )
    .point_scalars("contact_slip_1", slip_1)
    .point_scalars("x1", coordinate(0))
}
