//! The thick body's fields as files a researcher can open: a VTU on the curved body, colour
//! maps of the displacement and the stick/slip strip along the contact surface.
//!
//! Shared by `capstan contact --out`, `capstan sweep --out` (one VTU per point plus a `.pvd`)
//! and `capstan figure`.

use capstan_elasticity::NodalFields;
use capstan_elasticity::contact::ContactProfile;
use capstan_elasticity::solid::SolidFields;
use capstan_geometry::{Obstacle, ShellChart};

use crate::output::{ColourMap, OutputDir, OutputError, QuadGrid, StateStrip, Vtu, VtuCompression};

/// Names of the VTU point arrays written by [`body_vtu`], with their component counts
/// (a public contract, documented in `docs/guide.md`).
pub const VTU_ARRAYS: [(&str, usize); 11] = [
    ("displacement", 3),
    ("displacement_contravariant", 3),
    ("displacement_physical", 3),
    ("stress", 9),
    ("stress_physical", 9),
    ("strain", 9),
    ("strain_physical", 9),
    ("contact_state", 1),
    ("contact_slip", 1),
    ("x2", 1),
    ("x3", 1),
];

/// The body's nodes as quads in E^3: `Theta(0, x2, x3)` of the obstacle's shell chart.
///
/// # Errors
/// Geometry failures at a node; a grid too small for quads.
pub fn body_grid(obstacle: &Obstacle, fields: &NodalFields) -> Result<QuadGrid, OutputError> {
    let periodic = fields.grid.is_periodic();
    QuadGrid::from_chart(
        &ShellChart::new(obstacle),
        0.0,
        &fields.x2,
        &fields.x3,
        periodic,
    )
}

/// The contact state and physical slip of the contact node in each node's `x2` column
/// (`0` where the column has no contact node, e.g. a Dirichlet end).
fn column_contact(fields: &NodalFields, contact: &ContactProfile) -> (Vec<f64>, Vec<f64>) {
    let g = &fields.grid;
    let (n2, n3) = (g.n2(), g.n3());
    let mut state = vec![0.0; n2];
    let mut slip = vec![0.0; n2];
    // the column at the contact node's x2 (columns in increasing x2; the nearest one, as the
    // node positions of the high-order elements are not uniform)
    let column = |x: f64| -> Option<usize> {
        let i = fields.x2.partition_point(|&c| c < x);
        let near = [i.checked_sub(1), (i < n2).then_some(i)];
        near.into_iter()
            .flatten()
            .min_by(|&a, &b| {
                (fields.x2[a] - x)
                    .abs()
                    .total_cmp(&(fields.x2[b] - x).abs())
            })
            .filter(|&c| (fields.x2[c] - x).abs() <= 1e-9 * (1.0 + x.abs()))
    };
    for (k, &x) in contact.x2.iter().enumerate() {
        if let Some(i) = column(x) {
            state[i] = f64::from(contact.state[k]);
            slip[i] = contact.slip[k];
        }
    }
    let spread = |v: &[f64]| -> Vec<f64> { (0..n2 * n3).map(|node| v[node / n3]).collect() };
    (spread(&state), spread(&slip))
}

/// A VTU of the fields on `grid` (see [`VTU_ARRAYS`]): Cartesian, contravariant and physical
/// displacement (`v^1 = 0` on a prism), contravariant stress `T^ij` and covariant strain `E_ij`
/// with their physical components (row-major 3x3), the contact state `-1/0/+1` and physical
/// slip of the contact node in each `x2` column, and the parametric coordinates.
pub fn body_vtu<'g>(grid: &'g QuadGrid, fields: &NodalFields, contact: &ContactProfile) -> Vtu<'g> {
    let n = fields.displacement.len();
    let contravariant: Vec<[f64; 3]> = fields
        .displacement
        .iter()
        .map(|v| [0.0, v[0], v[1]])
        .collect();
    let physical: Vec<[f64; 3]> = (0..n)
        .map(|k| {
            let p = fields.physical_displacement(k);
            [0.0, p[0], p[1]]
        })
        .collect();
    let (state, slip) = column_contact(fields, contact);
    let g = &fields.grid;
    let x2: Vec<f64> = (0..n).map(|k| fields.x2[g.node(k)[0]]).collect();
    let x3: Vec<f64> = (0..n).map(|k| fields.x3[g.node(k)[1]]).collect();
    body_arrays_vtu(
        grid,
        [&fields.cartesian_displacement, &contravariant, &physical],
        fields,
        [state, slip, x2, x3],
    )
}

/// The nodal tensors a body VTU shows, of a plane-strain ([`NodalFields`]) or a 3-D
/// ([`SolidFields`]) body.
pub(crate) trait NodalTensors {
    /// `[T^ij, E_ij]` at every node: the contravariant stress and the covariant strain.
    fn tensors(&self) -> [&[[[f64; 3]; 3]]; 2];
    /// Their physical components at node `k`: `[sqrt(g_ii g_jj) T^ij, E_ij / sqrt(g_ii g_jj)]`.
    fn physical_tensors(&self, k: usize) -> [[[f64; 3]; 3]; 2];
}

impl NodalTensors for NodalFields {
    fn tensors(&self) -> [&[[[f64; 3]; 3]]; 2] {
        [&self.stress, &self.strain]
    }
    fn physical_tensors(&self, k: usize) -> [[[f64; 3]; 3]; 2] {
        [self.physical_stress(k), self.physical_strain(k)]
    }
}

impl NodalTensors for SolidFields {
    fn tensors(&self) -> [&[[[f64; 3]; 3]]; 2] {
        [&self.stress, &self.strain]
    }
    fn physical_tensors(&self, k: usize) -> [[[f64; 3]; 3]; 2] {
        [self.physical_stress(k), self.physical_strain(k)]
    }
}

/// The arrays of [`VTU_ARRAYS`] on `grid`, one entry per node: `displacement` as
/// `[Cartesian, contravariant, physical]` components, the stress and strain of `fields` with
/// their physical components, and `scalars` = `[contact_state, contact_slip, x2, x3]`; the
/// contact state and the Cartesian displacement are the active arrays.
pub(crate) fn body_arrays_vtu<'g>(
    grid: &'g QuadGrid,
    displacement: [&[[f64; 3]]; 3],
    fields: &impl NodalTensors,
    scalars: [Vec<f64>; 4],
) -> Vtu<'g> {
    let [stress, strain] = fields.tensors();
    let (stress_physical, strain_physical): (Vec<_>, Vec<_>) = (0..stress.len())
        .map(|k| {
            let [t, e] = fields.physical_tensors(k);
            (t, e)
        })
        .unzip();
    let [state, slip, x2, x3] = scalars;
    Vtu::new(grid)
        .point_vectors("displacement", displacement[0])
        .point_vectors("displacement_contravariant", displacement[1])
        .point_vectors("displacement_physical", displacement[2])
        .point_tensors("stress", stress)
        .point_tensors("stress_physical", &stress_physical)
        .point_tensors("strain", strain)
        .point_tensors("strain_physical", &strain_physical)
        .point_scalars("contact_state", state)
        .point_scalars("contact_slip", slip)
        .point_scalars("x2", x2)
        .point_scalars("x3", x3)
        .active_scalars("contact_state")
        .active_vectors("displacement")
}

/// The obstacle surface beside the body: `sigma(x1, x2)` on a ribbon `|x1| <= h` (`h` the
/// body's thickness) over the body's `x2` span widened by a quarter on each side, as quads
/// (node `i2 n3 + i1`).
///
/// # Errors
/// Geometry failures (a non-finite point).
pub fn obstacle_grid(obstacle: &Obstacle, fields: &NodalFields) -> Result<QuadGrid, OutputError> {
    use capstan_geometry::Surface;
    let g = &fields.grid;
    let (a, b) = (g.x2(0), g.x2(g.n2() - 1));
    let (lo, hi) = (a - 0.25 * (b - a), b + 0.25 * (b - a));
    let h = (g.x3(g.n3() - 1) - g.x3(0)).abs().max(f64::MIN_POSITIVE);
    let (n2, n1) = (4 * g.n2().max(2), 3);
    let mut points = Vec::with_capacity(n2 * n1);
    for i in 0..n2 {
        let t = lo + (hi - lo) * i as f64 / (n2 - 1) as f64;
        for j in 0..n1 {
            let x1 = -h + 2.0 * h * j as f64 / (n1 - 1) as f64;
            points.push(Surface::<f64>::sigma(obstacle, [x1, t]));
        }
    }
    QuadGrid::new(n2, n1, false, points)
}

/// Colour maps of `v^2` (rad) and `v^3` on the curved body, seen along `x1` (axes y, z).
///
/// # Errors
/// Non-finite values.
pub fn displacement_maps(
    grid: &QuadGrid,
    fields: &NodalFields,
    title: &str,
) -> Result<[ColourMap; 2], OutputError> {
    let v2: Vec<f64> = fields.displacement.iter().map(|v| v[0]).collect();
    let v3: Vec<f64> = fields.displacement.iter().map(|v| v[1]).collect();
    Ok([
        ColourMap::nodal(
            format!("{title}: azimuthal displacement v^2"),
            grid,
            [1, 2],
            &v2,
        )?
        .label("v^2 (rad)"),
        ColourMap::nodal(
            format!("{title}: radial displacement v^3"),
            grid,
            [1, 2],
            &v3,
        )?
        .label("v^3 (m)"),
    ])
}

/// The contact states `-1/0/+1` as the integers of a CSV column or a strip.
pub fn contact_states(contact: &ContactProfile) -> Vec<i32> {
    contact.state.iter().map(|&s| i32::from(s)).collect()
}

/// The stick/slip state along the contact surface.
pub fn state_strip(contact: &ContactProfile, title: &str) -> StateStrip {
    StateStrip::new(title, contact.x2.clone(), contact_states(contact)).x_label("x2 = theta (rad)")
}

/// What [`write_body`] writes besides the VTU's fields.
#[derive(Debug, Clone, Copy)]
pub struct BodyFiles {
    /// The VTU's `TimeValue` (a sweep's value).
    pub time: Option<f64>,
    /// Also the plots `STEM_v2`, `STEM_v3`, `STEM_state`.
    pub plots: bool,
    /// How the VTU's arrays are encoded (`output.vtu_compression` of a scene).
    pub compression: VtuCompression,
    /// Also the obstacle as a second piece ([`obstacle_grid`]; `output.vtu_obstacle`).
    pub obstacle: bool,
}

/// Writes `STEM.vtu`, `STEM_v2.{svg,png}`, `STEM_v3.{svg,png}` and `STEM_state.{svg,png}`
/// into `out` (each atomically); `options.time` becomes the VTU's `TimeValue`; `options.compression` chooses
/// zlib compression, `options.obstacle` the obstacle as a second piece ([`obstacle_grid`]).
///
/// # Errors
/// Geometry or output errors.
pub fn write_body(
    out: &OutputDir,
    stem: &str,
    obstacle: &Obstacle,
    fields: &NodalFields,
    contact: &ContactProfile,
    options: BodyFiles,
) -> Result<(), OutputError> {
    let BodyFiles {
        time,
        plots,
        compression,
        obstacle: with_obstacle,
    } = options;
    let grid = body_grid(obstacle, fields)?;
    let ribbon = if with_obstacle {
        Some(obstacle_grid(obstacle, fields)?)
    } else {
        None
    };
    let mut vtu = body_vtu(&grid, fields, contact).encoding(compression.encoding());
    if let Some(r) = &ribbon {
        vtu = vtu.second_piece(r);
    }
    if let Some(t) = time {
        vtu = vtu.time(t);
    }
    out.write_vtu(&format!("{stem}.vtu"), &vtu)?;
    if plots {
        let [v2, v3] = displacement_maps(&grid, fields, "Thick body")?;
        out.write_plot(&format!("{stem}_v2"), &v2)?;
        out.write_plot(&format!("{stem}_v3"), &v3)?;
        out.write_plot(
            &format!("{stem}_state"),
            &state_strip(contact, "Stick and slip along the contact surface"),
        )?;
    }
    Ok(())
}
