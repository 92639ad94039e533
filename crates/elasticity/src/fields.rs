//! Output fields at the nodes: displacement, strain, stress, physical and Cartesian components.

use capstan_geometry::ShellPoint;

use crate::continuum::kinematics::{LocalDisplacement, strain};
use crate::error::ElasticityError;
use crate::grid::Grid;
use crate::shell_geometry::ShellGeometry;

/// Fields at the nodes of a grid (node number `i2 n3 + i3`, see [`Grid::node_index`]).
///
/// # Math
/// ```text
/// physical displacement   v<i>  = sqrt(g_ii) v^i           (no sum)
/// physical stress         T<ij> = sqrt(g_ii g_jj) T^ij
/// physical strain         E<ij> = E_ij / sqrt(g_ii g_jj)
/// Cartesian displacement  U     = v^2 g_2 + v^3 g_3
/// ```
/// The physical components are the components on the unit vectors `g_i / |g_i|`; on the
/// orthogonal shell charts of prisms (`g_23 = 0`) they are the usual engineering components.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct NodalFields {
    /// The grid.
    pub grid: Grid,
    /// `x2` of the nodes of column `i2` (the grid's uniform positions, or the high-order
    /// elements' Gauss–Lobatto–Legendre points).
    pub x2: Vec<f64>,
    /// `x3` of the nodes of row `i3`.
    pub x3: Vec<f64>,
    /// `[v^2, v^3]` (contravariant).
    pub displacement: Vec<[f64; 2]>,
    /// `E_kl` (covariant), indexed `[k][l]`.
    pub strain: Vec<[[f64; 3]; 3]>,
    /// `T^ij` (contravariant), indexed `[i][j]`.
    pub stress: Vec<[[f64; 3]; 3]>,
    /// `sqrt(g_ii)` for `i = 1, 2, 3`.
    pub scale: Vec<[f64; 3]>,
    /// The Cartesian displacement `U = v^i g_i`.
    pub cartesian_displacement: Vec<[f64; 3]>,
}

/// `sqrt(g_ii g_jj) T^ij`: physical components of a contravariant tensor, from the scales
/// `s[i] = sqrt(g_ii)`.
pub(crate) fn physical_stress(t: &[[f64; 3]; 3], s: [f64; 3]) -> [[f64; 3]; 3] {
    core::array::from_fn(|i| core::array::from_fn(|j| s[i] * s[j] * t[i][j]))
}

/// `E_ij / sqrt(g_ii g_jj)`: physical components of a covariant tensor, from the scales
/// `s[i] = sqrt(g_ii)`.
pub(crate) fn physical_strain(e: &[[f64; 3]; 3], s: [f64; 3]) -> [[f64; 3]; 3] {
    core::array::from_fn(|i| core::array::from_fn(|j| e[i][j] / (s[i] * s[j])))
}

impl NodalFields {
    /// Physical displacement components `[sqrt(g_22) v^2, sqrt(g_33) v^3]` at node `k`.
    pub fn physical_displacement(&self, k: usize) -> [f64; 2] {
        let (v, s) = (self.displacement[k], self.scale[k]);
        [s[1] * v[0], s[2] * v[1]]
    }

    /// Physical stress components `sqrt(g_ii g_jj) T^ij` at node `k`.
    pub fn physical_stress(&self, k: usize) -> [[f64; 3]; 3] {
        physical_stress(&self.stress[k], self.scale[k])
    }

    /// Physical strain components `E_ij / sqrt(g_ii g_jj)` at node `k`.
    pub fn physical_strain(&self, k: usize) -> [[f64; 3]; 3] {
        physical_strain(&self.strain[k], self.scale[k])
    }

    /// The fields of a plane-strain discretisation: at every node of `grid`, `local` gives the
    /// recovered displacement and its contravariant stress `T^ij` from the chart point;
    /// strain, scales and the Cartesian displacement follow from the chart.
    ///
    /// # Errors
    /// Geometry failures of the chart; whatever `local` returns.
    pub fn from_nodes<G: ShellGeometry>(
        grid: Grid,
        chart: &G,
        local: impl FnMut(
            [usize; 2],
            &ShellPoint<f64>,
        ) -> Result<(LocalDisplacement, [[f64; 3]; 3]), ElasticityError>,
    ) -> Result<Self, ElasticityError> {
        Self::from_nodes_at(grid, |node| grid.coordinates(node), chart, local)
    }

    /// [`NodalFields::from_nodes`] for nodes of `grid`'s numbering placed at `position(node)`
    /// (the high-order elements' nodes are not uniformly spaced).
    ///
    /// # Errors
    /// Geometry failures of the chart; whatever `local` returns.
    pub(crate) fn from_nodes_at<G: ShellGeometry>(
        grid: Grid,
        position: impl Fn([usize; 2]) -> [f64; 2],
        chart: &G,
        mut local: impl FnMut(
            [usize; 2],
            &ShellPoint<f64>,
        ) -> Result<(LocalDisplacement, [[f64; 3]; 3]), ElasticityError>,
    ) -> Result<Self, ElasticityError> {
        let n = grid.node_count();
        let mut out = Self {
            x2: (0..grid.n2()).map(|i| position([i, 0])[0]).collect(),
            x3: (0..grid.n3()).map(|j| position([0, j])[1]).collect(),
            grid,
            displacement: Vec::with_capacity(n),
            strain: Vec::with_capacity(n),
            stress: Vec::with_capacity(n),
            scale: Vec::with_capacity(n),
            cartesian_displacement: Vec::with_capacity(n),
        };
        for k in 0..n {
            let node = grid.node(k);
            let [x2, x3] = position(node);
            let p = chart.shell_point([0.0, x2, x3])?;
            let (u, stress) = local(node, &p)?;
            out.displacement.push(u.value);
            out.strain.push(strain(&p, &u));
            out.stress.push(stress);
            out.scale.push([0, 1, 2].map(|i| p.metric[i][i].sqrt()));
            let g = &p.covariant_basis;
            out.cartesian_displacement
                .push([0, 1, 2].map(|a| u.value[0] * g[1][a] + u.value[1] * g[2][a]));
        }
        Ok(out)
    }
}
