//! Nodal recovery: the second-order gradient stencil at a node, the contact rows
//! `v -> [T^3_2, T^3_3]`, and the reduced-point divergence extrapolated to a node (SRI).

use super::FiniteElementNavier;
use crate::boundary::Component;
use crate::continuum::kinematics::LocalDisplacement;
use crate::discretisation::{Discretisation, SparseRow};
use crate::finite_element::element::{gauss_rule, lagrange_weights};
use crate::finite_element::volumetric::VolumetricIntegration;
use crate::shell_geometry::ShellGeometry;

impl<G: ShellGeometry + Sync> FiniteElementNavier<G> {
    /// The gradient-recovery stencil at a node: `(node, [value, d_2, d_3])` weights.
    pub(super) fn node_stencil(&self, node: [usize; 2]) -> Vec<([usize; 2], [f64; 3])> {
        let mut out = Vec::with_capacity(7);
        self.problem.grid.node_stencil(node, &mut out);
        out
    }

    /// The contact rows `[T^3_2, T^3_3]` at node `(i, 0)`: the recovery stencil applied to the
    /// pointwise coefficients; with [`VolumetricIntegration::Reduced`], `T^3_3` adds
    /// `lambda` times the reduced-point divergence of [`Self::reduced_divergence_terms`] to
    /// its pointwise shear part.
    pub(super) fn contact_rows(&self, i: usize) -> [SparseRow; 2] {
        let (coef, _) = &self.contact[i];
        let st = self.node_stencil([i, 0]);
        [0, 1].map(|e| {
            let mut terms = Vec::with_capacity(2 * st.len());
            for (node, w) in &st {
                for c in 0..2 {
                    let a = coef[e][c] * w[0] + coef[e][2 + c] * w[1] + coef[e][4 + c] * w[2];
                    terms.push((self.dof(*node, Component::ALL[c]), a));
                }
            }
            if e == 1 && self.volumetric == VolumetricIntegration::Reduced {
                let lambda = self.problem.material.lambda();
                terms.extend(
                    self.reduced_divergence_terms([i, 0])
                        .into_iter()
                        .map(|(d, w)| (d, lambda * w)),
                );
            }
            SparseRow::from_terms(&mut terms)
        })
    }

    /// The divergence at a node recovered from the reduced points of the elements around it
    /// (selective reduced integration only): `(dof, weight)` terms of `v -> div_h v (node)`,
    /// duplicates allowed. Its columns are those of the elements around the node, already in
    /// the pattern of the node's rows.
    ///
    /// # Math
    /// SRI controls the divergence only at the `k x k` reduced Gauss points `(xi_r, eta_s)` of
    /// each element (the pressure `lambda div v` of the equivalent mixed element: Q1-P0,
    /// Q2-Q1 discontinuous); between them, and at the nodes, the pointwise `div v` of the
    /// displacement carries the spurious (checkerboard) modes that `lambda` no longer
    /// penalises. The nodal value is the element's reduced-point field extrapolated with the
    /// tensor Lagrange interpolant of degree `k - 1` through those points,
    /// ```text
    /// div_e(xi, eta) = sum_(r, s) l_r(xi) l_s(eta) div v(xi_r, eta_s)
    /// div v(xi_r, eta_s) = sum_(a, c) v^c_a (t_c N_a + t_(2+c) d_2 N_a + t_(4+c) d_3 N_a)
    /// ```
    /// (`t_k = tr M_k` at the point, the curvilinear `nabla_i v^i = d_i v^i + Gamma^i_im v^m`
    /// of the stiffness), averaged over the elements containing the node:
    /// ```text
    /// div_h(node) = (1 / #E(node)) sum_(e in E(node)) div_e(xi_node, eta_node)
    /// ```
    /// Q1: `l_0 = 1`, the element-centre value, averaged over the two elements on either side
    /// of the node in each direction; at a boundary node (one element that way) the centre
    /// values of the two nearest element rows extrapolated linearly, `1.5 c_near - 0.5 c_far`
    /// (centres at `dx/2` and `3 dx/2`): second order where the divergence varies normal to the
    /// boundary, as on the contact surface (ellipse manufactured solution: order 1.78, errors
    /// 15.7x smaller than the first-row centre value at `dx3 = 1/64`). Q2: `l_0(s) = (1 - sqrt(3) s) / 2`, `l_1(s) = (1 + sqrt(3) s) / 2`
    /// through `-+1/sqrt(3)`, so on the bottom edge `eta = -1` the weights are
    /// `(1 +- sqrt(3)) / 2` and at the node abscissa `xi in {-1, 0, 1}` they are
    /// `((1 +- sqrt(3)) / 2, (1 -+ sqrt(3)) / 2)`, `(1/2, 1/2)`. Both reproduce a divergence of
    /// degree `k - 1` exactly, so the recovered pressure is `O(h^k)` where the reduced-point
    /// pressure is.
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
        let g = &self.problem.grid;
        let (k, nen) = (self.order.degree(), self.nodes_per_element());
        let (gp, _) = gauss_rule(k);
        let nr = k * k;
        let local = |a: usize| -1.0 + 2.0 * a as f64 / k as f64;
        // per direction: (element, weights of its reduced points along that direction)
        let direction = |i: usize, n: usize, count: usize, periodic: bool| {
            let along = self.elements_along(i, count, periodic);
            if k == 1 && !periodic && along.len() == 1 && count >= 2 {
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
                .map(|e| {
                    // local node number (k in the last element of a periodic grid at i = 0)
                    let l = lagrange_weights(&gp, local((i + n - k * e) % n));
                    (e, l.into_iter().map(|w| share * w).collect::<Vec<f64>>())
                })
                .collect::<Vec<_>>()
        };
        let along2 = direction(i2, g.n2(), self.elements[0], g.is_periodic());
        let along3 = direction(i3, g.n3(), self.elements[1], false);
        let mut terms = Vec::with_capacity(along2.len() * along3.len() * nr * 2 * nen);
        let mut nodes = [0; 9];
        for (e2, l2) in &along2 {
            for (e3, l3) in &along3 {
                let e = e2 * self.elements[1] + e3;
                self.element_nodes(e, &mut nodes);
                for (ri, w2) in l2.iter().enumerate() {
                    for (rj, w3) in l3.iter().enumerate() {
                        let r = ri * k + rj; // the order of `shape_table`
                        let w = w2 * w3;
                        let [_, t @ ..] = self.reduced_divergence[e * nr + r];
                        let phi = &self.reduced_shape[r * nen..(r + 1) * nen];
                        for (a, f) in phi.iter().enumerate() {
                            for c in 0..2 {
                                let d = t[c] * f[0] + t[2 + c] * f[1] + t[4 + c] * f[2];
                                terms.push((2 * nodes[a] + c, w * d));
                            }
                        }
                    }
                }
            }
        }
        terms
    }

    /// The local displacement at a node by the recovery stencil.
    pub(super) fn local(&self, node: [usize; 2], v: &[f64]) -> LocalDisplacement {
        LocalDisplacement::from_stencil(&self.node_stencil(node), |n, c| {
            v[self.dof(n, Component::ALL[c])]
        })
    }
}
