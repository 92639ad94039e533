//! What outputs read of the 3-D corner-refined body ([`SolidCornerNavier`]): the nodal
//! fields recovered from the element polynomials and the mesh as linear sub-hexahedra
//! ([`SolidOutput`]).

use rayon::prelude::*;

use super::corner::SolidCornerNavier;
use super::fields::{SolidFields, SolidOutput, SolidOutputMesh};
use super::grid::BoxGrid;
use super::setup::COMPONENTS;
use crate::error::ElasticityError;
use crate::shell_geometry::ShellGeometry;

/// Elements whose node gradients are held at once while recovering the nodal fields.
const ELEMENT_BLOCK: usize = 512;

impl<G: ShellGeometry + Sync> SolidCornerNavier<G> {
    /// The nodal fields of the solution `v` (see [`SolidFields`]), in the node order
    /// `i1 N + m` of the operator.
    ///
    /// # Math
    /// The physical gradient of the element polynomial at the node, averaged over the
    /// hexahedra holding it:
    /// ```text
    /// d_q v^c(node) = (1 / |E|) sum_(e in E) sum_b d_q N_b^e(node) v^c_b     E: the elements holding the node
    /// ```
    /// then the strain and the stress of [`SolidFields`]. Tangential derivatives are
    /// continuous across element faces, so on the tensor grid (`layers = 0`) this is the
    /// line average of the `fem-qp` body's recovery ([`super::SolidNavier::fields`]).
    ///
    /// # Errors
    /// [`ElasticityError::DimensionMismatch`] for a wrong length; geometry failures.
    pub fn fields(&self, v: &[f64]) -> Result<SolidFields, ElasticityError> {
        let mesh = &self.mesh;
        ElasticityError::check_length("displacement", self.dof_count(), v.len())?;
        let n = mesh.node_count();
        let np = mesh.gll.len();
        let nen = np * np * np;
        // sum of the element gradients [d_q v^c] (index 3 q + c) and their count, per node
        let mut sums = vec![[0.0; 9]; n];
        let mut counts = vec![0u32; n];
        let elements = mesh.element_count();
        for start in (0..elements).step_by(ELEMENT_BLOCK) {
            let block: Vec<(Vec<usize>, Vec<[f64; 9]>)> = (start
                ..(start + ELEMENT_BLOCK).min(elements))
                .into_par_iter()
                .map(|e| {
                    let nodes = mesh.element_nodes(e);
                    let mut grads = vec![[0.0; 9]; nen];
                    for (a, grad) in grads.iter_mut().enumerate() {
                        let xi = [
                            mesh.gll[a / (np * np)],
                            mesh.gll[(a / np) % np],
                            mesh.gll[a % np],
                        ];
                        let (phi, _, _) = mesh.shape_at(e, xi);
                        for (f, &m) in phi.iter().zip(&nodes) {
                            for q in 0..3 {
                                for c in 0..COMPONENTS {
                                    grad[3 * q + c] += f[1 + q] * v[COMPONENTS * m + c];
                                }
                            }
                        }
                    }
                    (nodes, grads)
                })
                .collect();
            for (nodes, grads) in block {
                for (&m, g) in nodes.iter().zip(&grads) {
                    counts[m] += 1;
                    for (s, x) in sums[m].iter_mut().zip(g) {
                        *s += x;
                    }
                }
            }
        }
        let mut out = SolidFields::with_capacity(n);
        for m in 0..n {
            let p = mesh.point(mesh.node_position(m))?;
            let mut u = [0.0; 12];
            for c in 0..COMPONENTS {
                u[c] = v[COMPONENTS * m + c];
            }
            let share = 1.0 / f64::from(counts[m].max(1));
            for (k, s) in sums[m].iter().enumerate() {
                u[3 + k] = s * share;
            }
            out.push_node(&p, u, self.material());
        }
        Ok(out)
    }

    /// The mesh as linear hexahedra: every Qp hexahedron as its `p^3` sub-hexahedra between
    /// GLL nodes, in VTK's order (the quad `(xi2, xi3)` at the lower `xi1`, then at the upper
    /// one; positive volume where `det J > 0`, as everywhere in the mesh).
    pub fn output_hexahedra(&self) -> Vec<[usize; 8]> {
        let mesh = &self.mesh;
        let np = mesh.gll.len();
        let p = np - 1;
        let index = |a1: usize, a2: usize, a3: usize| (a1 * np + a2) * np + a3;
        let mut out = Vec::with_capacity(mesh.element_count() * p * p * p);
        for e in 0..mesh.element_count() {
            let nodes = mesh.element_nodes(e);
            for a1 in 0..p {
                for a2 in 0..p {
                    for a3 in 0..p {
                        let quad = |b1: usize| {
                            [
                                nodes[index(b1, a2, a3)],
                                nodes[index(b1, a2 + 1, a3)],
                                nodes[index(b1, a2 + 1, a3 + 1)],
                                nodes[index(b1, a2, a3 + 1)],
                            ]
                        };
                        let (lo, hi) = (quad(a1), quad(a1 + 1));
                        out.push([lo[0], lo[1], lo[2], lo[3], hi[0], hi[1], hi[2], hi[3]]);
                    }
                }
            }
        }
        out
    }
}

impl<G: ShellGeometry + Sync> SolidOutput for SolidCornerNavier<G> {
    /// The box the mesh fills (not the nodes: [`SolidOutput::output_mesh`]).
    fn box_grid(&self) -> &BoxGrid {
        SolidCornerNavier::box_grid(self)
    }

    fn nodal_fields(&self, v: &[f64]) -> Result<SolidFields, ElasticityError> {
        self.fields(v)
    }

    fn output_mesh(&self) -> Option<SolidOutputMesh> {
        Some(SolidOutputMesh {
            nodes: (0..self.node_count())
                .map(|m| self.node_position(m))
                .collect(),
            hexahedra: self.output_hexahedra(),
        })
    }
}
