//! Error norms of a discrete displacement against an exact one.

use capstan_geometry::ShellPoint;
use rayon::prelude::*;

use super::FiniteElementNavier;
use crate::discretisation::Discretisation;
use crate::error::ElasticityError;
use crate::finite_element::element::gauss_rule;
use crate::shell_geometry::ShellGeometry;

/// Errors of a discrete displacement against an exact one.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct DisplacementErrors {
    /// Max over the nodes of `|U_h - U|` (Cartesian displacement error).
    pub max: f64,
    /// RMS over the parameter rectangle, `sqrt(int |U_h - U|^2 dx2 dx3 / area)` (the
    /// verification norm of the finite differences, integrated exactly instead of by the
    /// nodal trapezoid rule).
    pub rms: f64,
    /// Physical L2 norm `sqrt(int |U_h - U|^2 dA)` (per unit `x1`, `dA = sqrt(g) dx2 dx3`).
    pub l2: f64,
    /// `sqrt(int |U|^2 dA)`, for relative errors.
    pub l2_exact: f64,
}

impl<G: ShellGeometry + Sync> FiniteElementNavier<G> {
    /// Interpolates the discrete displacement `[v^2, v^3]` and the exact one over every
    /// element with a `(k + 2)`-point Gauss rule per direction and returns the error norms.
    ///
    /// # Errors
    /// [`ElasticityError::DimensionMismatch`] for a wrong length; geometry failures.
    pub fn displacement_errors(
        &self,
        v: &[f64],
        exact: &(dyn Fn([f64; 2]) -> [f64; 2] + Sync),
    ) -> Result<DisplacementErrors, ElasticityError> {
        ElasticityError::check_length("displacement", self.dof_count(), v.len())?;
        let norm2 = |p: &ShellPoint<f64>, e: [f64; 2]| {
            let g = &p.metric;
            g[1][1] * e[0] * e[0] + 2.0 * g[1][2] * e[0] * e[1] + g[2][2] * e[1] * e[1]
        };
        let max = (0..self.grid.node_count())
            .into_par_iter()
            .map(|k| -> Result<f64, ElasticityError> {
                let [x2, x3] = self.grid.coordinates(self.grid.node(k));
                let p = self.chart.shell_point([0.0, x2, x3])?;
                let u = exact([x2, x3]);
                Ok(norm2(&p, [v[2 * k] - u[0], v[2 * k + 1] - u[1]]).sqrt())
            })
            .try_reduce(|| 0.0, |a, b| Ok(a.max(b)))?;
        let (gp, gw) = gauss_rule(self.order.nodes_per_direction() + 1);
        let [l2, l3] = self.element_size();
        let det = 0.25 * l2 * l3;
        let np = self.order.nodes_per_direction();
        let ne = self.elements[0] * self.elements[1];
        let sums = (0..ne)
            .into_par_iter()
            .map(|e| -> Result<[f64; 3], ElasticityError> {
                let mut nodes = [0; 9];
                self.element_nodes(e, &mut nodes);
                let [x0, y0] = self.element_origin(e);
                let mut s = [0.0; 3];
                for (i, &xi) in gp.iter().enumerate() {
                    let (n2, _) = self.order.shape_1d(xi);
                    for (j, &eta) in gp.iter().enumerate() {
                        let (n3, _) = self.order.shape_1d(eta);
                        let x = [x0 + 0.5 * (xi + 1.0) * l2, y0 + 0.5 * (eta + 1.0) * l3];
                        let mut uh = [0.0; 2];
                        for a2 in 0..np {
                            for a3 in 0..np {
                                let node = nodes[a2 * np + a3];
                                let n = n2[a2] * n3[a3];
                                uh[0] += n * v[2 * node];
                                uh[1] += n * v[2 * node + 1];
                            }
                        }
                        let p = self.chart.shell_point([0.0, x[0], x[1]])?;
                        let u = exact(x);
                        let w = gw[i] * gw[j] * det;
                        let err2 = norm2(&p, [uh[0] - u[0], uh[1] - u[1]]);
                        s[0] += w * err2;
                        s[1] += w * p.sqrt_g * err2;
                        s[2] += w * p.sqrt_g * norm2(&p, u);
                    }
                }
                Ok(s)
            })
            .collect::<Result<Vec<_>, _>>()?;
        // sequential sum in element order: reproducible
        let s = sums.iter().fold([0.0; 3], |acc, x| {
            [acc[0] + x[0], acc[1] + x[1], acc[2] + x[2]]
        });
        let [t0, t1] = self.grid.theta();
        let area = (t1 - t0) * self.grid.thickness();
        Ok(DisplacementErrors {
            max,
            rms: (s[0] / area).sqrt(),
            l2: s[1].sqrt(),
            l2_exact: s[2].sqrt(),
        })
    }
}
