//! The 3-D curvilinear Navier operator by Q1/Q2/Qp hexahedral finite elements on the box.

use std::sync::Arc;

use capstan_geometry::ShellPoint;
use capstan_solvers::LinearSolver;
use rayon::prelude::*;

use super::boundary::{Face, FaceComponent, SolidBoundary};
use super::element::{ElementRule, HexElement, LineTables};
use super::grid::BoxGrid;
use crate::continuum::{FaceData, SOLID, divergence_coefficients, energy_matrix, face_flux};
use crate::discretisation::LinearSystem;
use crate::error::ElasticityError;
use crate::finite_element::ElementAssembly;
use crate::finite_element::VolumetricIntegration;
use crate::finite_element::high_order::gauss_legendre;
use crate::material::Material;
use crate::shell_geometry::ShellGeometry;

/// A body force density on the box: covariant components `[f_1, f_2, f_3]` at `(x1, x2, x3)`.
pub type SolidForce = Arc<dyn Fn([f64; 3]) -> [f64; 3] + Send + Sync>;

/// A chart point and its coordinates `(x1, x2, x3)`.
type PointAt = (ShellPoint<f64>, [f64; 3]);

/// Unknowns per node: `v^1, v^2, v^3`.
const COMPONENTS: usize = 3;

/// The curvilinear Navier operator of a 3-D body on the parametric box
/// `[x1a, x1b] x [x2a, x2b] x [0, h]` of a shell chart `sigma + x3 N`, by Q1, Q2 or Qp
/// Lagrange hexahedra ([`HexElement`]; Qp with GLL nodes), assembled from the chart alone.
///
/// # Math
/// ```text
/// a(v, w) = int_B A^ijkl E_kl(v) E_ij(w) sqrt(g) dx1 dx2 dx3
///         = int_B u(v)^T K w(w) dx,    K = energy_matrix(SOLID): 12 x 12 per point
/// l(w)    = int_B f_j w^j sqrt(g) dx + int_faces phi_j w^j dS
/// nabla_i w^j = d_i w^j + Gamma^j_im w^m          (all three directions and components)
/// ```
/// with the twelve inputs `u = [v^1, v^2, v^3, d_1 v^1, ..., d_3 v^3]` of
/// [`crate::continuum::SOLID`]. The full metric is used: `g_12 != 0` (a chart that is not
/// orthogonally parametrised, such as an elliptical cone) needs no special case. Boundary
/// fluxes on a face `x_a = const` (outward sign `s`):
/// ```text
/// traction t_j:   phi_j = sqrt(g) sqrt(g^aa) t_j      (dS = sqrt(g) sqrt(g^aa) dx_b dx_c)
/// stress T^a_j:   phi_j = s sqrt(g) T^a_j
/// ```
/// Quadrature: `(k + 1)^3` Gauss points per element (`k` the degree) (exact for the constant-coefficient
/// integrand of degree `2k` per direction). With [`VolumetricIntegration::Reduced`] the
/// volumetric part `lambda (div v)(div w) sqrt(g)` is integrated at `k^3` points (selective
/// reduced integration), the shear part with the full rule. Dirichlet conditions are imposed
/// symmetrically ([`ElementAssembly`]), so the matrix is symmetric positive definite once the
/// rigid motions are held, and [`capstan_solvers::SparseCholesky`] applies.
///
/// Dofs are numbered `3 node + c` (`c = 0, 1, 2` for `v^1, v^2, v^3`), nodes as
/// [`BoxGrid::node_index`].
///
/// # Errors
/// See [`SolidNavier::new`].
pub struct SolidNavier<G> {
    pub(crate) chart: G,
    pub(crate) material: Material,
    pub(crate) grid: BoxGrid,
    pub(crate) lines: LineTables,
    volumetric: VolumetricIntegration,
    elements: [usize; 3],
    pub(crate) dirichlet: Vec<Option<f64>>,
    assembly: ElementAssembly,
    /// Set when assembled for one process's rows ([`SolidNavier::distribution`]).
    distribution: Option<std::sync::Arc<dyn capstan_solvers::row_distribution::RowDistribution>>,
    system: LinearSystem,
}

impl<G> core::fmt::Debug for SolidNavier<G> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("SolidNavier")
            .field("element", &self.lines.element())
            .field("grid", &self.grid)
            .field("material", &self.material)
            .finish_non_exhaustive()
    }
}

/// Adds `scale B^T K B` to the element matrix `out` (`l x l`, `l = 3 nen`) for the shape
/// values `phi` at one point: `B` maps the local dofs to the twelve inputs
/// (`v^c -> N_a`, `d_p v^c -> d_p N_a`). Only the upper triangle is accumulated.
#[allow(clippy::needless_range_loop)] // mirrors B^T K B
fn add_point(out: &mut [f64], k: &[[f64; 12]; 12], phi: &[[f64; 4]]) {
    let nen = phi.len();
    let l = COMPONENTS * nen;
    // kb[i][3 b + d] = (K B)_(i, (b, d))
    let mut kb = vec![[0.0f64; 12]; l];
    for (b, f) in phi.iter().enumerate() {
        for d in 0..COMPONENTS {
            let col = &mut kb[COMPONENTS * b + d];
            for i in 0..12 {
                col[i] =
                    k[i][d] * f[0] + k[i][3 + d] * f[1] + k[i][6 + d] * f[2] + k[i][9 + d] * f[3];
            }
        }
    }
    for (a, f) in phi.iter().enumerate() {
        for c in 0..COMPONENTS {
            let r = COMPONENTS * a + c;
            let row = &mut out[r * l..(r + 1) * l];
            for (s, col) in kb.iter().enumerate().skip(r) {
                row[s] += f[0] * col[c] + f[1] * col[3 + c] + f[2] * col[6 + c] + f[3] * col[9 + c];
            }
        }
    }
}

impl<G: ShellGeometry + Sync> SolidNavier<G> {
    /// Builds and assembles the operator.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `grid.n1`, `grid.n2` or `grid.n3` if a
    /// direction is not a whole number of elements (Q2: odd node counts, even `n2` when
    /// periodic; Qp: `n - 1`, periodic `n2`, multiples of `p`); [`ElasticityError::InconsistentBoundary`] if grid and conditions disagree on
    /// periodicity or a pinned node is outside the grid; [`ElasticityError::Geometry`] at the
    /// first point where the chart is degenerate (e.g. the focal surface inside the body:
    /// `sqrt(g) <= 0`); [`ElasticityError::NonFinite`] for non-finite boundary data or body
    /// force.
    pub fn new(
        chart: G,
        material: Material,
        grid: BoxGrid,
        boundary: &SolidBoundary,
        body_force: Option<&SolidForce>,
        element: impl Into<HexElement>,
        volumetric: VolumetricIntegration,
    ) -> Result<Self, ElasticityError> {
        let element = element.into();
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
        let np = element.nodes_per_direction();
        let mut connectivity = Vec::with_capacity(elements.iter().product::<usize>() * np.pow(3));
        for e1 in 0..elements[0] {
            for e2 in 0..elements[1] {
                for e3 in 0..elements[2] {
                    for a1 in 0..np {
                        for a2 in 0..np {
                            for a3 in 0..np {
                                connectivity.push(grid.node_index([
                                    k * e1 + a1,
                                    (k * e2 + a2) % n2,
                                    k * e3 + a3,
                                ]));
                            }
                        }
                    }
                }
            }
        }
        // one process of a distributed solve assembles its own rows only
        let distribution = capstan_solvers::row_distribution::installed();
        let assembly = match &distribution {
            None => ElementAssembly::new(
                grid.node_count(),
                COMPONENTS,
                np.pow(3),
                connectivity,
                &dirichlet,
            )?,
            Some(d) => ElementAssembly::for_rows(
                grid.node_count(),
                COMPONENTS,
                np.pow(3),
                &connectivity,
                &dirichlet,
                d.owned(COMPONENTS * grid.node_count(), COMPONENTS),
            )?,
        };
        let mut op = Self {
            chart,
            material,
            grid,
            lines: LineTables::new(element),
            volumetric,
            elements,
            dirichlet,
            assembly,
            distribution,
            system: LinearSystem::from_parts(
                capstan_solvers::SparsityPattern::from_compressed_columns(0, 0, vec![0], vec![])
                    .expect("the empty pattern"),
                vec![],
                vec![],
            )?,
        };
        let mut load = op.body_load(body_force)?;
        op.add_face_loads(boundary, &mut load)?;
        let matrices = op.element_data()?;
        let l = COMPONENTS * np.pow(3);
        op.system = op.assembly.assemble(
            |e, out| {
                out.copy_from_slice(&matrices[e * l * l..(e + 1) * l * l]);
            },
            &load,
            &op.dirichlet,
        )?;
        if let Some(d) = &op.distribution {
            // the right-hand side whole on every rank (its other rows were partial sums)
            d.gather(&mut op.system.rhs, COMPONENTS);
        }
        Ok(op)
    }

    /// The process's share of a distributed solve this operator was assembled for (its
    /// rows only: [`ElementAssembly::for_rows`], the rows
    /// [`capstan_solvers::row_distribution::RowDistribution::owned`] of 3 unknowns a node;
    /// the right-hand side whole), `None` for the whole operator. Set when a distribution
    /// with more than one process is installed
    /// ([`capstan_solvers::row_distribution::install`]); the L2 errors and the linear
    /// [`SolidNavier::solve`] need the whole operator.
    pub fn distribution(
        &self,
    ) -> Option<&std::sync::Arc<dyn capstan_solvers::row_distribution::RowDistribution>> {
        self.distribution.as_ref()
    }

    /// The grid.
    pub fn grid(&self) -> &BoxGrid {
        &self.grid
    }

    /// The element.
    pub fn element(&self) -> HexElement {
        self.lines.element()
    }

    /// Number of unknowns, `3 n1 n2 n3`.
    pub fn dof_count(&self) -> usize {
        COMPONENTS * self.grid.node_count()
    }

    /// The dof of component `c` (0, 1, 2 for `v^1, v^2, v^3`) at node `(i1, i2, i3)`.
    pub fn dof(&self, node: [usize; 3], c: usize) -> usize {
        COMPONENTS * self.grid.node_index(node) + c
    }

    /// The assembled system `A v = b` (symmetric).
    pub fn system(&self) -> &LinearSystem {
        &self.system
    }

    /// Solves the linear problem with `solver` (Cholesky: the matrix is SPD).
    ///
    /// # Errors
    /// Solver failures (a singular matrix when the rigid motions are not held).
    pub fn solve(&self, solver: &mut dyn LinearSolver<f64>) -> Result<Vec<f64>, ElasticityError> {
        self.system.solve(solver)
    }

    /// Element lengths `[L1, L2, L3]` in parameter space.
    fn element_size(&self) -> [f64; 3] {
        let k = self.element().degree() as f64;
        self.grid.spacing().map(|d| k * d)
    }

    /// Lower corner `(x1, x2, x3)` of element `e` of the assembly (numbered
    /// `(e1 ne2 + e2) ne3 + e3` among all: [`ElementAssembly::element_id`]).
    fn element_origin(&self, e: usize) -> [f64; 3] {
        let e = self.assembly.element_id(e);
        let [_, ne2, ne3] = self.elements;
        let k = self.element().degree();
        let (e1, e2, e3) = (e / (ne2 * ne3), (e / ne3) % ne2, e % ne3);
        self.grid.coordinates([k * e1, k * e2, k * e3])
    }

    /// The chart at the tensor points `gp^3` of element `e`, one chart column per `(x1, x2)`
    /// abscissa pair: index `(q1 np + q2) np + q3`.
    fn element_points(&self, e: usize, gp: &[f64]) -> Result<Vec<PointAt>, ElasticityError> {
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

    /// Every element matrix (row-major, `l x l` each, symmetric), in parallel.
    fn element_data(&self) -> Result<Vec<f64>, ElasticityError> {
        let element = self.element();
        let len = self.element_size();
        let full = ElementRule::new(element, element.gauss_1d(), len);
        let nen = full.nen;
        let l = COMPONENTS * nen;
        let reduced = (self.volumetric == VolumetricIntegration::Reduced)
            .then(|| ElementRule::new(element, element.reduced_1d(), len));
        let ne = self.assembly.element_count();
        let mut data = vec![0.0; ne * l * l];
        let (lambda, mu) = (self.material.lambda(), self.material.mu());
        let full_lambda = if reduced.is_some() { 0.0 } else { lambda };
        data.par_chunks_mut(l * l).enumerate().try_for_each(
            |(e, out)| -> Result<(), ElasticityError> {
                let points = self.element_points(e, &full.points)?;
                for (q, (p, _)) in points.iter().enumerate() {
                    let kq = energy_matrix(p, &SOLID, full_lambda, mu, full.weight(q));
                    add_point(out, &kq, full.shape_at(q));
                }
                if let Some(rule) = &reduced {
                    // lambda (div v)(div w) sqrt(g): a rank-one update per reduced point
                    let points = self.element_points(e, &rule.points)?;
                    let mut d = vec![0.0; l];
                    for (r, (p, _)) in points.iter().enumerate() {
                        let c = lambda * p.sqrt_g * rule.weight(r);
                        let t = divergence_coefficients(p, &SOLID);
                        for (a, f) in rule.shape_at(r).iter().enumerate() {
                            for comp in 0..COMPONENTS {
                                d[COMPONENTS * a + comp] = t[comp] * f[0]
                                    + t[3 + comp] * f[1]
                                    + t[6 + comp] * f[2]
                                    + t[9 + comp] * f[3];
                            }
                        }
                        for i in 0..l {
                            let ci = c * d[i];
                            for j in i..l {
                                out[i * l + j] += ci * d[j];
                            }
                        }
                    }
                }
                // the lower triangle from the upper
                for i in 0..l {
                    for j in 0..i {
                        out[i * l + j] = out[j * l + i];
                    }
                }
                Ok(())
            },
        )?;
        Ok(data)
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
        let local: Vec<Vec<f64>> = (0..self.assembly.element_count())
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
            for (a, &node) in self.assembly.nodes(e).iter().enumerate() {
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
    pub fn l2_errors(
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
        let sums = (0..self.assembly.element_count())
            .into_par_iter()
            .map(|e| -> Result<[f64; 2], ElasticityError> {
                let nodes = self.assembly.nodes(e);
                let mut s = [0.0; 2];
                for (q, (p, x)) in self.element_points(e, &rule.points)?.iter().enumerate() {
                    let mut uh = [0.0; 3];
                    for (a, f) in rule.shape_at(q).iter().enumerate() {
                        for (c, u) in uh.iter_mut().enumerate() {
                            *u += f[0] * v[COMPONENTS * nodes[a] + c];
                        }
                    }
                    let u = exact(*x);
                    let norm2 = |e: [f64; 3]| -> f64 {
                        (0..3)
                            .map(|i| (0..3).map(|j| p.metric[i][j] * e[i] * e[j]).sum::<f64>())
                            .sum()
                    };
                    let w = rule.weight(q) * p.sqrt_g;
                    s[0] += w * norm2([uh[0] - u[0], uh[1] - u[1], uh[2] - u[2]]);
                    s[1] += w * norm2(u);
                }
                Ok(s)
            })
            .collect::<Result<Vec<_>, _>>()?;
        // sequential sum in element order: reproducible
        let s = sums
            .iter()
            .fold([0.0; 2], |acc, x| [acc[0] + x[0], acc[1] + x[1]]);
        Ok((s[0].sqrt(), s[1].sqrt()))
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
