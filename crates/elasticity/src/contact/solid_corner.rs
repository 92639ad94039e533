//! The 3-D corner-refined body ([`SolidCornerNavier`]) as a [`ContactOperator`]: its
//! contact face `x3 = 0` by `x1` line and in `x2` order, two tangential entries per node.

use crate::contact::operator::{ContactOperator, Extremum, extremum};
use crate::continuum::{SOLID, mixed_strains};
use crate::discretisation::{ContactNode, LinearSystem, SparseRow};
use crate::error::ElasticityError;
use crate::shell_geometry::ShellGeometry;
use crate::solid::SolidCornerNavier;

impl<G: ShellGeometry + Sync> ContactOperator for SolidCornerNavier<G> {
    fn method(&self) -> &'static str {
        "solid-qp-corner"
    }

    fn dof_count(&self) -> usize {
        SolidCornerNavier::dof_count(self)
    }

    fn contact_system(&self) -> Result<LinearSystem, ElasticityError> {
        Ok(self.system().clone())
    }

    /// The entries `v^1`, `v^2` of every face node, as the tensor grid's
    /// (`SolidSetup::contact_pair`) with the corner mesh's weights and gradients
    /// (`SolidCornerNavier::face_nodes`):
    /// ```text
    /// T^3_j = sum_k u_k (lambda delta_3j tr M_k + 2 mu M_k[3][j])
    /// w = sqrt(g) sqrt(g^33) int N dx1 dx2
    /// frame_1 = [sqrt(a_11), 0],  frame_2 = [a_12 / sqrt(a_11), 1 / sqrt(a^22)]
    /// ```
    /// Sites `i1 K + k` (`K` face nodes per `x1` line, `k` their rank in `x2`).
    fn contact_entries(&self) -> Result<Vec<ContactNode>, ElasticityError> {
        let face = self.face_nodes();
        let per_line = face.iter().filter(|f| f.i1 == 0).count();
        let material = self.material();
        let (lambda, two_mu) = (material.lambda(), 2.0 * material.mu());
        let mut out = Vec::with_capacity(2 * face.len());
        for f in &face {
            let x = self.node_position(f.node);
            let p = self.chart().shell_point(x)?;
            let (g, gi) = (&p.metric, &p.inverse_metric);
            let strains = mixed_strains(&p, &SOLID);
            let row = |j: usize| -> SparseRow {
                let mut terms = Vec::with_capacity(3 * f.stencil.len());
                for &(at, w) in &f.stencil {
                    for c in 0..3 {
                        let mut a = 0.0;
                        for (q, wq) in w.iter().enumerate() {
                            if *wq == 0.0 {
                                continue;
                            }
                            let k = if q == 0 { c } else { 3 + 3 * (q - 1) + c };
                            let m = &strains[k];
                            let trace = m[0][0] + m[1][1] + m[2][2];
                            let t = if j == 2 { lambda * trace } else { 0.0 } + two_mu * m[2][j];
                            a += t * wq;
                        }
                        terms.push((3 * at + c, a));
                    }
                }
                SparseRow::from_terms(&mut terms)
            };
            let normal = row(2);
            let weight = p.sqrt_g * gi[2][2].sqrt() * f.weight;
            let sqrt_a11 = g[0][0].sqrt();
            let frames = [[sqrt_a11, 0.0], [g[0][1] / sqrt_a11, 1.0 / gi[1][1].sqrt()]];
            for c in 0..2 {
                let dof = 3 * f.node + c;
                out.push(ContactNode {
                    node: [f.k, 0],
                    i1: f.i1,
                    site: f.i1 * per_line + f.k,
                    x1: x[0],
                    x2: x[1],
                    component: c + 1,
                    frame: frames[c],
                    tangential_row: self.dirichlet()[dof].is_none().then_some(dof),
                    tangential_dof: dof,
                    normal_dof: 3 * f.node + 2,
                    traction_weight: weight,
                    sqrt_g22: g[c][c].sqrt(),
                    normal_stress: normal.clone(),
                    shear_stress: row(c),
                });
            }
        }
        Ok(out)
    }

    fn solid(&self) -> Option<&dyn crate::solid::SolidOutput> {
        Some(self)
    }

    fn extremes(&self, v: &[f64]) -> [Extremum; 2] {
        [1, 2].map(|c| {
            extremum(
                self.node_count(),
                |m| v[3 * m + c],
                |m| {
                    let x = self.node_position(m);
                    (Some(x[0]), x[1], x[2])
                },
            )
        })
    }
}
