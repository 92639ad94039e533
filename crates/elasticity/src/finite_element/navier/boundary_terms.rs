//! Natural boundary terms (tractions and stresses on the sides) and Dirichlet data.

use capstan_geometry::ShellPoint;

use super::FiniteElementNavier;
use crate::boundary::{Component, ComponentCondition, Side, SideCondition};
use crate::continuum::{FaceData, face_flux};
use crate::error::ElasticityError;
use crate::shell_geometry::ShellGeometry;

/// Adds the natural boundary term of one quadrature point `at` of `side` (chart point `p`) to
/// `load`: for every component `c` with a natural condition and every `(node index, N)` of
/// `shape`, `load[2 node + c] += N phi_c w J` with the flux of [`face_flux`]
/// ```text
/// phi_c = sqrt(g) sqrt(g^aa) t_c(s)   (traction),   phi_c = +-sqrt(g) T_c(s)   (stress)
/// ```
/// `a` the side's normal index, `s` the coordinate along the side, `[w, J]` the rule's weight
/// and the Jacobian of the edge (applied in that order). Shared by Q1/Q2 and Qp.
///
/// # Errors
/// [`ElasticityError::NonFinite`] for a non-finite `phi_c`.
pub(crate) fn add_side_point_load(
    load: &mut [f64],
    cond: &SideCondition,
    side: Side,
    p: &ShellPoint<f64>,
    at: [f64; 2],
    [w, jacobian]: [f64; 2],
    shape: impl Iterator<Item = (usize, f64)> + Clone,
) -> Result<(), ElasticityError> {
    let a = side.normal_index();
    let s = if a == 2 { at[0] } else { at[1] };
    for c in Component::ALL {
        let data = match cond.component(c) {
            ComponentCondition::Displacement(_) => continue,
            ComponentCondition::Traction(f) => FaceData::Traction(f.eval(s)),
            ComponentCondition::Stress(f) => FaceData::Stress(f.eval(s)),
        };
        let flux = face_flux(p, a, side.sign(), data, at)?;
        for (node, n) in shape.clone() {
            load[2 * node + c.index()] += n * flux * w * jacobian;
        }
    }
    Ok(())
}

impl<G: ShellGeometry + Sync> FiniteElementNavier<G> {
    /// Adds `int phi_j N_a ds` over every side with a natural condition (Gauss rule of the
    /// element along each boundary edge).
    pub(super) fn add_boundary_loads(&mut self) -> Result<(), ElasticityError> {
        let (gp, gw) = self.order.gauss_1d();
        let (k, np) = (self.order.degree(), self.order.nodes_per_direction());
        let [l2, l3] = self.element_size();
        let (n2, n3) = (self.problem.grid.n2(), self.problem.grid.n3());
        for side in Side::ALL {
            let Some(cond) = self.problem.boundary.side(side).cloned() else {
                continue; // periodic x2
            };
            let along_x2 = side.normal_index() == 2;
            let (count, length) = if along_x2 {
                (self.elements[0], l2)
            } else {
                (self.elements[1], l3)
            };
            for e in 0..count {
                for (&xi, &w) in gp.iter().zip(&gw) {
                    let (shape, _) = self.order.shape_1d(xi);
                    let (x, nodes): ([f64; 2], Vec<[usize; 2]>) = if along_x2 {
                        let i3 = if side == Side::X3Min { 0 } else { n3 - 1 };
                        let x2 = self.problem.grid.x2(k * e) + 0.5 * (xi + 1.0) * length;
                        (
                            [x2, self.problem.grid.x3(i3)],
                            (0..np).map(|a| [(k * e + a) % n2, i3]).collect(),
                        )
                    } else {
                        let i2 = if side == Side::X2Min { 0 } else { n2 - 1 };
                        let x3 = self.problem.grid.x3(k * e) + 0.5 * (xi + 1.0) * length;
                        (
                            [self.problem.grid.x2(i2), x3],
                            (0..np).map(|a| [i2, k * e + a]).collect(),
                        )
                    };
                    let p = self.point(x[0], x[1])?;
                    let grid = &self.problem.grid;
                    let shape = nodes
                        .iter()
                        .zip(shape)
                        .map(|(m, n)| (grid.node_index(*m), n));
                    let weight = [w, 0.5 * length];
                    add_side_point_load(&mut self.load, &cond, side, &p, x, weight, shape)?;
                }
            }
        }
        Ok(())
    }
}
