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

/// The contact face of a 3-D body flattened onto its parameters `(x1, x2)`, each cell with
/// the fraction of its four nodes that have lifted off.
#[derive(Debug, Clone, PartialEq)]
pub struct SeparatedFace {
    /// `(x1, x2)` of the face nodes (profile order).
    pub points: Vec<[f64; 2]>,
    /// The face cells (node numbers into `points`), `x1` line by `x1` line.
    pub cells: Vec<[usize; 4]>,
    /// Per cell, the fraction (0, 1/4, ..., 1) of its nodes separated.
    pub fraction: Vec<f64>,
    /// `sum_cells fraction * (parametric cell area)`: the separated parametric area
    /// `int int [separated] dx1 dx2` by the trapezoid rule on the nodal indicator.
    pub area: f64,
    /// The parametric area of the whole face.
    pub face_area: f64,
}

impl SeparatedFace {
    /// From the contact face nodes `(x1[k], x2[k])`, listed `x1` line by `x1` line (`n2`
    /// nodes of equal `x1` each, as a 3-D contact profile lists them), and their
    /// `separated` flags.
    ///
    /// # Errors
    /// [`OutputError::LengthMismatch`] for columns of different lengths or a face that is not
    /// whole lines of at least two nodes, two lines at least.
    pub fn new(x1: &[f64], x2: &[f64], separated: &[bool]) -> Result<Self, OutputError> {
        let n = separated.len();
        let n2 = x1.iter().take_while(|&&a| a == x1[0]).count();
        if n2 < 2 || !n.is_multiple_of(n2) || n / n2 < 2 || x1.len() != n || x2.len() != n {
            return Err(OutputError::length_mismatch(
                "contact face nodes (whole x1 lines of n2 >= 2 nodes, n1 >= 2 lines)",
                n2.max(2) * (n / n2.max(1)).max(2),
                n,
            ));
        }
        let n1 = n / n2;
        let points: Vec<[f64; 2]> = (0..n).map(|k| [x1[k], x2[k]]).collect();
        let mut cells = Vec::with_capacity((n1 - 1) * (n2 - 1));
        let mut fraction = Vec::with_capacity(cells.capacity());
        let (mut area, mut face_area) = (0.0, 0.0);
        for i1 in 0..n1 - 1 {
            for i2 in 0..n2 - 1 {
                let c = [
                    i1 * n2 + i2,
                    (i1 + 1) * n2 + i2,
                    (i1 + 1) * n2 + i2 + 1,
                    i1 * n2 + i2 + 1,
                ];
                let f = 0.25 * c.iter().filter(|&&k| separated[k]).count() as f64;
                let cell = (x1[c[1]] - x1[c[0]]).abs() * (x2[c[3]] - x2[c[0]]).abs();
                area += f * cell;
                face_area += cell;
                fraction.push(f);
                cells.push(c);
            }
        }
        Ok(Self {
            points,
            cells,
            fraction,
            area,
            face_area,
        })
    }
}

/// The map of [`SeparatedFace`] for a 3-D body in unilateral contact (`body_separated` of
/// `capstan contact --out`; the title states the separated area); `None` for bilateral contact
/// (no `separated` column) or a profile that is not a 3-D one.
///
/// # Errors
/// See [`SeparatedFace::new`].
pub fn separated_face_map(
    contact: &ContactProfile,
) -> Result<Option<super::ColourMap>, OutputError> {
    let (Some(separated), Some(solid)) = (&contact.separated, &contact.solid) else {
        return Ok(None);
    };
    let face = SeparatedFace::new(&solid.x1, &contact.x2, separated)?;
    let title = format!(
        "Contact face lifted off: area {:.4} of {:.4}",
        face.area, face.face_area
    );
    Ok(Some(
        super::ColourMap::new(title, face.points, face.cells, face.fraction)
            .label("separated fraction of the cell's nodes")
            .axis_labels("x1", "x2 (rad on an angular chart)")
            .range(0.0, 1.0),
    ))
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
    let solid = contact.solid.as_ref();
    // the profile entry of each node: on the box grid the contact node (i1, i2) below it
    // (entry i1 n2 + i2: the column of node k); on a mesh the face node of its x1 line
    // nearest in x2
    let columns: Vec<usize> = if grid.is_unstructured() {
        nearest_face_entries(coordinates, contact)
    } else {
        let n3 = grid.n3();
        (0..n).map(|k| k / n3).collect()
    };
    let per_node =
        |f: &dyn Fn(usize) -> f64| -> Vec<f64> { columns.iter().map(|&c| f(c)).collect() };
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

/// For every node `(x1, x2, x3)` of a mesh, the entry of the 3-D contact `profile` on the
/// same `x1` line (equal `x1` to 1e-12 of the width) whose `x2` is nearest; `usize::MAX` (no
/// entry: state and slip 0) where the profile has no such line.
fn nearest_face_entries(coordinates: &[[f64; 3]], profile: &ContactProfile) -> Vec<usize> {
    let Some(solid) = profile.solid.as_ref() else {
        return vec![usize::MAX; coordinates.len()];
    };
    // the profile's x1 lines: (x1, first entry, end), entries in increasing x2 along each
    let mut lines: Vec<(f64, usize, usize)> = Vec::new();
    for (k, &x1) in solid.x1.iter().enumerate() {
        match lines.last_mut() {
            Some(line) if line.0 == x1 => line.2 = k + 1,
            _ => lines.push((x1, k, k + 1)),
        }
    }
    let span = solid
        .x1
        .iter()
        .fold([f64::INFINITY, f64::NEG_INFINITY], |[a, b], &x| {
            [a.min(x), b.max(x)]
        });
    let tol = 1e-12 * (span[1] - span[0]).abs().max(1.0);
    coordinates
        .iter()
        .map(|x| {
            let Some(&(_, from, to)) = lines.iter().find(|l| (l.0 - x[0]).abs() <= tol) else {
                return usize::MAX;
            };
            let x2 = &profile.x2[from..to];
            let i = x2.partition_point(|&c| c < x[1]);
            [i.checked_sub(1), (i < x2.len()).then_some(i)]
                .into_iter()
                .flatten()
                .min_by(|&a, &b| (x2[a] - x[1]).abs().total_cmp(&(x2[b] - x[1]).abs()))
                .map_or(usize::MAX, |j| from + j)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_separated_face_is_the_trapezoid_rule_on_the_nodal_flags() {
        // 3 x1 lines (0, 0.5, 1) of 4 nodes (x2 = 0, 1, 2, 3), separated for x2 >= 2
        let x1: Vec<f64> = (0..12).map(|k| 0.5 * (k / 4) as f64).collect();
        let x2: Vec<f64> = (0..12).map(|k| (k % 4) as f64).collect();
        let separated: Vec<bool> = x2.iter().map(|&y| y >= 2.0).collect();
        let face = SeparatedFace::new(&x1, &x2, &separated).unwrap();
        assert_eq!(face.cells.len(), 6);
        assert_eq!(face.fraction, [0.0, 0.5, 1.0, 0.0, 0.5, 1.0]);
        // the indicator's trapezoid rule: half of the middle strip and the last strip
        assert!((face.area - 1.5).abs() < 1e-15, "{}", face.area);
        assert!((face.face_area - 3.0).abs() < 1e-15);
        // a broken face is refused, not drawn
        assert!(SeparatedFace::new(&x1[..11], &x2[..11], &separated[..11]).is_err());
        assert!(SeparatedFace::new(&x1, &x2[..11], &separated).is_err());
    }
}
