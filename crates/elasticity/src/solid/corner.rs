//! [`SolidCornerNavier`]: the 3-D body by Qp hexahedra on the 2-D corner-refined mesh of the
//! `(x2, x3)` rectangle extruded along `x1`, refined toward the four edges where the contact
//! face `x3 = 0` and the top face `x3 = h` meet the ends `x2 = x2a, x2b`.

use capstan_solvers::LinearSolver;
use rayon::prelude::*;

use super::boundary::{Face, FaceComponent, SolidBoundary};
use super::grid::BoxGrid;
use super::operator::{SolidForce, add_point};
use super::setup::COMPONENTS;
use crate::continuum::{FaceData, SOLID, energy_matrix, face_flux};
use crate::discretisation::LinearSystem;
use crate::error::ElasticityError;
use crate::finite_element::high_order::corner_mesh::layout::{
    Layout, bilinear, local_edges, sides_of,
};
use crate::finite_element::high_order::{CornerSettings, gauss_legendre, gll_rule, lagrange_basis};
use crate::finite_element::{ElementAssembly, check_whole_elements};
use crate::material::Material;
use crate::shell_geometry::ShellGeometry;

/// Bits of the `(x2, x3)` rectangle's sides in `sides_of`: `x2 = x2a` (1), `x2 = x2b` (2),
/// `x3 = 0` (4), `x3 = h` (8), with the face over each.
const SIDE_FACES: [(Face, u8); 4] = [
    (Face::X2Min, 1),
    (Face::X2Max, 2),
    (Face::X3Min, 4),
    (Face::X3Max, 8),
];

/// The 3-D curvilinear Navier operator by Qp hexahedra (GLL nodes) on the corner-refined
/// mesh of the `(x2, x3)` rectangle ([`CornerSettings`]: coarse cells, geometric trapezoid
/// layers in the four corner cells) extruded along `x1` in `(n1 - 1)/p` equal elements:
/// refinement local to the four edges (along `x1`) where the contact face and the top face
/// meet the loaded ends, conforming throughout (no hanging nodes).
///
/// # Math
/// The weak form of [`super::SolidNavier`]. Element `(e1, q)` is the image of `[-1, 1]^3`
/// under
/// ```text
/// x1 = x1a + (e1 + (1 + xi1)/2) L1,   (x2, x3) = sum_i N_i(xi2, xi3) y_i
/// ```
/// (affine in `x1`, bilinear in `(x2, x3)` through the quad's vertices `y_i`), so with
/// `J = d(x2, x3)/d(xi2, xi3)` the physical derivatives are
/// ```text
/// d_1 = (2 / L1) d_xi1,   (d_2, d_3) = J^-T (d_xi2, d_xi3),   dx = (L1 / 2) det J dxi
/// ```
/// and every Gauss point (`(p + 1)^3` per element) adds `B^T K B w` with the twelve-input
/// energy matrix `K` of [`crate::continuum::SOLID`] (the point kernel of
/// [`super::SolidNavier`]). Natural conditions: the face flux of [`face_flux()`] per parameter
/// area, `dx2 dx3 = det J dxi2 dxi3` on the `x1` faces, `dx1 ds = (L1 / 2)(|e| / 2) dxi1 dt`
/// along an edge `e` of a quad on an `x2` or `x3` side. A dof on several faces takes the first
/// `Displacement` condition in the order `x3`, `x1`, `x2` faces (as [`SolidBoundary`]).
/// With `layers = 0` and `cells = [(n2 - 1)/p, (n3 - 1)/p]` the mesh is the tensor grid of
/// `fem-qp` and the operator is [`super::SolidNavier`] with [`super::HexElement::Gll`] up to
/// the node numbering.
///
/// Nodes are numbered `i1 N + m` (`i1` the `x1` node line, `0 ... n1 - 1`; `m` the 2-D node
/// of the corner layout, `N` of them); dofs `3 node + c`.
///
/// Scope: non-periodic `x2`, no pinned dofs, full integration, assembled (sparse direct
/// solvers).
pub struct SolidCornerNavier<G> {
    pub(super) mesh: Extruded<G>,
    /// The box the mesh fills (its ranges and `n1`; its `n2 x n3` nodes are not the mesh's).
    grid: BoxGrid,
    material: Material,
    dirichlet: Vec<Option<f64>>,
    system: LinearSystem,
}

/// A node of the contact face `x3 = 0` with what its contact rows need.
#[derive(Debug, Clone)]
pub(crate) struct FaceNode {
    /// The node (`i1 N + m`).
    pub node: usize,
    /// `i1` and the node's rank `k` in `x2` order along its `x1` line.
    pub i1: usize,
    /// Rank in `x2` order.
    pub k: usize,
    /// `int N dx1 dx2` of the node's basis function over the face (parameter area).
    pub weight: f64,
    /// `(node, [value, d_1, d_2, d_3])`: the value and the physical gradient at the node
    /// from the element polynomials, averaged over the face elements holding it with the
    /// weights of their share of `weight`.
    pub stencil: Vec<(usize, [f64; 4])>,
}

/// The extruded mesh on the chart: what the assembly, the error norms and the outputs share.
pub(super) struct Extruded<G> {
    chart: G,
    settings: CornerSettings,
    layout: Layout,
    /// `x1` of every node line.
    x1_lines: Vec<f64>,
    /// `[x1a, L1]`: the first line and the element length along `x1`.
    x1_elements: [f64; 2],
    /// Elements along `x1`.
    ne1: usize,
    /// The GLL nodes of order `p` on `[-1, 1]`.
    pub(super) gll: Vec<f64>,
    /// `[x2, x3]` of every 2-D node.
    positions: Vec<[f64; 2]>,
}

impl<G> core::fmt::Debug for SolidCornerNavier<G> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("SolidCornerNavier")
            .field("settings", &self.mesh.settings)
            .field("x1_elements", &self.mesh.ne1)
            .field("dofs", &self.dirichlet.len())
            .finish_non_exhaustive()
    }
}

/// Per element: the matrix (row-major, `l x l`) and the body-force load (`l`).
type ElementData = (Vec<f64>, Vec<f64>);

impl<G: ShellGeometry + Sync> SolidCornerNavier<G> {
    /// Builds and assembles the operator on the box of `grid` (its `x1`, `x2` ranges, its
    /// thickness and its `n1` node lines along `x1`; `n2`, `n3` are not used: `settings.cells`
    /// cut the rectangle).
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `order`, `cells`, `layers` or `ratio`
    /// ([`CornerSettings::check`]), `grid.n1` when `n1 - 1` is not a multiple of `p`,
    /// `grid.periodic` for a periodic `x2`, `boundary.pinned` for pinned dofs;
    /// [`ElasticityError::Geometry`] where the chart is degenerate inside the body
    /// (`sqrt(g) <= 0`); [`ElasticityError::NonFinite`] for non-finite data or body force.
    pub fn new(
        chart: G,
        material: Material,
        grid: BoxGrid,
        boundary: &SolidBoundary,
        body_force: Option<&SolidForce>,
        settings: CornerSettings,
    ) -> Result<Self, ElasticityError> {
        settings.check()?;
        if grid.is_periodic() || boundary.periodic_x2 {
            return Err(ElasticityError::InvalidParameter {
                field: "grid.periodic",
                value: 1.0,
                allowed: "a non-periodic x2 (corner refinement needs the four corner edges)",
            });
        }
        if !boundary.pinned.is_empty() {
            return Err(ElasticityError::InvalidParameter {
                field: "boundary.pinned",
                value: boundary.pinned.len() as f64,
                allowed: "no pinned dofs (Dirichlet data from the faces only)",
            });
        }
        let p = settings.order;
        let n1 = grid.counts()[0];
        check_whole_elements(
            "grid.n1",
            n1,
            false,
            p,
            [
                "p e + 1 nodes (e elements of order p = discretisation.order) with fem-qp-corner",
                "",
            ],
        )?;
        let ne1 = (n1 - 1) / p;
        let [x1a, x1b] = grid.x1_range();
        let l1 = (x1b - x1a) / ne1 as f64;
        let (gll, _) = gll_rule(p);
        let x1_lines = (0..n1)
            .map(|i| {
                if i == n1 - 1 {
                    x1b
                } else {
                    x1a + ((i / p) as f64 + 0.5 * (1.0 + gll[i % p])) * l1
                }
            })
            .collect();
        let rect = [grid.x2_range(), [0.0, grid.thickness()]];
        let layout = Layout::new(rect, &settings);
        let np = p + 1;
        let mut positions = vec![[0.0; 2]; layout.node_count];
        for (q, quad) in layout.quads.iter().enumerate() {
            let v = quad.map(|i| layout.vertices[i]);
            for a2 in 0..np {
                for a3 in 0..np {
                    let m = layout.element_nodes[q * np * np + a2 * np + a3];
                    positions[m] = bilinear(&v, [gll[a2], gll[a3]]).0;
                }
            }
        }
        let op = Extruded {
            chart,
            settings,
            layout,
            x1_lines,
            x1_elements: [x1a, l1],
            ne1,
            gll,
            positions,
        };
        let dirichlet = op.dirichlet_values(boundary, rect)?;
        let data = op.element_data(material, body_force)?;
        let nen = np * np * np;
        let l = COMPONENTS * nen;
        let mut load = vec![0.0; op.dof_count()];
        let mut connectivity = Vec::with_capacity(op.element_count() * nen);
        for (e, (_, f)) in data.iter().enumerate() {
            let nodes = op.element_nodes(e);
            for (a, &m) in nodes.iter().enumerate() {
                for c in 0..COMPONENTS {
                    load[COMPONENTS * m + c] += f[COMPONENTS * a + c];
                }
            }
            connectivity.extend(nodes);
        }
        op.add_face_loads(boundary, rect, &mut load)?;
        let assembly =
            ElementAssembly::new(op.node_count(), COMPONENTS, nen, connectivity, &dirichlet)?;
        let system = assembly.assemble(
            |e, out| out.copy_from_slice(&data[e].0[..l * l]),
            &load,
            &dirichlet,
        )?;
        Ok(Self {
            mesh: op,
            grid,
            material,
            dirichlet,
            system,
        })
    }

    /// The box the mesh fills: its `x1`, `x2` ranges, thickness and `n1` node lines (its
    /// `n2 x n3` nodes are not the mesh's: [`crate::solid::SolidOutput::output_mesh`]).
    pub fn box_grid(&self) -> &BoxGrid {
        &self.grid
    }

    /// The corner layout's settings.
    pub fn settings(&self) -> CornerSettings {
        self.mesh.settings
    }

    /// Number of hexahedra: `(n1 - 1)/p` times the quads of the corner layout.
    pub fn element_count(&self) -> usize {
        self.mesh.element_count()
    }

    /// Number of nodes, `n1 N`.
    pub fn node_count(&self) -> usize {
        self.mesh.node_count()
    }

    /// Number of unknowns, `3 n1 N` (prescribed ones included).
    pub fn dof_count(&self) -> usize {
        self.mesh.dof_count()
    }

    /// `(x1, x2, x3)` of node `m`.
    ///
    /// # Panics
    /// For `m` outside the nodes.
    #[track_caller]
    pub fn node_position(&self, m: usize) -> [f64; 3] {
        self.mesh.node_position(m)
    }

    /// The chart.
    pub(crate) fn chart(&self) -> &G {
        &self.mesh.chart
    }

    /// The material.
    pub(crate) fn material(&self) -> Material {
        self.material
    }

    /// The nodes of the contact face `x3 = 0`, by `x1` line and in increasing `x2` along it.
    ///
    /// # Math
    /// ```text
    /// weight = sum over face elements e holding the node of (w_a1 L1 / 2)(w_k |edge| / 2)
    /// grad v(node) = sum_e theta_e grad v_e(node),  theta_e = its term / weight
    /// ```
    /// (`w` the GLL weights, `a1` and `k` the node's place in the element along `x1` and along
    /// its face edge): the exact integral of the basis function over the face, and the
    /// element gradients averaged by that share (equal shares on a uniform mesh: the tensor
    /// grid's average).
    pub(crate) fn face_nodes(&self) -> Vec<FaceNode> {
        self.mesh.face_nodes()
    }

    /// The prescribed value of every dof (`None`: free).
    pub fn dirichlet(&self) -> &[Option<f64>] {
        &self.dirichlet
    }

    /// The assembled system `A v = b` (symmetric).
    pub fn system(&self) -> &LinearSystem {
        &self.system
    }

    /// Solves the linear problem with `solver` (Cholesky: the matrix is SPD once the rigid
    /// motions are held).
    ///
    /// # Errors
    /// Solver failures.
    pub fn solve(&self, solver: &mut dyn LinearSolver<f64>) -> Result<Vec<f64>, ElasticityError> {
        self.system.solve(solver)
    }

    /// Error norms of the discrete displacement `v` against `exact` (contravariant
    /// `[v^1, v^2, v^3]` at `(x1, x2, x3)`), by a `(p + 2)^3`-point Gauss rule per element.
    ///
    /// # Math
    /// ```text
    /// |e|^2 = g_ij e^i e^j     (physical length)
    /// l2 = sqrt(int |v_h - v|^2 sqrt(g) dx),   l2_exact = sqrt(int |v|^2 sqrt(g) dx)
    /// dx = (L1 / 2) det J dxi1 dxi2 dxi3
    /// ```
    ///
    /// # Errors
    /// [`ElasticityError::DimensionMismatch`] for a wrong length; geometry failures.
    pub fn l2_errors(
        &self,
        v: &[f64],
        exact: &(dyn Fn([f64; 3]) -> [f64; 3] + Sync),
    ) -> Result<(f64, f64), ElasticityError> {
        self.mesh.l2_errors(v, exact)
    }
}

impl<G: ShellGeometry + Sync> Extruded<G> {
    /// Number of hexahedra: `(n1 - 1)/p` times the quads of the corner layout.
    pub(super) fn element_count(&self) -> usize {
        self.ne1 * self.layout.quads.len()
    }

    /// Number of nodes, `n1 N`.
    pub(super) fn node_count(&self) -> usize {
        self.x1_lines.len() * self.layout.node_count
    }

    /// Number of unknowns, `3 n1 N` (prescribed ones included).
    fn dof_count(&self) -> usize {
        COMPONENTS * self.node_count()
    }

    /// `(x1, x2, x3)` of node `m`.
    ///
    /// # Panics
    /// For `m` outside the nodes.
    #[track_caller]
    pub(super) fn node_position(&self, m: usize) -> [f64; 3] {
        let n = self.layout.node_count;
        let [x2, x3] = self.positions[m % n];
        [self.x1_lines[m / n], x2, x3]
    }

    /// The nodes of element `e = e1 Q + q` (`Q` quads), local order `(a1 np + a2) np + a3`.
    pub(super) fn element_nodes(&self, e: usize) -> Vec<usize> {
        let p = self.settings.order;
        let np = p + 1;
        let nq = self.layout.quads.len();
        let n = self.layout.node_count;
        let (e1, q) = (e / nq, e % nq);
        let plane = &self.layout.element_nodes[q * np * np..(q + 1) * np * np];
        (0..np)
            .flat_map(|a1| plane.iter().map(move |&m| (p * e1 + a1) * n + m))
            .collect()
    }

    /// The quad's vertices of element `e`.
    fn quad_vertices(&self, e: usize) -> [[f64; 2]; 4] {
        let q = e % self.layout.quads.len();
        self.layout.quads[q].map(|i| self.layout.vertices[i])
    }

    /// `x1` at `xi1` in element `e`.
    fn x1_at(&self, e: usize, xi1: f64) -> f64 {
        let e1 = e / self.layout.quads.len();
        let [x1a, l1] = self.x1_elements;
        x1a + (e1 as f64 + 0.5 * (1.0 + xi1)) * l1
    }

    /// The chart at `x`, checked non-degenerate.
    pub(super) fn point(
        &self,
        x: [f64; 3],
    ) -> Result<capstan_geometry::ShellPoint<f64>, ElasticityError> {
        let p = self.chart.shell_point(x)?;
        if !(p.sqrt_g > 0.0 && p.sqrt_g.is_finite()) {
            return Err(capstan_geometry::GeometryError::Degenerate {
                what: "shell chart: sqrt(g) <= 0 (the focal surface is inside the body)",
                at: x,
            }
            .into());
        }
        Ok(p)
    }

    /// `[N_a, d_1 N_a, d_2 N_a, d_3 N_a]` of every node at the reference point `xi` of
    /// element `e`, with the point `(x1, x2, x3)` and the volume factor `(L1 / 2) det J`.
    pub(super) fn shape_at(&self, e: usize, xi: [f64; 3]) -> (Vec<[f64; 4]>, [f64; 3], f64) {
        let (b1, d1) = lagrange_basis(&self.gll, xi[0]);
        let (b2, d2) = lagrange_basis(&self.gll, xi[1]);
        let (b3, d3) = lagrange_basis(&self.gll, xi[2]);
        let (y, j) = bilinear(&self.quad_vertices(e), [xi[1], xi[2]]);
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        // G = J^-T
        let g = [
            [j[1][1] / det, -j[1][0] / det],
            [-j[0][1] / det, j[0][0] / det],
        ];
        let s1 = 2.0 / self.x1_elements[1];
        let np = self.gll.len();
        let mut phi = Vec::with_capacity(np * np * np);
        for a1 in 0..np {
            for a2 in 0..np {
                for a3 in 0..np {
                    let (r2, r3) = (b1[a1] * d2[a2] * b3[a3], b1[a1] * b2[a2] * d3[a3]);
                    phi.push([
                        b1[a1] * b2[a2] * b3[a3],
                        s1 * d1[a1] * b2[a2] * b3[a3],
                        g[0][0] * r2 + g[0][1] * r3,
                        g[1][0] * r2 + g[1][1] * r3,
                    ]);
                }
            }
        }
        let x = [self.x1_at(e, xi[0]), y[0], y[1]];
        (phi, x, 0.5 * self.x1_elements[1] * det)
    }

    /// Every element matrix and body-force load, in parallel (Gauss rule of `p + 1` points
    /// per direction).
    fn element_data(
        &self,
        material: Material,
        body_force: Option<&SolidForce>,
    ) -> Result<Vec<ElementData>, ElasticityError> {
        let np = self.settings.order + 1;
        let l = COMPONENTS * np * np * np;
        let (gp, gw) = gauss_legendre(np);
        let (lambda, mu) = (material.lambda(), material.mu());
        (0..self.element_count())
            .into_par_iter()
            .map(|e| -> Result<ElementData, ElasticityError> {
                let mut matrix = vec![0.0; l * l];
                let mut load = vec![0.0; l];
                for (q1, &xi1) in gp.iter().enumerate() {
                    for (q2, &xi2) in gp.iter().enumerate() {
                        for (q3, &xi3) in gp.iter().enumerate() {
                            let (phi, x, det) = self.shape_at(e, [xi1, xi2, xi3]);
                            let w = gw[q1] * gw[q2] * gw[q3] * det;
                            let pt = self.point(x)?;
                            add_point(
                                &mut matrix,
                                &energy_matrix(&pt, &SOLID, lambda, mu, w),
                                &phi,
                            );
                            if let Some(force) = body_force {
                                let f = force(x);
                                if f.iter().any(|v| !v.is_finite()) {
                                    return Err(ElasticityError::NonFinite {
                                        what: "body force",
                                        at: [x[1], x[2]],
                                    });
                                }
                                let ws = w * pt.sqrt_g;
                                for (a, s) in phi.iter().enumerate() {
                                    for c in 0..COMPONENTS {
                                        load[COMPONENTS * a + c] += s[0] * ws * f[c];
                                    }
                                }
                            }
                        }
                    }
                }
                // the lower triangle from the upper (add_point fills the upper)
                for i in 0..l {
                    for j in 0..i {
                        matrix[i * l + j] = matrix[j * l + i];
                    }
                }
                Ok((matrix, load))
            })
            .collect()
    }

    /// See [`SolidCornerNavier::face_nodes`].
    fn face_nodes(&self) -> Vec<FaceNode> {
        let p = self.settings.order;
        let np = p + 1;
        let (_, gw) = gll_rule(p);
        let rect = self.rect();
        let nq = self.layout.quads.len();
        let n = self.layout.node_count;
        // the quads' edges on x3 = 0: (q, local node, GLL weight times the half-length)
        let mut holders: std::collections::BTreeMap<usize, Vec<(usize, usize, f64)>> =
            std::collections::BTreeMap::new();
        for q in 0..nq {
            let nodes = &self.layout.element_nodes[q * np * np..(q + 1) * np * np];
            for (edge, line) in self.quad_edges(q) {
                let [xs, xe] = edge.map(|i| self.layout.vertices[i]);
                if sides_of(xs, rect) & sides_of(xe, rect) & 4 == 0 {
                    continue;
                }
                let half = 0.5 * ((xe[0] - xs[0]).powi(2) + (xe[1] - xs[1]).powi(2)).sqrt();
                for (k, &m) in line.iter().enumerate() {
                    let a = nodes.iter().position(|&x| x == m).unwrap_or(0);
                    holders.entry(m).or_default().push((q, a, gw[k] * half));
                }
            }
        }
        let mut face: Vec<usize> = holders.keys().copied().collect();
        face.sort_by(|&a, &b| self.positions[a][0].total_cmp(&self.positions[b][0]));
        let n1 = self.x1_lines.len();
        let l1 = self.x1_elements[1];
        let mut out = Vec::with_capacity(n1 * face.len());
        for i1 in 0..n1 {
            // the x1 elements holding line i1 and the node's place in each
            let along: Vec<(usize, usize)> = if i1 % p == 0 {
                [
                    (i1 / p).checked_sub(1).map(|e| (e, p)),
                    (i1 / p < self.ne1).then_some((i1 / p, 0)),
                ]
                .into_iter()
                .flatten()
                .collect()
            } else {
                vec![(i1 / p, i1 % p)]
            };
            for (k, &m) in face.iter().enumerate() {
                let mut weight = 0.0;
                let mut grad: std::collections::BTreeMap<usize, [f64; 4]> =
                    std::collections::BTreeMap::new();
                let mut terms = Vec::new();
                for &(e1, a1) in &along {
                    for &(q, a, w) in &holders[&m] {
                        let theta = gw[a1] * 0.5 * l1 * w;
                        weight += theta;
                        let e = e1 * nq + q;
                        let xi = [self.gll[a1], self.gll[a / np], self.gll[a % np]];
                        terms.push((e, xi, theta));
                    }
                }
                for (e, xi, theta) in terms {
                    let (phi, _, _) = self.shape_at(e, xi);
                    for (f, node) in phi.iter().zip(self.element_nodes(e)) {
                        let g = grad.entry(node).or_insert([0.0; 4]);
                        for d in 1..4 {
                            g[d] += theta / weight * f[d];
                        }
                    }
                }
                let node = i1 * n + m;
                grad.entry(node).or_insert([0.0; 4])[0] = 1.0;
                out.push(FaceNode {
                    node,
                    i1,
                    k,
                    weight,
                    stencil: grad.into_iter().collect(),
                });
            }
        }
        out
    }

    /// The `(x2, x3)` rectangle.
    fn rect(&self) -> [[f64; 2]; 2] {
        let v = &self.layout.vertices;
        let lo = v
            .iter()
            .fold([f64::INFINITY; 2], |a, x| [a[0].min(x[0]), a[1].min(x[1])]);
        let hi = v.iter().fold([f64::NEG_INFINITY; 2], |a, x| {
            [a[0].max(x[0]), a[1].max(x[1])]
        });
        [[lo[0], hi[0]], [lo[1], hi[1]]]
    }

    /// The 2-D nodes on each side of the rectangle: bit mask per node (`sides_of` bits).
    fn node_sides(&self, rect: [[f64; 2]; 2]) -> Vec<u8> {
        let np = self.settings.order + 1;
        let mut out = vec![0u8; self.layout.node_count];
        for q in 0..self.layout.quads.len() {
            for (edge, line) in self.quad_edges(q) {
                let [xs, xe] = edge.map(|i| self.layout.vertices[i]);
                let mask = sides_of(xs, rect) & sides_of(xe, rect);
                line[..np].iter().for_each(|&m| out[m] |= mask);
            }
        }
        out
    }

    /// The four edges of quad `q` (start, end vertices) with the 2-D nodes along each from
    /// its start vertex.
    fn quad_edges(&self, q: usize) -> Vec<([usize; 2], Vec<usize>)> {
        let p = self.settings.order;
        let np = p + 1;
        let nodes = &self.layout.element_nodes[q * np * np..(q + 1) * np * np];
        let lines: [Vec<usize>; 4] = [
            (0..np).map(|b| nodes[b]).collect(),
            (0..np).map(|b| nodes[p * np + b]).collect(),
            (0..np).map(|a| nodes[a * np]).collect(),
            (0..np).map(|a| nodes[a * np + p]).collect(),
        ];
        local_edges(&self.layout.quads[q])
            .into_iter()
            .zip(lines)
            .collect()
    }

    /// The prescribed value of every dof (the first `Displacement` condition in the order
    /// `x3`, `x1`, `x2` faces).
    fn dirichlet_values(
        &self,
        boundary: &SolidBoundary,
        rect: [[f64; 2]; 2],
    ) -> Result<Vec<Option<f64>>, ElasticityError> {
        let sides = self.node_sides(rect);
        let n = self.layout.node_count;
        let n1 = self.x1_lines.len();
        let mut out = vec![None; self.dof_count()];
        for node in 0..self.node_count() {
            let (i1, m) = (node / n, node % n);
            let mask = sides[m];
            let mut faces = Vec::with_capacity(3);
            let bit = |b: u8| mask & b != 0;
            if bit(4) {
                faces.push(Face::X3Min);
            }
            if bit(8) {
                faces.push(Face::X3Max);
            }
            if i1 == 0 {
                faces.push(Face::X1Min);
            }
            if i1 == n1 - 1 {
                faces.push(Face::X1Max);
            }
            if bit(1) {
                faces.push(Face::X2Min);
            }
            if bit(2) {
                faces.push(Face::X2Max);
            }
            if faces.is_empty() {
                continue;
            }
            let x = self.node_position(node);
            for c in 0..COMPONENTS {
                let value = faces.iter().find_map(|&f| match boundary.face(f) {
                    Some(cond) => match &cond.0[c] {
                        FaceComponent::Displacement(g) => Some(g.eval(x)),
                        _ => None,
                    },
                    None => None,
                });
                if let Some(v) = value {
                    if !v.is_finite() {
                        return Err(ElasticityError::NonFinite {
                            what: "prescribed displacement",
                            at: [x[1], x[2]],
                        });
                    }
                    out[COMPONENTS * node + c] = Some(v);
                }
            }
        }
        Ok(out)
    }

    /// Adds `int phi_c N_a dx_b dx_c` over every face with a natural condition (Gauss rule of
    /// `p + 1` points per direction on each boundary element face).
    fn add_face_loads(
        &self,
        boundary: &SolidBoundary,
        rect: [[f64; 2]; 2],
        load: &mut [f64],
    ) -> Result<(), ElasticityError> {
        let p = self.settings.order;
        let np = p + 1;
        let (gp, gw) = gauss_legendre(np);
        let n = self.layout.node_count;
        let nq = self.layout.quads.len();
        let basis: Vec<Vec<f64>> = gp.iter().map(|&x| lagrange_basis(&self.gll, x).0).collect();
        let natural = |face: Face| {
            boundary.face(face).filter(|cond| {
                cond.0
                    .iter()
                    .any(|c| !matches!(c, FaceComponent::Displacement(_)))
            })
        };
        let mut add = |x: [f64; 3],
                       face: Face,
                       weight: f64,
                       nodes: &mut dyn Iterator<Item = (usize, f64)>|
         -> Result<(), ElasticityError> {
            let Some(cond) = natural(face) else {
                return Ok(());
            };
            let a = face.normal_index();
            let (b, c) = match a {
                0 => (1, 2),
                1 => (0, 2),
                _ => (0, 1),
            };
            let pt = self.point(x)?;
            let mut flux = [0.0; 3];
            for (comp, fc) in cond.0.iter().enumerate() {
                let data = match fc {
                    FaceComponent::Displacement(_) => continue,
                    FaceComponent::Traction(f) => FaceData::Traction(f.eval(x)),
                    FaceComponent::Stress(f) => FaceData::Stress(f.eval(x)),
                };
                flux[comp] = face_flux(&pt, a, face.sign(), data, [x[b], x[c]])? * weight;
            }
            for (m, s) in nodes {
                for (comp, f) in flux.iter().enumerate() {
                    load[COMPONENTS * m + comp] += s * f;
                }
            }
            Ok(())
        };
        // the x1 faces: every quad at the first and the last node line
        for (face, e1, a1, xi1) in [
            (Face::X1Min, 0, 0, -1.0),
            (Face::X1Max, self.ne1 - 1, p, 1.0),
        ] {
            if natural(face).is_none() {
                continue;
            }
            for q in 0..nq {
                let e = e1 * nq + q;
                let v = self.quad_vertices(e);
                let plane = &self.layout.element_nodes[q * np * np..(q + 1) * np * np];
                let base = (p * e1 + a1) * n;
                for (q2, &xi2) in gp.iter().enumerate() {
                    for (q3, &xi3) in gp.iter().enumerate() {
                        let (y, j) = bilinear(&v, [xi2, xi3]);
                        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
                        let x = [self.x1_at(e, xi1), y[0], y[1]];
                        let mut nodes = plane
                            .iter()
                            .enumerate()
                            .map(|(a, &m)| (base + m, basis[q2][a / np] * basis[q3][a % np]));
                        add(x, face, gw[q2] * gw[q3] * det, &mut nodes)?;
                    }
                }
            }
        }
        // the x2 and x3 faces: every quad edge on a side, times every x1 element
        for q in 0..nq {
            for (edge, line) in self.quad_edges(q) {
                let [xs, xe] = edge.map(|i| self.layout.vertices[i]);
                let mask = sides_of(xs, rect) & sides_of(xe, rect);
                for &(face, bit) in &SIDE_FACES {
                    if mask & bit == 0 || natural(face).is_none() {
                        continue;
                    }
                    let length = ((xe[0] - xs[0]).powi(2) + (xe[1] - xs[1]).powi(2)).sqrt();
                    for e1 in 0..self.ne1 {
                        let e = e1 * nq + q;
                        for (q1, &xi1) in gp.iter().enumerate() {
                            for (qs, &s) in gp.iter().enumerate() {
                                let t = 0.5 * (s + 1.0);
                                let x = [
                                    self.x1_at(e, xi1),
                                    xs[0] + t * (xe[0] - xs[0]),
                                    xs[1] + t * (xe[1] - xs[1]),
                                ];
                                let weight =
                                    gw[q1] * gw[qs] * 0.5 * self.x1_elements[1] * 0.5 * length;
                                let mut nodes = (0..np).flat_map(|a1| {
                                    let (b1, bs) = (&basis[q1], &basis[qs]);
                                    line.iter()
                                        .enumerate()
                                        .map(move |(k, &m)| ((p * e1 + a1) * n + m, b1[a1] * bs[k]))
                                });
                                add(x, face, weight, &mut nodes)?;
                            }
                        }
                    }
                }
            }
        }
        Ok(())
    }

    /// Error norms of the discrete displacement `v` against `exact` (contravariant
    /// `[v^1, v^2, v^3]` at `(x1, x2, x3)`), by a `(p + 2)^3`-point Gauss rule per element.
    ///
    /// # Math
    /// ```text
    /// |e|^2 = g_ij e^i e^j     (physical length)
    /// l2 = sqrt(int |v_h - v|^2 sqrt(g) dx),   l2_exact = sqrt(int |v|^2 sqrt(g) dx)
    /// dx = (L1 / 2) det J dxi1 dxi2 dxi3
    /// ```
    ///
    /// # Errors
    /// [`ElasticityError::DimensionMismatch`] for a wrong length; geometry failures.
    fn l2_errors(
        &self,
        v: &[f64],
        exact: &(dyn Fn([f64; 3]) -> [f64; 3] + Sync),
    ) -> Result<(f64, f64), ElasticityError> {
        ElasticityError::check_length("displacement", self.dof_count(), v.len())?;
        let (gp, gw) = gauss_legendre(self.settings.order + 2);
        let sums = (0..self.element_count())
            .into_par_iter()
            .map(|e| -> Result<[f64; 2], ElasticityError> {
                let nodes = self.element_nodes(e);
                let mut s = [0.0; 2];
                for (q1, &xi1) in gp.iter().enumerate() {
                    for (q2, &xi2) in gp.iter().enumerate() {
                        for (q3, &xi3) in gp.iter().enumerate() {
                            let (phi, x, det) = self.shape_at(e, [xi1, xi2, xi3]);
                            let pt = self.point(x)?;
                            let mut uh = [0.0; 3];
                            for (f, &m) in phi.iter().zip(&nodes) {
                                for (c, u) in uh.iter_mut().enumerate() {
                                    *u += f[0] * v[COMPONENTS * m + c];
                                }
                            }
                            let u = exact(x);
                            let w = gw[q1] * gw[q2] * gw[q3] * det * pt.sqrt_g;
                            super::norms::add_error_point(&mut s, w, &pt.metric, uh, u);
                        }
                    }
                }
                Ok(s)
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(super::norms::error_norms(&sums))
    }
}
