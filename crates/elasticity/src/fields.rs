//! Output fields at the nodes: displacement, strain, stress, physical and Cartesian components.

use crate::grid::Grid;

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

impl NodalFields {
    /// Physical displacement components `[sqrt(g_22) v^2, sqrt(g_33) v^3]` at node `k`.
    pub fn physical_displacement(&self, k: usize) -> [f64; 2] {
        let (v, s) = (self.displacement[k], self.scale[k]);
        [s[1] * v[0], s[2] * v[1]]
    }

    /// Physical stress components `sqrt(g_ii g_jj) T^ij` at node `k`.
    pub fn physical_stress(&self, k: usize) -> [[f64; 3]; 3] {
        let (t, s) = (&self.stress[k], self.scale[k]);
        core::array::from_fn(|i| core::array::from_fn(|j| s[i] * s[j] * t[i][j]))
    }

    /// Physical strain components `E_ij / sqrt(g_ii g_jj)` at node `k`.
    pub fn physical_strain(&self, k: usize) -> [[f64; 3]; 3] {
        let (e, s) = (&self.strain[k], self.scale[k]);
        core::array::from_fn(|i| core::array::from_fn(|j| e[i][j] / (s[i] * s[j])))
    }
}
