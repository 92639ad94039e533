//! Nodal fields of a 3-D body: displacement, strain and stress at every node, recovered by
//! the contact rows' stencil everywhere (Q1/Q2: second-order differences of the nodal values;
//! Qp: the element polynomials).

use super::grid::BoxGrid;
use super::matrix_free::SolidMatrixFree;
use super::operator::SolidNavier;
use super::setup::SolidSetup;
use crate::continuum::{SOLID, mixed_strains};
use crate::error::ElasticityError;
use crate::shell_geometry::ShellGeometry;

/// Displacement, strain and stress at the nodes of a 3-D body (node order of
/// [`super::BoxGrid::node_index`]).
///
/// # Math
/// With the twelve inputs `u = [v^c, d_p v^c]` at a node (the recovery stencil of the nodal
/// values, at the node's true position)
/// and the mixed strains `M_k` of the unit inputs ([`crate::continuum::mixed_strains`]):
/// ```text
/// E^i_j = sum_k u_k M_k[i][j],  E_ij = g_im E^m_j
/// T^i_j = lambda delta^i_j E^m_m + 2 mu E^i_j,  T^ij = T^i_m g^mj
/// physical: sqrt(g_ii) v^i,  sqrt(g_ii g_jj) T^ij,  E_ij / sqrt(g_ii g_jj)
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct SolidFields {
    /// Contravariant displacement `[v^1, v^2, v^3]`.
    pub displacement: Vec<[f64; 3]>,
    /// Cartesian displacement `v^i g_i`.
    pub cartesian_displacement: Vec<[f64; 3]>,
    /// Contravariant stress `T^ij`.
    pub stress: Vec<[[f64; 3]; 3]>,
    /// Covariant strain `E_ij`.
    pub strain: Vec<[[f64; 3]; 3]>,
    /// `sqrt(g_ii)` per node: the physical scales.
    pub scale: Vec<[f64; 3]>,
}

impl SolidFields {
    /// Physical displacement `sqrt(g_ii) v^i` at node `k`.
    pub fn physical_displacement(&self, k: usize) -> [f64; 3] {
        let (v, s) = (self.displacement[k], self.scale[k]);
        core::array::from_fn(|i| s[i] * v[i])
    }

    /// Physical stress `sqrt(g_ii g_jj) T^ij` at node `k`.
    pub fn physical_stress(&self, k: usize) -> [[f64; 3]; 3] {
        crate::fields::physical_stress(&self.stress[k], self.scale[k])
    }

    /// Physical strain `E_ij / sqrt(g_ii g_jj)` at node `k`.
    pub fn physical_strain(&self, k: usize) -> [[f64; 3]; 3] {
        crate::fields::physical_strain(&self.strain[k], self.scale[k])
    }
}

/// What outputs read of a 3-D body's operator, whatever its chart: the box grid of its nodes
/// and the nodal fields of a solution. A [`crate::contact::BodyOperator`] of a 3-D body gives it
/// through [`crate::contact::ContactOperator::solid`].
pub trait SolidOutput {
    /// The box grid of the nodes ([`SolidNavier::grid`]).
    fn box_grid(&self) -> &BoxGrid;
    /// The nodal fields of the solution `v` ([`SolidNavier::fields`]).
    ///
    /// # Errors
    /// As [`SolidNavier::fields`].
    fn nodal_fields(&self, v: &[f64]) -> Result<SolidFields, ElasticityError>;
    /// The nodes and hexahedra of the output when they are not the box grid's tensor
    /// product (a mesh discretisation: [`super::SolidCornerNavier`]); `None` (the default):
    /// the nodes of [`SolidOutput::box_grid`] in its node order, its hexahedra.
    fn output_mesh(&self) -> Option<SolidOutputMesh> {
        None
    }
}

/// The nodes and linear hexahedra of a 3-D body on a mesh, for outputs: node `k` of
/// [`SolidOutput::nodal_fields`] is at the parameters `nodes[k] = (x1, x2, x3)`, and a Qp
/// hexahedron of order `p` is written as its `p^3` linear sub-hexahedra between GLL nodes.
#[derive(Debug, Clone, PartialEq)]
pub struct SolidOutputMesh {
    /// `(x1, x2, x3)` of every node.
    pub nodes: Vec<[f64; 3]>,
    /// The linear hexahedra, in VTK's order: the quad `(x2, x3)` counter-clockwise at the
    /// lower `x1`, then the same quad at the upper `x1` (the order of the box grid's
    /// hexahedra).
    pub hexahedra: Vec<[usize; 8]>,
}

impl<G: ShellGeometry + Sync> SolidOutput for SolidNavier<G> {
    fn box_grid(&self) -> &BoxGrid {
        self.grid()
    }

    fn nodal_fields(&self, v: &[f64]) -> Result<SolidFields, ElasticityError> {
        self.fields(v)
    }
}

impl<G: ShellGeometry + Sync> SolidNavier<G> {
    /// The nodal fields of the solution `v` (see [`SolidFields`]).
    ///
    /// # Errors
    /// [`ElasticityError::DimensionMismatch`] for a wrong length; geometry failures.
    pub fn fields(&self, v: &[f64]) -> Result<SolidFields, ElasticityError> {
        self.setup.fields(v)
    }
}

impl<G: ShellGeometry + Sync> SolidOutput for SolidMatrixFree<G> {
    fn box_grid(&self) -> &BoxGrid {
        self.grid()
    }

    fn nodal_fields(&self, v: &[f64]) -> Result<SolidFields, ElasticityError> {
        self.setup.fields(v)
    }
}

impl<G: ShellGeometry + Sync> SolidSetup<G> {
    /// The nodal fields of the solution `v` (see [`SolidFields`]).
    ///
    /// # Errors
    /// [`ElasticityError::DimensionMismatch`] for a wrong length; geometry failures.
    pub(crate) fn fields(&self, v: &[f64]) -> Result<SolidFields, ElasticityError> {
        ElasticityError::check_length("displacement", self.dof_count(), v.len())?;
        let n = self.grid.node_count();
        let mut out = SolidFields::with_capacity(n);
        for m in 0..n {
            let node = self.grid.node(m);
            let p = self.chart.shell_point(self.grid.coordinates(node))?;
            let value: [f64; 3] = core::array::from_fn(|c| v[3 * m + c]);
            // u = [v^c, d_p v^c] (input 3 + 3 p + c)
            let mut u = [0.0; 12];
            u[..3].copy_from_slice(&value);
            for (at, w) in self.node_stencil(node) {
                let k = 3 * self.grid.node_index(at);
                for q in 0..3 {
                    for c in 0..3 {
                        u[3 + 3 * q + c] += w[1 + q] * v[k + c];
                    }
                }
            }
            out.push_node(&p, u, self.material);
        }
        Ok(out)
    }
}

impl SolidFields {
    /// An empty set of fields for `n` nodes.
    pub(crate) fn with_capacity(n: usize) -> Self {
        Self {
            displacement: Vec::with_capacity(n),
            cartesian_displacement: Vec::with_capacity(n),
            stress: Vec::with_capacity(n),
            strain: Vec::with_capacity(n),
            scale: Vec::with_capacity(n),
        }
    }

    /// Appends the fields of a node at the chart point `p` from its twelve inputs
    /// `u = [v^c, d_p v^c]` (input `3 + 3 p + c`), by the formulas of [`SolidFields`].
    #[allow(clippy::needless_range_loop)] // index loops mirror the tensor formulas
    pub(crate) fn push_node(
        &mut self,
        p: &capstan_geometry::ShellPoint<f64>,
        u: [f64; 12],
        material: crate::material::Material,
    ) {
        let (lambda, two_mu) = (material.lambda(), 2.0 * material.mu());
        let value: [f64; 3] = [u[0], u[1], u[2]];
        let strains = mixed_strains(p, &SOLID);
        let mut mixed = [[0.0; 3]; 3];
        for (mk, uk) in strains.iter().zip(&u) {
            for i in 0..3 {
                for j in 0..3 {
                    mixed[i][j] += uk * mk[i][j];
                }
            }
        }
        let trace = mixed[0][0] + mixed[1][1] + mixed[2][2];
        let (g, gi) = (&p.metric, &p.inverse_metric);
        let mut strain = [[0.0; 3]; 3];
        let mut stress = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                strain[i][j] = (0..3).map(|k| g[i][k] * mixed[k][j]).sum();
                stress[i][j] = (0..3)
                    .map(|k| {
                        let t = if i == k { lambda * trace } else { 0.0 } + two_mu * mixed[i][k];
                        t * gi[k][j]
                    })
                    .sum();
            }
        }
        let basis = &p.covariant_basis;
        self.cartesian_displacement.push(core::array::from_fn(|a| {
            (0..3).map(|i| value[i] * basis[i][a]).sum()
        }));
        self.scale.push(core::array::from_fn(|i| g[i][i].sqrt()));
        self.displacement.push(value);
        self.strain.push(strain);
        self.stress.push(stress);
    }
}
