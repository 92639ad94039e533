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
        let p = settings.order;
        let [e2, e3] = settings.cells;
        let line = |[a, b]: [f64; 2], e: usize, j: usize| -> f64 {
            if j == e {
                b
            } else {
                a + (b - a) * j as f64 / e as f64
            }
        };
        let mut builder = Builder::default();
        for i in 0..e2 {
            for j in 0..e3 {
                let x = [line(rect[0], e2, i), line(rect[0], e2, i + 1)];
                let y = [line(rect[1], e3, j), line(rect[1], e3, j + 1)];
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

    #[test]
    fn corner_mesh_tiles_the_rectangle_with_positive_jacobians() {
        let rect = [[-1.5, 1.5], [0.0, 1.0]];
        for (p, n) in [(1, 1), (3, 2), (5, 4)] {
            let l = Layout::new(rect, &settings(p, n));
            assert_eq!(l.quads.len(), 12 - 4 + 4 * (2 * n + 1));
            // area: sum of det J over a 2-point Gauss rule is exact for bilinear maps
            let g = 1.0 / 3f64.sqrt();
            let mut area = 0.0;
            for q in &l.quads {
                let v = q.map(|i| l.vertices[i]);
                for xi in [-g, g] {
                    for eta in [-g, g] {
                        let (_, j) = bilinear(&v, [xi, eta]);
                        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
                        assert!(det > 0.0, "{v:?}");
                        area += det;
                    }
                }
            }
            assert!((area - 3.0).abs() < 1e-13, "{area}");
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
