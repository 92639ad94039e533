//! The structured grid a VTU file is written on: quads of a 2-D body, hexahedra of a layered
//! (3-D) body, with the covariant bases at the nodes for Cartesian vectors.

use capstan_geometry::{ShellChart, Surface};

use super::error::{OutputError, check_all_finite};

/// VTK's cell type number for a 4-node quadrilateral.
pub const VTK_QUAD: u8 = 9;

/// VTK cell type of a linear hexahedron (bottom quad, then the top quad above it).
pub const VTK_HEXAHEDRON: u8 = 12;

/// A structured `n2 x n3` grid of points in E^3, written as quads.
///
/// Node `k = i2 n3 + i3` (`x3` fastest), the numbering of the elasticity crate's grid, so
/// nodal fields pass through unchanged. Cell `c = i2 (n3 - 1) + i3` has the nodes
/// `(i2, i3), (i2 + 1, i3), (i2 + 1, i3 + 1), (i2, i3 + 1)`; on a periodic grid `i2 + 1`
/// wraps to 0, so a full wrap closes without a seam (and has `n2` cells in `x2`, not `n2 - 1`).
///
/// # Example
/// ```
/// use capstan::geometry::{EllipticalPrism, ShellChart};
/// use capstan::output::QuadGrid;
/// let chart = ShellChart::new(EllipticalPrism::new(2.0, 1.0).unwrap());
/// let grid = QuadGrid::from_chart(&chart, 0.0, &[0.0, 0.5, 1.0], &[0.0, 0.1], false).unwrap();
/// assert_eq!((grid.node_count(), grid.cell_count()), (6, 2));
/// // sigma = (x1, a sin t, b cos t); x3 moves along the outward normal
/// assert_eq!(grid.points()[0], [0.0, 0.0, 1.0]);
/// assert!((grid.points()[1][2] - 1.1).abs() < 1e-14);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct QuadGrid {
    /// Layers in `x1`: 1 for a quad grid, `n1 >= 2` for the hexahedra of a 3-D body.
    n1: usize,
    n2: usize,
    n3: usize,
    periodic: bool,
    points: Vec<[f64; 3]>,
    bases: Option<Vec<[[f64; 3]; 3]>>,
    /// The hexahedra of an unstructured grid ([`QuadGrid::hexahedra`]); `None`: structured.
    hexahedra: Option<Vec<[usize; 8]>>,
}

impl QuadGrid {
    /// A grid from its points, `points[i2 * n3 + i3]`.
    ///
    /// # Errors
    /// [`OutputError::InvalidParameter`] for `n2 < 2` (`< 3` when periodic) or `n3 < 2`;
    /// [`OutputError::LengthMismatch`] unless there are `n2 n3` points;
    /// [`OutputError::NonFinite`] for a non-finite coordinate.
    pub fn new(
        n2: usize,
        n3: usize,
        periodic: bool,
        points: Vec<[f64; 3]>,
    ) -> Result<Self, OutputError> {
        let min2 = if periodic { 3 } else { 2 };
        if n2 < min2 {
            return Err(OutputError::InvalidParameter {
                field: "n2",
                value: n2 as f64,
                allowed: if periodic { "[3, inf)" } else { "[2, inf)" },
            });
        }
        if n3 < 2 {
            return Err(OutputError::InvalidParameter {
                field: "n3",
                value: n3 as f64,
                allowed: "[2, inf)",
            });
        }
        if points.len() != n2 * n3 {
            return Err(OutputError::LengthMismatch {
                column: "points".to_owned(),
                expected: n2 * n3,
                found: points.len(),
            });
        }
        check_all_finite("points", points.as_flattened())?;
        Ok(Self {
            n1: 1,
            n2,
            n3,
            periodic,
            points,
            bases: None,
            hexahedra: None,
        })
    }

    /// An unstructured grid of linear hexahedra on `points` (a 3-D body on a mesh: node `k`
    /// at `points[k]`, each cell in VTK's hexahedron order), with the covariant bases at the
    /// nodes when given (for [`QuadGrid::to_cartesian`]). Its `n1`, `n2`, `n3` are 0.
    ///
    /// # Errors
    /// [`OutputError::InvalidParameter`] for no cells or a node number out of range;
    /// [`OutputError::LengthMismatch`] unless there is one basis per point;
    /// [`OutputError::NonFinite`] for a non-finite coordinate.
    pub fn hexahedra(
        points: Vec<[f64; 3]>,
        bases: Option<Vec<[[f64; 3]; 3]>>,
        cells: Vec<[usize; 8]>,
    ) -> Result<Self, OutputError> {
        let n = points.len();
        if cells.is_empty() || cells.iter().flatten().any(|&k| k >= n) {
            return Err(OutputError::InvalidParameter {
                field: "hexahedra",
                value: cells.len() as f64,
                allowed: "at least one cell, node numbers below the number of points",
            });
        }
        if let Some(b) = &bases
            && b.len() != n
        {
            return Err(OutputError::LengthMismatch {
                column: "bases".to_owned(),
                expected: n,
                found: b.len(),
            });
        }
        check_all_finite("points", points.as_flattened())?;
        Ok(Self {
            n1: 0,
            n2: 0,
            n3: 0,
            periodic: false,
            points,
            bases,
            hexahedra: Some(cells),
        })
    }

    /// Whether the grid is an unstructured one of [`QuadGrid::hexahedra`] (no `(i1, i2, i3)`
    /// numbering).
    pub fn is_unstructured(&self) -> bool {
        self.hexahedra.is_some()
    }

    /// The grid `Theta(x1, x2[i2], x3[i3])` of a shell chart, keeping the covariant bases
    /// `g_i` at the nodes for [`QuadGrid::to_cartesian`].
    ///
    /// For a periodic grid, `x2` lists the distinct nodes of one period (the last is not
    /// repeated).
    ///
    /// # Errors
    /// [`OutputError::Geometry`] if the chart fails at a node (for example `x3` past the
    /// focal surface); otherwise as [`QuadGrid::new`].
    pub fn from_chart<S: Surface<f64>>(
        chart: &ShellChart<S>,
        x1: f64,
        x2: &[f64],
        x3: &[f64],
        periodic: bool,
    ) -> Result<Self, OutputError> {
        let mut points = Vec::with_capacity(x2.len() * x3.len());
        let mut bases = Vec::with_capacity(points.capacity());
        for &t in x2 {
            for &h in x3 {
                let p = chart.point([x1, t, h])?;
                points.push(p.position);
                bases.push(p.covariant_basis);
            }
        }
        let mut grid = Self::new(x2.len(), x3.len(), periodic, points)?;
        grid.bases = Some(bases);
        Ok(grid)
    }

    /// The hexahedra between consecutive `layers` (quad grids of the same shape at increasing
    /// `x1`, e.g. [`QuadGrid::from_chart`] at each `x1` node of a 3-D body): nodes
    /// `(i1 n2 + i2) n3 + i3`, cell `(i1, i2, i3)` the quad `(i2, i3)` of layer `i1` and the
    /// same quad of layer `i1 + 1` (VTK's hexahedron order). Bases are kept if every layer has
    /// them.
    ///
    /// # Errors
    /// [`OutputError::InvalidParameter`] for fewer than two layers, layers of different
    /// shapes or layers that are themselves layered.
    pub fn layered(layers: Vec<QuadGrid>) -> Result<Self, OutputError> {
        let Some(first) = layers.first() else {
            return Err(OutputError::InvalidParameter {
                field: "layers",
                value: 0.0,
                allowed: "[2, inf)",
            });
        };
        let (n2, n3, periodic) = (first.n2, first.n3, first.periodic);
        if layers.len() < 2 {
            return Err(OutputError::InvalidParameter {
                field: "layers",
                value: layers.len() as f64,
                allowed: "[2, inf)",
            });
        }
        if layers.iter().any(|l| {
            l.is_unstructured() || l.n1 != 1 || l.n2 != n2 || l.n3 != n3 || l.periodic != periodic
        }) {
            return Err(OutputError::InvalidParameter {
                field: "layers",
                value: layers.len() as f64,
                allowed: "quad grids of one shape",
            });
        }
        let bases = layers
            .iter()
            .map(|l| l.bases.clone())
            .collect::<Option<Vec<_>>>()
            .map(|b| b.concat());
        Ok(Self {
            n1: layers.len(),
            n2,
            n3,
            periodic,
            points: layers
                .iter()
                .flat_map(|l| l.points.iter().copied())
                .collect(),
            bases,
            hexahedra: None,
        })
    }

    /// Layers in `x1` (1 for a quad grid).
    pub fn n1(&self) -> usize {
        self.n1
    }

    /// Nodes in `x2`.
    pub fn n2(&self) -> usize {
        self.n2
    }

    /// Nodes in `x3`.
    pub fn n3(&self) -> usize {
        self.n3
    }

    /// Whether `x2` wraps around.
    pub fn is_periodic(&self) -> bool {
        self.periodic
    }

    /// Number of nodes, `n1 n2 n3` (the points of an unstructured grid).
    pub fn node_count(&self) -> usize {
        self.points.len()
    }

    /// Cells in `x2`: `n2` when periodic, `n2 - 1` otherwise.
    fn cells2(&self) -> usize {
        if self.periodic { self.n2 } else { self.n2 - 1 }
    }

    /// Number of cells: quads, or hexahedra of a layered or an unstructured grid.
    pub fn cell_count(&self) -> usize {
        if let Some(h) = &self.hexahedra {
            return h.len();
        }
        self.cells2() * (self.n3 - 1) * (self.n1 - 1).max(1)
    }

    /// The points, `points()[i2 * n3 + i3]`.
    pub fn points(&self) -> &[[f64; 3]] {
        &self.points
    }

    /// The VTK cells: connectivity, nodes per cell and cell type (quads, or the hexahedra of a
    /// layered grid, in the order `(i1, i2, i3)`).
    pub fn topology(&self) -> (Vec<usize>, usize, u8) {
        if let Some(h) = &self.hexahedra {
            return (h.as_flattened().to_vec(), 8, VTK_HEXAHEDRON);
        }
        let quads = self.cells();
        if self.n1 == 1 {
            return (quads.into_iter().flatten().collect(), 4, VTK_QUAD);
        }
        let layer = self.n2 * self.n3;
        let mut connectivity = Vec::with_capacity(8 * self.cell_count());
        for i1 in 0..self.n1 - 1 {
            for q in &quads {
                connectivity.extend(q.iter().map(|k| i1 * layer + k));
                connectivity.extend(q.iter().map(|k| (i1 + 1) * layer + k));
            }
        }
        (connectivity, 8, VTK_HEXAHEDRON)
    }

    /// The node numbers of every quad cell, in cell order (see the type's docs); of one layer
    /// for a layered grid; none for an unstructured grid.
    pub fn cells(&self) -> Vec<[usize; 4]> {
        if self.is_unstructured() {
            return Vec::new();
        }
        let (n2, n3) = (self.n2, self.n3);
        let mut cells = Vec::with_capacity(self.cell_count());
        for i2 in 0..self.cells2() {
            let j2 = (i2 + 1) % n2;
            for i3 in 0..n3 - 1 {
                cells.push([
                    i2 * n3 + i3,
                    j2 * n3 + i3,
                    j2 * n3 + i3 + 1,
                    i2 * n3 + i3 + 1,
                ]);
            }
        }
        cells
    }

    /// Cartesian vectors `v = v^i g_i` from contravariant components `v^i` at the nodes
    /// (displacements, tractions), for a grid built by [`QuadGrid::from_chart`].
    ///
    /// # Errors
    /// [`OutputError::LengthMismatch`] unless there is one vector per node;
    /// [`OutputError::InvalidParameter`] for a grid built from bare points (no bases).
    pub fn to_cartesian(&self, contravariant: &[[f64; 3]]) -> Result<Vec<[f64; 3]>, OutputError> {
        let Some(bases) = &self.bases else {
            return Err(OutputError::InvalidParameter {
                field: "QuadGrid bases",
                value: 0.0,
                allowed: "a grid built by QuadGrid::from_chart",
            });
        };
        if contravariant.len() != bases.len() {
            return Err(OutputError::LengthMismatch {
                column: "contravariant components".to_owned(),
                expected: bases.len(),
                found: contravariant.len(),
            });
        }
        Ok(contravariant
            .iter()
            .zip(bases)
            .map(|(v, g)| std::array::from_fn(|k| v[0] * g[0][k] + v[1] * g[1][k] + v[2] * g[2][k]))
            .collect())
    }
}
