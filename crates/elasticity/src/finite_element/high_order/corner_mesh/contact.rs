//! The corner mesh as a contact operator ([`MeshDiscretisation`]): the contact face's nodes in
//! increasing `x2` with the face quadrature weights, and the one-sided stresses `T^3_2`,
//! `T^3_3` from the element polynomials, weighted by quadrature share exactly as the tensor
//! Qp elements' contact rows ([`super::super::HighOrderNavier`], `contact_node_terms`).

use super::super::gll::{gll_rule, lagrange_basis};
use super::layout::{bilinear, local_edges, sides_of};
use super::operator::CornerRefinedNavier;
use crate::continuum::check_plane_strain;
use crate::continuum::kinematics::mixed_stress_coefficients;
use crate::discretisation::{ContactNode, LinearSystem, SparseRow};
use crate::error::ElasticityError;
use crate::mesh_discretisation::MeshDiscretisation;
use crate::shell_geometry::ShellGeometry;

/// Bit of the contact side `x3 = 0` in `sides_of`.
const CONTACT_SIDE: u8 = 4;

/// One face element holding a contact node: element, the node's local `(a2, a3)`, and the
/// node's face quadrature weight in it, `w_k L_e / 2` (GLL weight along the edge times the
/// edge's half-length in `x2`).
struct FaceShare {
    element: usize,
    local: [usize; 2],
    weight: f64,
}

impl<G: ShellGeometry + Sync> CornerRefinedNavier<G> {
    /// Every contact node (`x3 = 0`) with the face elements holding it.
    fn face_shares(&self) -> Vec<(usize, Vec<FaceShare>)> {
        let p = self.settings.order;
        let np = p + 1;
        let (_, weights) = gll_rule(p);
        let rect = [
            self.problem.grid.theta(),
            [0.0, self.problem.grid.thickness()],
        ];
        let mut shares: Vec<Vec<FaceShare>> = (0..self.layout.node_count).map(|_| vec![]).collect();
        for (e, q) in self.layout.quads.iter().enumerate() {
            for (k, [s, t]) in local_edges(q).into_iter().enumerate() {
                let [xs, xe] = [s, t].map(|i| self.layout.vertices[i]);
                if sides_of(xs, rect) & sides_of(xe, rect) & CONTACT_SIDE == 0 {
                    continue;
                }
                let half = 0.5 * (xe[0] - xs[0]).abs();
                for (j, &w) in weights.iter().enumerate() {
                    // edges xi = -1, xi = 1 (a3 varies), eta = -1, eta = 1 (a2 varies)
                    let local = match k {
                        0 => [0, j],
                        1 => [p, j],
                        2 => [j, 0],
                        _ => [j, p],
                    };
                    let m = self.nodes(e)[local[0] * np + local[1]];
                    shares[m].push(FaceShare {
                        element: e,
                        local,
                        weight: w * half,
                    });
                }
            }
        }
        shares
            .into_iter()
            .enumerate()
            .filter(|(_, s)| !s.is_empty())
            .collect()
    }

    /// The value and gradient at node `m` as weights of nodal values, `(node, [value, d_2,
    /// d_3])`: the element polynomials' one-sided gradients of the face elements holding it,
    /// weighted by their share of the face quadrature (normalised).
    ///
    /// # Math
    /// In element `e` at the node's reference point `(xi_a2, eta_a3)`, with `J` the bilinear
    /// map's Jacobian there,
    /// ```text
    /// (d_2 v, d_3 v) = J^-T (sum_b l_b'(xi_a2) v(b, a3), sum_b l_b'(eta_a3) v(a2, b))
    /// grad v (node) = sum_e theta_e grad_e v,   theta_e = w_e L_e / sum_f w_f L_f
    /// ```
    /// On a rectangle `J^-T = diag(2 / L2, 2 / L3)`: the tensor elements' `contact_node_terms`.
    fn face_terms(&self, m: usize, shares: &[FaceShare]) -> Vec<(usize, [f64; 3])> {
        let np = self.np();
        let total: f64 = shares.iter().map(|s| s.weight).sum();
        let mut terms = vec![(m, [1.0, 0.0, 0.0])];
        for s in shares {
            let theta = s.weight / total;
            let [a2, a3] = s.local;
            let vertices = self.element_vertices(s.element);
            let (_, j) = bilinear(&vertices, [self.gll[a2], self.gll[a3]]);
            let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
            // G = J^-T: (d_2, d_3) = G (d_xi, d_eta)
            let g = [
                [j[1][1] / det, -j[1][0] / det],
                [-j[0][1] / det, j[0][0] / det],
            ];
            let (_, dxi) = lagrange_basis(&self.gll, self.gll[a2]);
            let (_, deta) = lagrange_basis(&self.gll, self.gll[a3]);
            let nodes = self.nodes(s.element);
            for b in 0..np {
                let d = theta * dxi[b];
                terms.push((nodes[b * np + a3], [0.0, g[0][0] * d, g[1][0] * d]));
                let d = theta * deta[b];
                terms.push((nodes[a2 * np + b], [0.0, g[0][1] * d, g[1][1] * d]));
            }
        }
        terms
    }
}

impl<G: ShellGeometry + Sync> MeshDiscretisation for CornerRefinedNavier<G> {
    fn method(&self) -> &'static str {
        "fem-qp-corner"
    }

    fn node_count(&self) -> usize {
        self.layout.node_count
    }

    fn node_position(&self, m: usize) -> [f64; 2] {
        self.positions[m]
    }

    fn system(&self) -> Result<LinearSystem, ElasticityError> {
        self.full_system()
    }

    /// The face's nodes in increasing `x2` (the corner layers add nodes near both ends).
    /// Traction weight `sqrt(g) sqrt(g^33) sum_e w_e L_e / 2` (the face quadrature), rows
    /// `T^3_2`, `T^3_3` from the one-sided gradients of the face elements (`face_terms`) and the pointwise mixed-stress
    /// coefficients, as the tensor Qp elements build them.
    fn contact_nodes(&self) -> Result<Vec<ContactNode>, ElasticityError> {
        let mut face = self.face_shares();
        face.sort_by(|a, b| self.positions[a.0][0].total_cmp(&self.positions[b.0][0]));
        face.iter()
            .enumerate()
            .map(|(k, (m, shares))| {
                let x2 = self.positions[*m][0];
                let at = [0.0, x2, 0.0];
                let p = self.problem.chart.shell_point(at)?;
                check_plane_strain(&p, at)?;
                let length: f64 = shares.iter().map(|s| s.weight).sum();
                let c = mixed_stress_coefficients(&p, &self.problem.material);
                let terms = self.face_terms(*m, shares);
                // coef[e][k]: the coefficient of input k in T^3_(e+2)
                let rows = [0, 1].map(|e| {
                    let mut row = Vec::with_capacity(2 * terms.len());
                    for &(n, w) in &terms {
                        for comp in 0..2 {
                            let a = c[comp][2][e + 1] * w[0]
                                + c[2 + comp][2][e + 1] * w[1]
                                + c[4 + comp][2][e + 1] * w[2];
                            row.push((2 * n + comp, a));
                        }
                    }
                    SparseRow::from_terms(&mut row)
                });
                let [shear_stress, normal_stress] = rows;
                let sqrt_g22 = p.metric[1][1].sqrt();
                let tangential_dof = 2 * m;
                Ok(ContactNode {
                    node: [k, 0],
                    i1: 0,
                    site: k,
                    x1: 0.0,
                    x2,
                    component: 2,
                    frame: [0.0, sqrt_g22],
                    tangential_row: self.dirichlet[tangential_dof]
                        .is_none()
                        .then_some(tangential_dof),
                    tangential_dof,
                    normal_dof: 2 * m + 1,
                    traction_weight: p.sqrt_g * p.inverse_metric[2][2].sqrt() * length,
                    sqrt_g22,
                    normal_stress,
                    shear_stress,
                })
            })
            .collect()
    }

    fn output_cells(&self) -> Vec<[usize; 4]> {
        let np = self.np();
        (0..self.element_count())
            .flat_map(|e| {
                let nodes = self.nodes(e);
                (0..np - 1).flat_map(move |a2| {
                    (0..np - 1).map(move |a3| {
                        let at = |i: usize, j: usize| nodes[(a2 + i) * np + a3 + j];
                        [at(0, 0), at(1, 0), at(1, 1), at(0, 1)]
                    })
                })
            })
            .collect()
    }
}
