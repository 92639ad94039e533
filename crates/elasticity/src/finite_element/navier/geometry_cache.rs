//! The geometry at the quadrature points: the chart walked column by column, the pointwise
//! stiffness (and the reduced-point divergence of selective reduced integration) cached once.

use capstan_geometry::ShellPoint;
use rayon::prelude::*;

use super::{FiniteElementNavier, packed_energy, packed_stiffness};
use crate::continuum::{PLANE_STRAIN, divergence_coefficients};
use crate::discretisation::Discretisation;
use crate::error::ElasticityError;
use crate::finite_element::element::gauss_rule;
use crate::finite_element::volumetric::VolumetricIntegration;
use crate::plane_problem::BodyForce;
use crate::shell_geometry::ShellGeometry;

impl<G: ShellGeometry + Sync> FiniteElementNavier<G> {
    /// `x3` of every Gauss point `gp` (reference abscissae) of a column of elements, element
    /// by element: index `e3 nqd + j`.
    pub(super) fn column_heights(&self, gp: &[f64]) -> Vec<f64> {
        let [_, l3] = self.element_size();
        let k = self.order.degree();
        (0..self.elements[1])
            .flat_map(|e3| {
                let y0 = self.problem.grid.x3(k * e3);
                gp.iter().map(move |&eta| y0 + 0.5 * (eta + 1.0) * l3)
            })
            .collect()
    }

    /// Walks the tensor Gauss points `gp x gp` of the column of elements `e2`, one chart column
    /// ([`ShellGeometry::shell_column`]) per `x2` abscissa: `visit(i, e3, j, point, [x2, x3])`
    /// with `i`, `j` the point's indices along `x2`, `x3` inside element `(e2, e3)`; the point
    /// is checked for the plane-strain reduction first.
    pub(super) fn walk_column(
        &self,
        e2: usize,
        gp: &[f64],
        heights: &[f64],
        mut visit: impl FnMut(
            usize,
            usize,
            usize,
            &ShellPoint<f64>,
            [f64; 2],
        ) -> Result<(), ElasticityError>,
    ) -> Result<(), ElasticityError> {
        let [l2, _] = self.element_size();
        let x0 = self.problem.grid.x2(self.order.degree() * e2);
        let nqd = gp.len();
        let mut points = Vec::with_capacity(heights.len());
        for (i, &xi) in gp.iter().enumerate() {
            let x2 = x0 + 0.5 * (xi + 1.0) * l2;
            self.problem
                .visit_column(x2, heights, &mut points, |idx, p, x3| {
                    visit(i, idx / nqd, idx % nqd, p, [x2, x3])
                })?;
        }
        Ok(())
    }

    /// Evaluates the geometry at every quadrature point and adds the body force: one column
    /// of points ([`ShellGeometry::shell_column`], one surface jet) per `x2` abscissa of each
    /// column of elements, the columns in parallel.
    pub(super) fn cache_geometry(
        &mut self,
        body_force: Option<&BodyForce>,
    ) -> Result<(), ElasticityError> {
        let (gp, gw) = self.order.gauss_1d();
        let [l2, l3] = self.element_size();
        let det = 0.25 * l2 * l3;
        let (nq, nen) = (self.quadrature_points(), self.nodes_per_element());
        let [ne2, ne3] = self.elements;
        let nqd = gp.len();
        let heights = self.column_heights(&gp);
        let mut stiffness = vec![[0.0; 21]; ne2 * ne3 * nq];
        let mut local_loads = vec![
            0.0;
            if body_force.is_some() {
                ne2 * ne3 * 2 * nen
            } else {
                0
            }
        ];
        let this = &*self;
        // one column of elements: stiffness `kq` (ne3 nq) and loads (ne3 2 nen, if any)
        let compute = |e2: usize,
                       kq: &mut [[f64; 21]],
                       mut load: Option<&mut [f64]>|
         -> Result<(), ElasticityError> {
            this.walk_column(e2, &gp, &heights, |i, e3, j, p, [x2, x3]| {
                let q = i * nqd + j;
                let w = gw[i] * gw[j] * det;
                kq[e3 * nq + q] = match this.volumetric {
                    VolumetricIntegration::Full => packed_stiffness(p, &this.problem.material, w),
                    // the shear part only: the volumetric part is at the reduced points
                    VolumetricIntegration::Reduced => {
                        packed_energy(p, 0.0, this.problem.material.mu(), w)
                    }
                };
                if let (Some(f), Some(load)) = (body_force, load.as_deref_mut()) {
                    let x = [x2, x3];
                    let fx = f(x);
                    if !(fx[0].is_finite() && fx[1].is_finite()) {
                        return Err(ElasticityError::NonFinite {
                            what: "body force",
                            at: x,
                        });
                    }
                    let load = &mut load[e3 * 2 * nen..(e3 + 1) * 2 * nen];
                    for a in 0..nen {
                        let n = this.shape[q * nen + a][0] * p.sqrt_g * w;
                        load[2 * a] += n * fx[0];
                        load[2 * a + 1] += n * fx[1];
                    }
                }
                Ok(())
            })
        };
        if body_force.is_some() {
            stiffness
                .par_chunks_mut(ne3 * nq)
                .zip(local_loads.par_chunks_mut(ne3 * 2 * nen))
                .enumerate()
                .try_for_each(|(e2, (kq, load))| compute(e2, kq, Some(load)))?;
        } else {
            stiffness
                .par_chunks_mut(ne3 * nq)
                .enumerate()
                .try_for_each(|(e2, kq)| compute(e2, kq, None))?;
        }
        self.stiffness = stiffness;
        self.load = vec![0.0; self.dof_count()];
        if body_force.is_some() {
            let mut nodes = [0; 9];
            for e in 0..ne2 * ne3 {
                self.element_nodes(e, &mut nodes);
                for a in 0..nen {
                    for c in 0..2 {
                        self.load[2 * nodes[a] + c] += local_loads[e * 2 * nen + 2 * a + c];
                    }
                }
            }
        }
        Ok(())
    }

    /// The volumetric part at the reduced `k x k` Gauss points of every element (selective
    /// reduced integration): shape functions, `lambda sqrt(g) w det J` and the divergence
    /// coefficients `tr M_k`, one column of points per `x2` abscissa as in
    /// [`Self::cache_geometry`].
    pub(super) fn cache_reduced_divergence(&mut self) -> Result<(), ElasticityError> {
        let (gp, gw) = gauss_rule(self.order.degree());
        self.reduced_shape = self.shape_table(&gp);
        let [l2, l3] = self.element_size();
        let det = 0.25 * l2 * l3;
        let [ne2, ne3] = self.elements;
        let nqd = gp.len();
        let nr = nqd * nqd;
        let heights = self.column_heights(&gp);
        let lambda = self.problem.material.lambda();
        let mut out = vec![[0.0; 7]; ne2 * ne3 * nr];
        let this = &*self;
        out.par_chunks_mut(ne3 * nr)
            .enumerate()
            .try_for_each(|(e2, column)| {
                this.walk_column(e2, &gp, &heights, |i, e3, j, p, _| {
                    let t = divergence_coefficients(p, &PLANE_STRAIN);
                    let c = lambda * p.sqrt_g * gw[i] * gw[j] * det;
                    column[e3 * nr + i * nqd + j] = [c, t[0], t[1], t[2], t[3], t[4], t[5]];
                    Ok(())
                })
            })?;
        self.reduced_divergence = out;
        Ok(())
    }
}
