//! What the assembled and the matrix-free 3-D operators share: the validated grid and
//! boundary, the element, the chart at quadrature points, the load vector and the error norms.

use std::sync::Arc;

use capstan_geometry::ShellPoint;
use rayon::prelude::*;

use super::boundary::{Face, FaceComponent, SolidBoundary};
use super::element::{ElementRule, HexElement, LineTables};
use super::grid::BoxGrid;
use crate::continuum::{FaceData, face_flux};
use crate::error::ElasticityError;
use crate::finite_element::VolumetricIntegration;
use crate::finite_element::high_order::gauss_legendre;
use crate::material::Material;
use crate::shell_geometry::ShellGeometry;

/// A body force density on the box: covariant components `[f_1, f_2, f_3]` at `(x1, x2, x3)`.
pub type SolidForce = Arc<dyn Fn([f64; 3]) -> [f64; 3] + Send + Sync>;

/// A chart point and its coordinates `(x1, x2, x3)`.
pub(crate) type PointAt = (ShellPoint<f64>, [f64; 3]);

/// Unknowns per node: `v^1, v^2, v^3`.
pub(crate) const COMPONENTS: usize = 3;

/// The body on its box before any operator is built: chart, material, grid (with the GLL
/// node lines of Qp), element, the prescribed value of every dof and the element counts.
pub(crate) struct SolidSetup<G> {
    pub(crate) chart: G,
    pub(crate) material: Material,
    pub(crate) grid: BoxGrid,
    pub(crate) lines: LineTables,
    pub(crate) volumetric: VolumetricIntegration,
    /// Elements per direction.
    pub(crate) elements: [usize; 3],
    pub(crate) dirichlet: Vec<Option<f64>>,
}

impl<G: ShellGeometry + Sync> SolidSetup<G> {
    /// Validates the grid against the element and the boundary, places the Qp node lines
    /// and collects the Dirichlet values (see [`super::SolidNavier::new`] for the errors).
    pub(crate) fn new(
        chart: G,
        material: Material,
        grid: BoxGrid,
        boundary: &SolidBoundary,
        element: HexElement,
        volumetric: VolumetricIntegration,
    ) -> Result<Self, ElasticityError> {
        if grid.is_periodic() != boundary.periodic_x2 {
            return Err(ElasticityError::InconsistentBoundary {
                what: "the grid and the x2 conditions must both be periodic or both not",
            });
        }
        let [n1, n2, n3] = grid.counts();
        if boundary
            .pinned
            .iter()
            .any(|(n, c, _)| n[0] >= n1 || n[1] >= n2 || n[2] >= n3 || *c >= COMPONENTS)
        {
            return Err(ElasticityError::InconsistentBoundary {
                what: "a pinned node is outside the grid",
            });
        }
        element.check_grid([n1, n2, n3], grid.is_periodic())?;
        // the nodes at their true positions: GLL lines inside the Qp elements
        let grid = match element {
            HexElement::Gll(p) => grid.with_gll_lines(p)?,
            HexElement::Uniform(_) => grid,
        };
        let k = element.degree();
        let elements = [
            (n1 - 1) / k,
            if grid.is_periodic() {
                n2 / k
            } else {
                (n2 - 1) / k
            },
            (n3 - 1) / k,
        ];
        let dirichlet = dirichlet_values(&grid, boundary)?;
        Ok(Self {
            chart,
            material,
            grid,
            lines: LineTables::new(element),
            volumetric,
            elements,
            dirichlet,
        })
    }

    /// The element.
    pub(crate) fn element(&self) -> HexElement {
        self.lines.element()
    }

    /// Number of unknowns, `3 n1 n2 n3`.
    pub(crate) fn dof_count(&self) -> usize {
        COMPONENTS * self.grid.node_count()
    }

    /// The dof of component `c` at node `(i1, i2, i3)`.
    pub(crate) fn dof(&self, node: [usize; 3], c: usize) -> usize {
        COMPONENTS * self.grid.node_index(node) + c
    }

    /// Number of elements.
    pub(crate) fn element_count(&self) -> usize {
        self.elements.iter().product()
    }

    /// The nodes of element `e` (numbered `(e1 ne2 + e2) ne3 + e3`), local order
    /// `(a1 np + a2) np + a3`.
    pub(crate) fn element_nodes(&self, e: usize) -> Vec<usize> {
        let [_, ne2, ne3] = self.elements;
        let n2 = self.grid.counts()[1];
        let k = self.element().degree();
        let np = k + 1;
        let (e1, e2, e3) = (e / (ne2 * ne3), (e / ne3) % ne2, e % ne3);
        let mut out = Vec::with_capacity(np * np * np);
        for a1 in 0..np {
            for a2 in 0..np {
                for a3 in 0..np {
                    out.push(
                        self.grid
                            .node_index([k * e1 + a1, (k * e2 + a2) % n2, k * e3 + a3]),
                    );
                }
            }
        }
        out
    }

    /// The load vector `l(w)` (body force and natural face conditions), before the
    /// Dirichlet lifting.
    pub(crate) fn load(
        &self,
        boundary: &SolidBoundary,
        body_force: Option<&SolidForce>,
    ) -> Result<Vec<f64>, ElasticityError> {
        let mut load = self.body_load(body_force)?;
        self.add_face_loads(boundary, &mut load)?;
        Ok(load)
    }

    /// Element lengths `[L1, L2, L3]` in parameter space.
    pub(crate) fn element_size(&self) -> [f64; 3] {
        let k = self.element().degree() as f64;
        self.grid.spacing().map(|d| k * d)
    }

    /// Lower corner `(x1, x2, x3)` of element `e` (numbered `(e1 ne2 + e2) ne3 + e3`).
    pub(crate) fn element_origin(&self, e: usize) -> [f64; 3] {
        let [_, ne2, ne3] = self.elements;
        let k = self.element().degree();
        let (e1, e2, e3) = (e / (ne2 * ne3), (e / ne3) % ne2, e % ne3);
        self.grid.coordinates([k * e1, k * e2, k * e3])
    }

    /// The chart at the tensor points `gp^3` of element `e`, one chart column per `(x1, x2)`
    /// abscissa pair: index `(q1 np + q2) np + q3`.
    pub(crate) fn element_points(
        &self,
        e: usize,
        gp: &[f64],
    ) -> Result<Vec<PointAt>, ElasticityError> {
        let o = self.element_origin(e);
        let len = self.element_size();
        let at = |i: usize, xi: f64| o[i] + 0.5 * (xi + 1.0) * len[i];
        let heights: Vec<f64> = gp.iter().map(|&z| at(2, z)).collect();
        let mut out = Vec::with_capacity(gp.len().pow(3));
        let mut column = Vec::with_capacity(gp.len());
        for &xi in gp {
            for &eta in gp {
                let (x1, x2) = (at(0, xi), at(1, eta));
                column.clear();
                self.chart.shell_column([x1, x2], &heights, &mut column)?;
                for (p, &x3) in column.iter().zip(&heights) {
                    if !(p.sqrt_g > 0.0 && p.sqrt_g.is_finite()) {
                        return Err(capstan_geometry::GeometryError::Degenerate {
                            what: "shell chart: sqrt(g) <= 0 (the focal surface is inside the body)",
                            at: [x1, x2, x3],
                        }
                        .into());
                    }
                    out.push((*p, [x1, x2, x3]));
                }
            }
        }
        Ok(out)
    }

    /// `int f_j N_a sqrt(g) dx` over every element, assembled.
    fn body_load(&self, body_force: Option<&SolidForce>) -> Result<Vec<f64>, ElasticityError> {
        let mut load = vec![0.0; self.dof_count()];
        let Some(force) = body_force else {
            return Ok(load);
        };
        let element = self.element();
        let rule = ElementRule::new(element, element.gauss_1d(), self.element_size());
        let nen = rule.nen;
        let local: Vec<Vec<f64>> = (0..self.element_count())
            .into_par_iter()
            .map(|e| -> Result<Vec<f64>, ElasticityError> {
                let mut out = vec![0.0; COMPONENTS * nen];
                for (q, (p, x)) in self.element_points(e, &rule.points)?.iter().enumerate() {
                    let f = force(*x);
                    if f.iter().any(|v| !v.is_finite()) {
                        return Err(ElasticityError::NonFinite {
                            what: "body force",
                            at: [x[1], x[2]],
                        });
                    }
                    let w = rule.weight(q) * p.sqrt_g;
                    for (a, s) in rule.shape_at(q).iter().enumerate() {
                        for c in 0..COMPONENTS {
                            out[COMPONENTS * a + c] += s[0] * w * f[c];
                        }
                    }
                }
                Ok(out)
            })
            .collect::<Result<_, _>>()?;
        for (e, out) in local.iter().enumerate() {
            for (a, &node) in self.element_nodes(e).iter().enumerate() {
                for c in 0..COMPONENTS {
                    load[COMPONENTS * node + c] += out[COMPONENTS * a + c];
                }
            }
        }
        Ok(load)
    }

    /// Adds `int phi_j N_a dx_b dx_c` over every face with a natural condition (the element's
    /// Gauss rule on each boundary element face).
    fn add_face_loads(
        &self,
        boundary: &SolidBoundary,
        load: &mut [f64],
    ) -> Result<(), ElasticityError> {
        let element = self.element();
        let (gp, gw) = element.gauss_1d();
        let k = element.degree();
        let len = self.element_size();
        let [n1, n2, n3] = self.grid.counts();
        let counts = [n1, n2, n3];
        for face in Face::ALL {
            let Some(cond) = boundary.face(face) else {
                continue;
            };
            if cond
                .0
                .iter()
                .all(|c| matches!(c, FaceComponent::Displacement(_)))
            {
                continue;
            }
            let a = face.normal_index();
            let (b, c) = match a {
                0 => (1, 2),
                1 => (0, 2),
                _ => (0, 1),
            };
            let fixed = if face.is_max() { counts[a] - 1 } else { 0 };
            let xa = self.grid.coordinates([fixed; 3])[a];
            for eb in 0..self.elements[b] {
                for ec in 0..self.elements[c] {
                    let mut origin = [0usize; 3];
                    origin[a] = fixed;
                    origin[b] = k * eb;
                    origin[c] = k * ec;
                    let o = self.grid.coordinates(origin);
                    for (qb, &xb) in gp.iter().enumerate() {
                        let (sb, _) = element.shape_1d(xb);
                        for (qc, &xc) in gp.iter().enumerate() {
                            let (sc, _) = element.shape_1d(xc);
                            let mut x = [0.0; 3];
                            x[a] = xa;
                            x[b] = o[b] + 0.5 * (xb + 1.0) * len[b];
                            x[c] = o[c] + 0.5 * (xc + 1.0) * len[c];
                            let p = self.chart.shell_point(x)?;
                            let weight = gw[qb] * gw[qc] * 0.25 * len[b] * len[c];
                            for (comp, fc) in cond.0.iter().enumerate() {
                                let data = match fc {
                                    FaceComponent::Displacement(_) => continue,
                                    FaceComponent::Traction(f) => FaceData::Traction(f.eval(x)),
                                    FaceComponent::Stress(f) => FaceData::Stress(f.eval(x)),
                                };
                                let flux = face_flux(&p, a, face.sign(), data, [x[b], x[c]])?;
                                for (ab, nb) in sb.iter().enumerate() {
                                    for (ac, nc) in sc.iter().enumerate() {
                                        let mut node = origin;
                                        node[b] += ab;
                                        node[c] += ac;
                                        node[1] %= n2;
                                        let d = self.dof(node, comp);
                                        load[d] += nb * nc * flux * weight;
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
        Ok(())
    }

    /// Error norms of the discrete displacement `v` against `exact` (contravariant
    /// `[v^1, v^2, v^3]` at `(x1, x2, x3)`), by a `(k + 2)^3`-point Gauss rule per element.
    ///
    /// # Math
    /// ```text
    /// |e|^2 = g_ij e^i e^j     (physical length)
    /// l2 = sqrt(int |v_h - v|^2 sqrt(g) dx),   l2_exact = sqrt(int |v|^2 sqrt(g) dx)
    /// ```
    ///
    /// # Errors
    /// [`ElasticityError::DimensionMismatch`] for a wrong length; geometry failures.
    pub(crate) fn l2_errors(
        &self,
        v: &[f64],
        exact: &(dyn Fn([f64; 3]) -> [f64; 3] + Sync),
    ) -> Result<(f64, f64), ElasticityError> {
        ElasticityError::check_length("displacement", self.dof_count(), v.len())?;
        let element = self.element();
        let rule = ElementRule::new(
            element,
            gauss_legendre(element.nodes_per_direction() + 1),
            self.element_size(),
        );
        let sums = (0..self.element_count())
            .into_par_iter()
            .map(|e| -> Result<[f64; 2], ElasticityError> {
                let nodes = self.element_nodes(e);
                let mut s = [0.0; 2];
                for (q, (p, x)) in self.element_points(e, &rule.points)?.iter().enumerate() {
                    let mut uh = [0.0; 3];
                    for (a, f) in rule.shape_at(q).iter().enumerate() {
                        for (c, u) in uh.iter_mut().enumerate() {
                            *u += f[0] * v[COMPONENTS * nodes[a] + c];
                        }
                    }
                    let u = exact(*x);
                    super::norms::add_error_point(
                        &mut s,
                        rule.weight(q) * p.sqrt_g,
                        &p.metric,
                        uh,
                        u,
                    );
                }
                Ok(s)
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(super::norms::error_norms(&sums))
    }
}

/// The prescribed value of every dof: pinned dofs first, then the first `Displacement` face
/// condition in the order `x3`, `x1`, `x2` faces.
fn dirichlet_values(
    grid: &BoxGrid,
    boundary: &SolidBoundary,
) -> Result<Vec<Option<f64>>, ElasticityError> {
    let [n1, n2, n3] = grid.counts();
    let mut out = vec![None; COMPONENTS * grid.node_count()];
    for m in 0..grid.node_count() {
        let [i1, i2, i3] = grid.node(m);
        let x = grid.coordinates([i1, i2, i3]);
        let mut faces = Vec::with_capacity(3);
        if i3 == 0 {
            faces.push(Face::X3Min);
        }
        if i3 == n3 - 1 {
            faces.push(Face::X3Max);
        }
        if i1 == 0 {
            faces.push(Face::X1Min);
        }
        if i1 == n1 - 1 {
            faces.push(Face::X1Max);
        }
        if i2 == 0 {
            faces.push(Face::X2Min);
        }
        if i2 == n2 - 1 {
            faces.push(Face::X2Max);
        }
        for c in 0..COMPONENTS {
            let value = faces.iter().find_map(|&f| match boundary.face(f) {
                Some(cond) => match &cond.0[c] {
                    FaceComponent::Displacement(g) => Some(g.eval(x)),
                    _ => None,
                },
                None => None,
            });
            out[COMPONENTS * m + c] = value;
        }
    }
    for &(node, c, value) in &boundary.pinned {
        out[COMPONENTS * grid.node_index(node) + c] = Some(value);
    }
    if let Some(d) = out.iter().position(|v| v.is_some_and(|x| !x.is_finite())) {
        let x = grid.coordinates(grid.node(d / COMPONENTS));
        return Err(ElasticityError::NonFinite {
            what: "prescribed displacement",
            at: [x[1], x[2]],
        });
    }
    Ok(out)
}

impl<G> SolidSetup<G> {
    /// The gradient-recovery stencil at a node: `(node, [value, d_1, d_2, d_3])` weights
    /// (Q1/Q2: second-order differences of the nodal values, one-sided at the faces; Qp: the
    /// element polynomials' derivatives averaged over the elements sharing the node; see
    /// [`LineTables`]).
    pub(crate) fn node_stencil(&self, node: [usize; 3]) -> Vec<([usize; 3], [f64; 4])> {
        let counts = self.grid.counts();
        let spacing = self.grid.spacing();
        let periodic = [false, self.grid.is_periodic(), false];
        let mut out = Vec::with_capacity(16);
        out.push((node, [1.0, 0.0, 0.0, 0.0]));
        for q in 0..3 {
            for (i, w) in self
                .lines
                .derivative(node[q], counts[q], spacing[q], periodic[q])
            {
                let mut at = node;
                at[q] = i;
                let mut weights = [0.0; 4];
                weights[1 + q] = w;
                out.push((at, weights));
            }
        }
        out
    }
}
