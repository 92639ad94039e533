//! The conforming quadrilateral mesh refined toward the corners of the parameter rectangle:
//! coarse rectangular cells, each corner cell replaced by geometric layers of two trapezoids,
//! and the numbering of the Qp nodes on it (vertices, edges, interiors).

use std::collections::HashMap;

use crate::error::ElasticityError;

/// The corner-refined mesh's parameters (scene-free: the library names them as fields of
/// [`CornerSettings`]).
///
/// # Math
/// The rectangle `[a2, b2] x [0, h]` is cut into `cells[0] x cells[1]` equal cells. Each of the
/// four corner cells, mapped to `[0, 1]^2` with the corner at the origin, is replaced by `n`
/// L-shaped layers `[0, sigma^k]^2 \ [0, sigma^(k+1)]^2` (`k = 0 ... n - 1`), each split along
/// the diagonal into two trapezoids
/// ```text
/// A_k = (sigma^(k+1), 0), (sigma^k, 0), (sigma^(k+1), sigma^(k+1)), (sigma^k, sigma^k)
/// B_k = (0, sigma^(k+1)), (sigma^(k+1), sigma^(k+1)), (0, sigma^k), (sigma^k, sigma^k)
/// ```
/// and the square `[0, sigma^n]^2` at the corner: `2n + 1` elements per corner whose edges
/// match (no hanging nodes) and whose outer edges are the cell's, so the coarse cells around
/// stay single elements. The smallest element is `sigma^n` of the cell; the element count is
/// `cells[0] cells[1] + 8n` against `(2n + m2) (2n + m3)` for geometric grading along whole
/// lines of a tensor grid.
///
/// # References
/// Schwab, *p- and hp-Finite Element Methods* (1998), §4.4.3 (geometric meshes on
/// quadrilaterals with trapezoidal layers).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CornerSettings {
    /// The order `p` (`1 ... 10`).
    pub order: usize,
    /// Coarse cells `[in x2, in x3]`, each at least 2.
    pub cells: [usize; 2],
    /// Geometric layers per corner, `0 ... 16` (`0`: the uniform mesh of the cells).
    pub layers: usize,
    /// The ratio `sigma` of successive layers, `0.05 ... 0.95`.
    pub ratio: f64,
}

impl CornerSettings {
    /// The allowed numbers of layers.
    pub const LAYERS: core::ops::RangeInclusive<usize> = 0..=16;

    /// Checks the ranges.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `order`, `cells`, `layers` or `ratio`.
    pub fn check(&self) -> Result<(), ElasticityError> {
        let bad = |field: &'static str, value: f64, allowed: &'static str| {
            Err(ElasticityError::InvalidParameter {
                field,
                value,
                allowed,
            })
        };
        if !super::super::ORDERS.contains(&self.order) {
            return bad("order", self.order as f64, "1..=10");
        }
        if let Some(&c) = self.cells.iter().find(|&&c| c < 2) {
            return bad("cells", c as f64, "at least 2 cells per direction");
        }
        if !Self::LAYERS.contains(&self.layers) {
            return bad("layers", self.layers as f64, "0..=16");
        }
        if !(0.05..=0.95).contains(&self.ratio) {
            return bad("ratio", self.ratio, "0.05 <= ratio <= 0.95");
        }
        Ok(())
    }

    /// The nodes of the Qp mesh of these settings on a rectangle (any: the count does not
    /// depend on its size), the `N` of a plane-strain body's `2 N` unknowns and of a 3-D
    /// body's `3 n1 N`.
    pub fn node_count(&self) -> usize {
        Layout::new([[0.0, 1.0], [0.0, 1.0]], self).node_count
    }

    /// The nodes on the contact face `x3 = 0` of the mesh (per `x1` line of a 3-D body):
    /// `p cells[0] + 1` of the coarse cells and `p` more for every layer at each of the
    /// face's two corners.
    ///
    /// # Math
    /// ```text
    /// K = p e2 + 1 + 2 layers p
    /// ```
    pub fn face_node_count(&self) -> usize {
        self.order * (self.cells[0] + 2 * self.layers) + 1
    }
}

/// Geometric layers of `x2` lines toward interior points of the contact face (the stick/slip
/// transitions of a frictional solve), added to the corner mesh ([`CornerSettings`]).
///
/// # Math
/// With `H` the coarse cell width in `x2` and `sigma = ratio`, every point `t` strictly inside
/// the non-corner cells becomes an element line, with lines at `t +- H sigma^k`,
/// `k = k0 ... layers`: whole columns through the thickness, so the elements touching `t` are
/// `H sigma^layers` wide and grow geometrically away from it (the hp mesh of a point
/// singularity of the traction: Schwab, *p- and hp-FEM*, section 4.4). On each side
/// separately, `k0 >= 1` is the least `k` with `H sigma^k <= 0.4 g`, `g` the distance to the
/// next point on that side or twice the distance to the corner-cell line, so two points'
/// layers never cross (the element between them is at least `0.2 g`); coarse lines on that
/// side within `H sigma^k0 (1 + sigma) / (2 sigma)` of `t` are dropped (the graded region
/// replaces them, leaving no element thinner than `H sigma^k0 (1 - sigma) / (2 sigma)` beside
/// it).
/// Points in the corner cells (or outside the face) are not graded: the corner layers serve
/// there. `layers = 0` or no points is today's mesh exactly.
///
/// `face_layers = m > 0` also grades the rows toward the contact face: a stick zone is a
/// feature of the face of its own length (on the default scene `0.03`, with the elastic length
/// `G eps / (mu |sigma_n|) ~ 0.03` of the regularised law's stick stiffness), which the
/// columns resolve in `x2` but a coarse row (`H3 = h / e3`, `0.125` on `24 x 8` cells) does
/// not in `x3`. The first and the last row and column (the corner cells' own) get lines at
/// ```text
/// x3 = H3 sigma^k,  h - H3 sigma^k,  x2 = a + H2 sigma^k,  b - H2 sigma^k   (k = 1 ... m)
/// ```
/// so the corner cells stay squares (of side `H sigma^m`, with their corner layers inside)
/// when the coarse cells are, and the rows at the face are `H3 sigma^m` high. The cells of
/// this band are anisotropic (up to `sigma^-m`) only where they are thin across a direction
/// in which the solution varies slowly (along the face, along the ends).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TransitionGrading {
    /// The `x2` points (parameter units).
    pub points: Vec<f64>,
    /// Layers per side of every point, `0 ... 16`.
    pub layers: usize,
    /// The ratio `sigma` of successive layers, `0.05 ... 0.95`.
    pub ratio: f64,
    /// Layers of rows toward the faces `x3 = 0, h` (and of columns toward the ends, keeping
    /// the corner cells square), `0 ... 16`; `0`: none.
    pub face_layers: usize,
}

impl TransitionGrading {
    /// No grading (today's corner mesh).
    pub const NONE: Self = Self {
        points: Vec::new(),
        layers: 0,
        ratio: 0.3,
        face_layers: 0,
    };

    /// Checks the ranges.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `transition_layers`, `transition_ratio`,
    /// `face_layers` or `transition_points` (not finite).
    pub fn check(&self) -> Result<(), ElasticityError> {
        if !CornerSettings::LAYERS.contains(&self.layers) {
            return Err(ElasticityError::InvalidParameter {
                field: "transition_layers",
                value: self.layers as f64,
                allowed: "0..=16",
            });
        }
        if !CornerSettings::LAYERS.contains(&self.face_layers) {
            return Err(ElasticityError::InvalidParameter {
                field: "face_layers",
                value: self.face_layers as f64,
                allowed: "0..=16",
            });
        }
        if !(0.05..=0.95).contains(&self.ratio) {
            return Err(ElasticityError::InvalidParameter {
                field: "transition_ratio",
                value: self.ratio,
                allowed: "0.05 <= transition_ratio <= 0.95",
            });
        }
        if let Some(&t) = self.points.iter().find(|t| !t.is_finite()) {
            return Err(ElasticityError::InvalidParameter {
                field: "transition_points",
                value: t,
                allowed: "finite x2 on the contact face",
            });
        }
        Ok(())
    }

    /// The `x2` lines of the mesh: the `e2 + 1` equal cell lines of `[a, b]` (bit for bit those
    /// of [`Layout::new`]) with the graded lines of the type's doc; the first and last
    /// intervals are the corner cells, unchanged.
    pub(super) fn x2_lines(&self, [a, b]: [f64; 2], e2: usize) -> Vec<f64> {
        let uniform: Vec<f64> = (0..=e2)
            .map(|j| {
                if j == e2 {
                    b
                } else {
                    a + (b - a) * j as f64 / e2 as f64
                }
            })
            .collect();
        if self.layers == 0 || self.points.is_empty() || e2 < 3 {
            return uniform;
        }
        let (lo, hi) = (uniform[1], uniform[e2 - 1]);
        let h = (b - a) / e2 as f64;
        let sigma = self.ratio;
        let mut points: Vec<f64> = self
            .points
            .iter()
            .copied()
            .filter(|&t| t > lo && t < hi)
            .collect();
        points.sort_by(f64::total_cmp);
        points.dedup();
        let mut keep = vec![true; uniform.len()];
        let mut added = Vec::new();
        for (i, &t) in points.iter().enumerate() {
            added.push(t);
            for side in [-1.0, 1.0] {
                // the room on this side: half way to the next point, or up to the corner cell
                let g = if side < 0.0 {
                    i.checked_sub(1).map_or(2.0 * (t - lo), |j| t - points[j])
                } else {
                    points.get(i + 1).map_or(2.0 * (hi - t), |&u| u - t)
                };
                let Some(k0) = (1..=self.layers).find(|&k| h * sigma.powi(k as i32) <= 0.4 * g)
                else {
                    continue;
                };
                let reach = h * sigma.powi(k0 as i32) * (1.0 + sigma) / (2.0 * sigma);
                for (j, &x) in uniform.iter().enumerate().take(e2 - 1).skip(2) {
                    let d = side * (x - t);
                    if (0.0..reach).contains(&d) {
                        keep[j] = false;
                    }
                }
                for k in k0..=self.layers {
                    added.push(t + side * h * sigma.powi(k as i32));
                }
            }
        }
        let mut lines: Vec<f64> = uniform
            .into_iter()
            .zip(keep)
            .filter_map(|(x, k)| k.then_some(x))
            .chain(added)
            .collect();
        lines.sort_by(f64::total_cmp);
        lines.dedup();
        lines
    }
}

/// `lines` (increasing) with `m` geometric lines of ratio `sigma` in its first and its last
/// interval, toward the ends: `l0 + (l1 - l0) sigma^k`, `ln - (ln - l(n-1)) sigma^k`,
/// `k = 1 ... m` ([`TransitionGrading`]'s `face_layers`). The ends stay bit for bit.
fn toward_ends(lines: Vec<f64>, m: usize, sigma: f64) -> Vec<f64> {
    let n = lines.len();
    if m == 0 || n < 3 {
        return lines;
    }
    let (first, last) = ((lines[0], lines[1]), (lines[n - 1], lines[n - 2]));
    let mut out = lines;
    for k in 1..=m {
        let s = sigma.powi(k as i32);
        out.push(first.0 + (first.1 - first.0) * s);
        out.push(last.0 - (last.0 - last.1) * s);
    }
    out.sort_by(f64::total_cmp);
    out.dedup();
    out
}

/// One side of the parameter rectangle an element edge may lie on, in the order of
/// `Side`'s normal index and sign.
pub(crate) type SideMask = u8;

/// The quadrilaterals and the Qp node numbering.
#[derive(Debug, Clone)]
pub(crate) struct Layout {
    /// Vertex positions `[x2, x3]`.
    pub vertices: Vec<[f64; 2]>,
    /// Vertices of each element in the order `(xi, eta) = (-1,-1), (1,-1), (-1,1), (1,1)`,
    /// positively oriented.
    pub quads: Vec<[usize; 4]>,
    /// Global node of every local node `a = a2 (p + 1) + a3`, per element.
    pub element_nodes: Vec<usize>,
    /// Nodes on the element edges (vertices and edge nodes, numbered first).
    pub skeleton_count: usize,
    /// All nodes.
    pub node_count: usize,
}

/// Bit of the side with `x2 = a2` (`1`), `x2 = b2` (`2`), `x3 = 0` (`4`), `x3 = h` (`8`) on
/// which `x` lies (exact comparisons: boundary vertices are placed exactly).
pub(crate) fn sides_of(x: [f64; 2], [[a2, b2], [a3, b3]]: [[f64; 2]; 2]) -> SideMask {
    u8::from(x[0] == a2)
        | (u8::from(x[0] == b2) << 1)
        | (u8::from(x[1] == a3) << 2)
        | (u8::from(x[1] == b3) << 3)
}

impl Layout {
    /// The mesh of `settings` on `rect = [[a2, b2], [a3, b3]]` and its Qp numbering.
    pub fn new(rect: [[f64; 2]; 2], settings: &CornerSettings) -> Self {
        Self::graded(rect, settings, &TransitionGrading::NONE)
    }

    /// The mesh of `settings` with the `x2` lines graded toward `transitions`
    /// ([`TransitionGrading`]); [`TransitionGrading::NONE`] gives [`Self::new`]'s mesh.
    pub fn graded(
        rect: [[f64; 2]; 2],
        settings: &CornerSettings,
        transitions: &TransitionGrading,
    ) -> Self {
        let p = settings.order;
        let (m, sigma) = (transitions.face_layers, transitions.ratio);
        let columns = toward_ends(transitions.x2_lines(rect[0], settings.cells[0]), m, sigma);
        let e2 = columns.len() - 1;
        let line = |[a, b]: [f64; 2], e: usize, j: usize| -> f64 {
            if j == e {
                b
            } else {
                a + (b - a) * j as f64 / e as f64
            }
        };
        let uniform_rows = (0..=settings.cells[1])
            .map(|j| line(rect[1], settings.cells[1], j))
            .collect();
        let rows = toward_ends(uniform_rows, m, sigma);
        let e3 = rows.len() - 1;
        let mut builder = Builder::default();
        for i in 0..e2 {
            for j in 0..e3 {
                let x = [columns[i], columns[i + 1]];
                let y = [rows[j], rows[j + 1]];
                let corner_x = (i == 0).then_some(0).or((i == e2 - 1).then_some(1));
                let corner_y = (j == 0).then_some(0).or((j == e3 - 1).then_some(1));
                match (corner_x, corner_y) {
                    (Some(cx), Some(cy)) => builder.corner_cell(x, y, [cx, cy], settings),
                    _ => builder.quad([[x[0], y[0]], [x[1], y[0]], [x[0], y[1]], [x[1], y[1]]]),
                }
            }
        }
        builder.number(p)
    }
}

/// Vertices deduplicated by their exact coordinates, quads as vertex ids.
#[derive(Default)]
struct Builder {
    ids: HashMap<[u64; 2], usize>,
    vertices: Vec<[f64; 2]>,
    quads: Vec<[usize; 4]>,
}

impl Builder {
    fn vertex(&mut self, x: [f64; 2]) -> usize {
        let key = [x[0].to_bits(), x[1].to_bits()];
        let next = self.vertices.len();
        *self.ids.entry(key).or_insert_with(|| {
            self.vertices.push(x);
            next
        })
    }

    fn quad(&mut self, v: [[f64; 2]; 4]) {
        let q = v.map(|x| self.vertex(x));
        self.quads.push(q);
    }

    /// The geometric pattern of the type's doc in the cell `x x y`, the corner at
    /// `(x[cx], y[cy])`.
    fn corner_cell(&mut self, x: [f64; 2], y: [f64; 2], [cx, cy]: [usize; 2], s: &CornerSettings) {
        // local (s, t) in [0, 1]^2 with the corner at 0: exact at 0 and 1
        let map = |u: f64, [near, far]: [f64; 2]| -> f64 {
            if u == 0.0 {
                near
            } else if u == 1.0 {
                far
            } else {
                near + (far - near) * u
            }
        };
        let (xs, ys) = ([x[cx], x[1 - cx]], [y[cy], y[1 - cy]]);
        let mut local = |v: [[f64; 2]; 4]| {
            let mut q = v.map(|[u, w]| [map(u, xs), map(w, ys)]);
            // mirrored cells: restore the positive orientation
            if cx == 1 {
                q = [q[1], q[0], q[3], q[2]];
            }
            if cy == 1 {
                q = [q[2], q[3], q[0], q[1]];
            }
            self.quad(q);
        };
        for k in 0..s.layers {
            let (r0, r1) = (s.ratio.powi(k as i32), s.ratio.powi(k as i32 + 1));
            local([[r1, 0.0], [r0, 0.0], [r1, r1], [r0, r0]]);
            local([[0.0, r1], [r1, r1], [0.0, r0], [r0, r0]]);
        }
        let rn = s.ratio.powi(s.layers as i32);
        local([[0.0, 0.0], [rn, 0.0], [0.0, rn], [rn, rn]]);
    }

    /// Numbers the Qp nodes: vertices, then `p - 1` nodes per edge (from its lower vertex
    /// id), then `(p - 1)^2` per element interior.
    fn number(self, p: usize) -> Layout {
        let np = p + 1;
        let nv = self.vertices.len();
        let mut edges: HashMap<[usize; 2], usize> = HashMap::new();
        for q in &self.quads {
            for [s, e] in local_edges(q) {
                let next = edges.len();
                edges.entry([s.min(e), s.max(e)]).or_insert(next);
            }
        }
        let skeleton_count = nv + edges.len() * (p - 1);
        let mut element_nodes = Vec::with_capacity(self.quads.len() * np * np);
        for (el, q) in self.quads.iter().enumerate() {
            let [v00, v10, v01, v11] = *q;
            let along = |start: usize, end: usize, k: usize| -> usize {
                let id = edges[&[start.min(end), start.max(end)]];
                let j = if start < end { k } else { p - k };
                nv + id * (p - 1) + j - 1
            };
            let interior = skeleton_count + el * (p - 1) * (p - 1);
            for a2 in 0..np {
                for a3 in 0..np {
                    let node = match (a2, a3) {
                        (0, 0) => v00,
                        (a, 0) if a == p => v10,
                        (0, b) if b == p => v01,
                        (a, b) if a == p && b == p => v11,
                        (0, b) => along(v00, v01, b),
                        (a, b) if a == p => along(v10, v11, b),
                        (a, 0) => along(v00, v10, a),
                        (a, b) if b == p => along(v01, v11, a),
                        (a, b) => interior + (a - 1) * (p - 1) + b - 1,
                    };
                    element_nodes.push(node);
                }
            }
        }
        Layout {
            node_count: skeleton_count + self.quads.len() * (p - 1) * (p - 1),
            vertices: self.vertices,
            quads: self.quads,
            element_nodes,
            skeleton_count,
        }
    }
}

/// The four edges of a quad as (start, end) vertices, in the local directions of increasing
/// `xi` or `eta`: `xi = -1`, `xi = 1`, `eta = -1`, `eta = 1`.
pub(crate) fn local_edges(&[v00, v10, v01, v11]: &[usize; 4]) -> [[usize; 2]; 4] {
    [[v00, v01], [v10, v11], [v00, v10], [v01, v11]]
}

/// `x(xi, eta)` of the bilinear map through `v = [x00, x10, x01, x11]` and its Jacobian
/// `[[d x2/d xi, d x2/d eta], [d x3/d xi, d x3/d eta]]`.
pub(crate) fn bilinear(v: &[[f64; 2]; 4], [xi, eta]: [f64; 2]) -> ([f64; 2], [[f64; 2]; 2]) {
    let n = [
        0.25 * (1.0 - xi) * (1.0 - eta),
        0.25 * (1.0 + xi) * (1.0 - eta),
        0.25 * (1.0 - xi) * (1.0 + eta),
        0.25 * (1.0 + xi) * (1.0 + eta),
    ];
    let x = core::array::from_fn(|c| (0..4).map(|i| n[i] * v[i][c]).sum());
    let jacobian = core::array::from_fn(|c| {
        [
            0.25 * ((1.0 - eta) * (v[1][c] - v[0][c]) + (1.0 + eta) * (v[3][c] - v[2][c])),
            0.25 * ((1.0 - xi) * (v[2][c] - v[0][c]) + (1.0 + xi) * (v[3][c] - v[1][c])),
        ]
    });
    (x, jacobian)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn settings(p: usize, n: usize) -> CornerSettings {
        CornerSettings {
            order: p,
            cells: [4, 3],
            layers: n,
            ratio: 0.3,
        }
    }

    /// The layout's quads have positive Jacobians at the 2 x 2 Gauss points and their areas
    /// (the Gauss rule is exact for a bilinear map's determinant) sum to `area`.
    fn assert_tiles(l: &Layout, area: f64) {
        let q = 1.0 / 3f64.sqrt();
        let mut sum = 0.0;
        for quad in &l.quads {
            let v = quad.map(|i| l.vertices[i]);
            for xi in [-q, q] {
                for eta in [-q, q] {
                    let (_, j) = bilinear(&v, [xi, eta]);
                    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
                    assert!(det > 0.0, "{v:?}");
                    sum += det;
                }
            }
        }
        assert!((sum - area).abs() < 1e-13, "{sum}");
    }

    #[test]
    fn corner_mesh_tiles_the_rectangle_with_positive_jacobians() {
        let rect = [[-1.5, 1.5], [0.0, 1.0]];
        for (p, n) in [(1, 1), (3, 2), (5, 4)] {
            let l = Layout::new(rect, &settings(p, n));
            assert_eq!(l.quads.len(), 12 - 4 + 4 * (2 * n + 1));
            assert_tiles(&l, 3.0);
            // Euler: V - E + F = 1 for a disc; p - 1 nodes per edge
            let (nv, nf) = (l.vertices.len(), l.quads.len());
            let ne = nv + nf - 1;
            assert_eq!(l.skeleton_count, nv + ne * (p - 1));
            assert_eq!(l.node_count, l.skeleton_count + nf * (p - 1) * (p - 1));
            // every node is used, and shared nodes agree on their position
            let mut seen = vec![false; l.node_count];
            l.element_nodes.iter().for_each(|&m| seen[m] = true);
            assert!(seen.iter().all(|&s| s));
        }
    }

    #[test]
    fn transition_grading_adds_geometric_columns_around_interior_points() {
        let rect = [[-1.5, 1.5], [0.0, 1.0]];
        let s = CornerSettings {
            cells: [12, 2],
            ..settings(3, 2)
        };
        // none: the uniform lines bit for bit
        let plain = Layout::new(rect, &s);
        let none = Layout::graded(rect, &s, &TransitionGrading::NONE);
        assert_eq!(plain.vertices, none.vertices);
        assert_eq!(plain.quads, none.quads);
        // two close points (a stick zone) and one in a corner cell (not graded)
        let g = TransitionGrading {
            points: vec![0.1, 0.13, -1.45],
            layers: 4,
            ratio: 0.3,
            face_layers: 0,
        };
        let lines = g.x2_lines(rect[0], 12);
        let h = 0.25;
        assert!(lines.windows(2).all(|w| w[1] > w[0]), "{lines:?}");
        assert_eq!(lines[..2], [-1.5, -1.25]); // the corner cells unchanged
        assert_eq!(lines[lines.len() - 2..], [1.25, 1.5]);
        for t in [0.1, 0.13] {
            let k = lines.iter().position(|&x| x == t).unwrap();
            let d = h * 0.3f64.powi(4);
            assert!((lines[k + 1] - t - d).abs() < 1e-15 && (t - lines[k - 1] - d).abs() < 1e-15);
        }
        // no sliver: every element at least 0.3 of its neighbour
        let widths: Vec<f64> = lines.windows(2).map(|w| w[1] - w[0]).collect();
        for w in widths.windows(2) {
            let r = w[0] / w[1];
            assert!((0.15..=1.0 / 0.15).contains(&r), "{widths:?}");
        }
        // the mesh tiles the rectangle with positive Jacobians
        let l = Layout::graded(rect, &s, &g);
        assert_tiles(&l, 3.0);
        assert_eq!(l.quads.len(), (lines.len() - 1) * 2 - 4 + 4 * (2 * 2 + 1));
        let bad = TransitionGrading {
            points: vec![f64::NAN],
            ..g.clone()
        };
        assert!(matches!(
            bad.check(),
            Err(ElasticityError::InvalidParameter {
                field: "transition_points",
                ..
            })
        ));
        let bad = TransitionGrading { layers: 17, ..g };
        assert!(bad.check().is_err());
    }

    #[test]
    fn face_layers_grade_rows_toward_the_faces_and_keep_the_corner_cells_square() {
        // 12 x 4 cells of 0.25 x 0.25 on [-1.5, 1.5] x [0, 1], two face layers of 0.3
        let rect = [[-1.5, 1.5], [0.0, 1.0]];
        let s = CornerSettings {
            cells: [12, 4],
            ..settings(3, 2)
        };
        let g = TransitionGrading {
            face_layers: 2,
            ..TransitionGrading::NONE
        };
        assert!(g.check().is_ok());
        let l = Layout::graded(rect, &s, &g);
        // the rows: 0, H sigma^2, H sigma, H, 2H, 3H, 1 - H sigma, 1 - H sigma^2, 1
        let mut ys: Vec<f64> = l.vertices.iter().map(|v| v[1]).collect();
        ys.sort_by(f64::total_cmp);
        ys.dedup();
        let h = 0.25;
        for y in [
            h * 0.09,
            h * 0.3,
            h,
            2.0 * h,
            3.0 * h,
            1.0 - h * 0.3,
            1.0 - h * 0.09,
        ] {
            assert!(
                ys.iter().any(|&v| (v - y).abs() < 1e-15),
                "{y} not in {ys:?}"
            );
        }
        // the corner cell at (-1.5, 0) is the square of side H sigma^2 = 0.0225, its corner
        // layers inside: the smallest element at the corner is 0.0225 0.3^2
        let side = h * 0.09;
        let smallest = l
            .quads
            .iter()
            .map(|q| q.map(|i| l.vertices[i]))
            .filter(|v| v[0] == [-1.5, 0.0])
            .map(|v| (v[1][0] - v[0][0], v[2][1] - v[0][1]))
            .next()
            .expect("an element at the corner");
        assert!((smallest.0 - side * 0.09).abs() < 1e-15, "{smallest:?}");
        assert!((smallest.1 - side * 0.09).abs() < 1e-15, "{smallest:?}");
        // 16 columns, 8 rows, 4 corner cells of 2 * 2 + 1 elements
        assert_eq!(l.quads.len(), 16 * 8 - 4 + 4 * 5);
        assert_tiles(&l, 3.0);
        let bad = TransitionGrading {
            face_layers: 17,
            ..g
        };
        assert!(matches!(
            bad.check(),
            Err(ElasticityError::InvalidParameter {
                field: "face_layers",
                ..
            })
        ));
    }

    #[test]
    fn shared_edge_nodes_sit_at_the_same_point_from_both_sides() {
        let p = 4;
        let l = Layout::new([[0.0, 2.0], [0.0, 1.0]], &settings(p, 3));
        let (gll, _) = super::super::super::gll_rule(p);
        let mut position: Vec<Option<[f64; 2]>> = vec![None; l.node_count];
        for (e, q) in l.quads.iter().enumerate() {
            let v = q.map(|i| l.vertices[i]);
            for a2 in 0..=p {
                for a3 in 0..=p {
                    let (x, _) = bilinear(&v, [gll[a2], gll[a3]]);
                    let m = l.element_nodes[e * (p + 1) * (p + 1) + a2 * (p + 1) + a3];
                    if let Some(y) = position[m] {
                        assert!(
                            (x[0] - y[0]).abs() + (x[1] - y[1]).abs() < 1e-14,
                            "{x:?} {y:?}"
                        );
                    }
                    position[m] = Some(x);
                }
            }
        }
    }

    #[test]
    fn settings_outside_their_ranges_are_typed_errors() {
        let good = settings(4, 3);
        assert!(good.check().is_ok());
        let cases = [
            (CornerSettings { order: 0, ..good }, "order"),
            (CornerSettings { order: 11, ..good }, "order"),
            (
                CornerSettings {
                    cells: [1, 3],
                    ..good
                },
                "cells",
            ),
            (CornerSettings { layers: 17, ..good }, "layers"),
            (CornerSettings { ratio: 0.0, ..good }, "ratio"),
            (
                CornerSettings {
                    ratio: f64::NAN,
                    ..good
                },
                "ratio",
            ),
            (CornerSettings { ratio: 1.0, ..good }, "ratio"),
        ];
        for (s, name) in cases {
            match s.check() {
                Err(ElasticityError::InvalidParameter { field, .. }) => assert_eq!(field, name),
                other => panic!("{s:?}: {other:?}"),
            }
        }
    }
}
