//! The nodal recovery of the Qp operator: the value and gradient of the displacement at a
//! node, which the contact rows (`T^3_2`, `T^3_3` on `x3 = 0`) and the output fields read,
//! formed from the nodal values as [`NodalRecovery`] says, and the reduced-point divergence of
//! selective reduced integration extrapolated to a node.

use super::nodal_recovery::NodalRecovery;
use super::operator::HighOrderNavier;
use crate::continuum::kinematics::{LocalDisplacement, mixed_stress_coefficients};
use crate::continuum::{PLANE_STRAIN, mixed_strains};
use crate::discretisation::SparseRow;
use crate::finite_element::element::lagrange_weights;
use crate::finite_element::high_order::gauss_legendre;
use crate::finite_element::volumetric::VolumetricIntegration;
use crate::shell_geometry::ShellGeometry;
use capstan_geometry::ShellPoint;

impl<G: ShellGeometry + Sync> HighOrderNavier<G> {
    /// The value and derivatives at grid node `node` as weights of nodal values,
    /// `(node index, [value, d_2, d_3])`, by the operator's [`NodalRecovery`].
    pub(super) fn recovery_terms(&self, node: [usize; 2]) -> Vec<(usize, [f64; 3])> {
        match self.recovery {
            NodalRecovery::Element => self.node_terms(node),
            NodalRecovery::Differences => {
                let grid = &self.problem.grid;
                let mut stencil = Vec::with_capacity(7);
                grid.node_stencil(node, &mut stencil);
                stencil
                    .into_iter()
                    .map(|(n, w)| (grid.node_index(n), w))
                    .collect()
            }
        }
    }

    /// The local displacement (value and gradient) at a node ([`Self::recovery_terms`]).
    pub(super) fn local(&self, node: [usize; 2], v: &[f64]) -> LocalDisplacement {
        let mut s = [[0.0; 2]; 3];
        for (m, w) in self.recovery_terms(node) {
            for (t, wt) in w.iter().enumerate() {
                s[t][0] += wt * v[2 * m];
                s[t][1] += wt * v[2 * m + 1];
            }
        }
        LocalDisplacement {
            value: s[0],
            gradient: [s[1], s[2]],
        }
    }

    /// The contact rows `[T^3_2, T^3_3]` at node `(i, 0)` (chart point `p` there): the
    /// recovery terms applied to the pointwise mixed-stress coefficients; with
    /// [`NodalRecovery::Differences`] and reduced integration, `T^3_3` is its shear part plus
    /// `lambda div_h v` ([`Self::reduced_divergence_terms`]).
    pub(super) fn contact_rows(&self, i: usize, p: &ShellPoint<f64>) -> [SparseRow; 2] {
        let c = mixed_stress_coefficients(p, &self.problem.material);
        // coef[e][k]: the coefficient of input k in T^3_(e+2)
        let mut coef: [[f64; 6]; 2] =
            core::array::from_fn(|e| core::array::from_fn(|k| c[k][2][e + 1]));
        let split = self.recovery == NodalRecovery::Differences
            && self.volumetric == VolumetricIntegration::Reduced;
        if split {
            // T^3_3 = lambda tr M + 2 mu M^3_3: only the shear part is pointwise
            let two_mu = 2.0 * self.problem.material.mu();
            coef[1] = mixed_strains(p, &PLANE_STRAIN).map(|m| two_mu * m[2][2]);
        }
        // element recovery weighs the one-sided x2 derivatives of the elements sharing the
        // node as the face quadrature does (graded meshes: `Self::contact_node_terms`)
        let terms = match self.recovery {
            NodalRecovery::Element => self.contact_node_terms([i, 0]),
            NodalRecovery::Differences => self.recovery_terms([i, 0]),
        };
        [0, 1].map(|e| {
            let mut row = Vec::with_capacity(2 * terms.len());
            for &(m, w) in &terms {
                for comp in 0..2 {
                    let a =
                        coef[e][comp] * w[0] + coef[e][2 + comp] * w[1] + coef[e][4 + comp] * w[2];
                    row.push((2 * m + comp, a));
                }
            }
            if e == 1 && split {
                let lambda = self.problem.material.lambda();
                row.extend(
                    self.reduced_divergence_terms([i, 0])
                        .into_iter()
                        .map(|(d, w)| (d, lambda * w)),
                );
            }
            SparseRow::from_terms(&mut row)
        })
    }

    /// The divergence at a node recovered from the reduced points of the elements around it
    /// (selective reduced integration): `(dof, weight)` terms of `v -> div_h v (node)`,
    /// duplicates allowed (see [`NodalRecovery::Differences`]).
    ///
    /// # Math
    /// At reduced point `(xi_r, eta_s)` of element `e`
    /// ```text
    /// div v(xi_r, eta_s) = sum_(a, c) v^c_a (t_c N_a + t_(2+c) d_2 N_a + t_(4+c) d_3 N_a)
    /// ```
    /// (`t_k = tr M_k` there, the curvilinear `nabla_i v^i` of the stiffness), weighted by
    /// `l_r(xi_node) l_s(eta_node) / #E(node)`.
    ///
    /// # Panics
    /// If the volumetric part is integrated with the full rule (no reduced points cached).
    #[track_caller]
    pub(super) fn reduced_divergence_terms(&self, [i2, i3]: [usize; 2]) -> Vec<(usize, f64)> {
        assert_eq!(
            self.volumetric,
            VolumetricIntegration::Reduced,
            "reduced points are cached with selective reduced integration only"
        );
        let rt = self
            .reduced_tables
            .as_ref()
            .expect("reduced tables with selective reduced integration");
        let g = &self.problem.grid;
        let (p, np, nq) = (self.degree, self.np(), rt.nq);
        let (gp, _) = gauss_legendre(p);
        // per direction: (element, weights of its reduced points along that direction)
        let direction = |i: usize, count: usize, periodic: bool| {
            let along = self.elements_along(i, count, periodic);
            if p == 1 && !periodic && along.len() == 1 && count >= 2 {
                // Q1 at a boundary node: the centre values of the two nearest element rows,
                // extrapolated linearly (centres at dx/2 and 3 dx/2 from the node)
                let (near, far) = if i == 0 {
                    (0, 1)
                } else {
                    (count - 1, count - 2)
                };
                return vec![(near, vec![1.5]), (far, vec![-0.5])];
            }
            let share = 1.0 / along.len() as f64;
            along
                .into_iter()
                .map(|(e, a)| {
                    let l = lagrange_weights(&gp, self.gll[a]);
                    (e, l.into_iter().map(|w| share * w).collect::<Vec<f64>>())
                })
                .collect::<Vec<_>>()
        };
        let along2 = direction(i2, self.elements[0], g.is_periodic());
        let along3 = direction(i3, self.elements[1], false);
        let mut terms = Vec::with_capacity(along2.len() * along3.len() * nq * nq * 2 * np * np);
        for (e2, l2) in &along2 {
            for (e3, l3) in &along3 {
                let e = e2 * self.elements[1] + e3;
                let nodes = self.element_nodes(e);
                let (_, [size2, size3]) = self.element_box(e);
                let (s2, s3) = (2.0 / size2, 2.0 / size3);
                for (ri, w2) in l2.iter().enumerate() {
                    for (rj, w3) in l3.iter().enumerate() {
                        let w = w2 * w3;
                        let t = &self.reduced_divergence[e * nq * nq + ri * nq + rj];
                        for a2 in 0..np {
                            let (x, dx) = (rt.value[a2 * nq + ri], rt.d2[a2 * nq + ri] * s2);
                            for a3 in 0..np {
                                let (y, dy) = (rt.value[a3 * nq + rj], rt.d3[a3 * nq + rj] * s3);
                                let f = [x * y, dx * y, x * dy];
                                let m = nodes[a2 * np + a3];
                                for c in 0..2 {
                                    let d = t[c] * f[0] + t[2 + c] * f[1] + t[4 + c] * f[2];
                                    terms.push((2 * m + c, w * d));
                                }
                            }
                        }
                    }
                }
            }
        }
        terms
    }
}
