//! The structured grid on the parameter rectangle `[theta0, theta1] x [0, h]`.

use crate::error::ElasticityError;

/// Nodes `x2_i`, `x3_j` of a uniform grid on `[theta0, theta1] x [0, thickness]`.
///
/// # Math
/// ```text
/// bounded x2:  x2_i = theta0 + i dx2,  dx2 = (theta1 - theta0)/(n2 - 1),  i = 0..n2-1
/// periodic x2: x2_i = theta0 + i dx2,  dx2 = (theta1 - theta0)/n2         (node n2 == node 0)
/// x3_j = j dx3,  dx3 = thickness/(n3 - 1),  j = 0..n3-1
/// ```
/// The paper's `250 x 41` grid is `n2 = 250`, `n3 = 41`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Grid {
    theta0: f64,
    theta1: f64,
    thickness: f64,
    n2: usize,
    n3: usize,
    periodic: bool,
}

impl Grid {
    /// The grid as the solvers see it for a fill-reducing ordering: `n2 x n3` nodes of the two
    /// plane-strain unknowns `(v^2, v^3)`, periodic in `x2` as the grid is.
    pub fn shape(&self) -> capstan_solvers::GridShape {
        capstan_solvers::GridShape {
            n2: self.n2(),
            n3: self.n3(),
            dofs_per_node: 2,
            periodic: self.is_periodic(),
        }
    }

    /// A grid with `n2 x n3` nodes; `periodic` wraps `x2` (then `theta1 - theta0` is the period).
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] for `theta1 <= theta0`, a thickness that is not
    /// positive, `n2 < 3` or `n3 < 3` (the one-sided boundary differences need three nodes).
    pub fn new(
        theta: [f64; 2],
        thickness: f64,
        n2: usize,
        n3: usize,
        periodic: bool,
    ) -> Result<Self, ElasticityError> {
        if !(theta[0].is_finite() && theta[1].is_finite() && theta[1] > theta[0]) {
            return Err(ElasticityError::InvalidParameter {
                field: "body.theta1",
                value: theta[1],
                allowed: "(theta0, inf)",
            });
        }
        if !(thickness.is_finite() && thickness > 0.0) {
            return Err(ElasticityError::InvalidParameter {
                field: "body.thickness",
                value: thickness,
                allowed: "(0, inf)",
            });
        }
        for (field, n) in [("grid.n2", n2), ("grid.n3", n3)] {
            if n < 3 {
                return Err(ElasticityError::InvalidParameter {
                    field,
                    value: n as f64,
                    allowed: "[3, inf)",
                });
            }
        }
        Ok(Self {
            theta0: theta[0],
            theta1: theta[1],
            thickness,
            n2,
            n3,
            periodic,
        })
    }

    /// Nodes in `x2`.
    pub fn n2(&self) -> usize {
        self.n2
    }
    /// Nodes in `x3`.
    pub fn n3(&self) -> usize {
        self.n3
    }
    /// Number of nodes `n2 n3`.
    pub fn node_count(&self) -> usize {
        self.n2 * self.n3
    }
    /// Whether `x2` is periodic.
    pub fn is_periodic(&self) -> bool {
        self.periodic
    }
    /// `[theta0, theta1]`.
    pub fn theta(&self) -> [f64; 2] {
        [self.theta0, self.theta1]
    }
    /// Thickness `h`.
    pub fn thickness(&self) -> f64 {
        self.thickness
    }
    /// Spacing `dx2`.
    pub fn dx2(&self) -> f64 {
        let span = self.theta1 - self.theta0;
        if self.periodic {
            span / self.n2 as f64
        } else {
            span / (self.n2 - 1) as f64
        }
    }
    /// Spacing `dx3`.
    pub fn dx3(&self) -> f64 {
        self.thickness / (self.n3 - 1) as f64
    }
    /// `x2_i`.
    pub fn x2(&self, i2: usize) -> f64 {
        self.theta0 + i2 as f64 * self.dx2()
    }
    /// `x3_j`.
    pub fn x3(&self, i3: usize) -> f64 {
        i3 as f64 * self.dx3()
    }
    /// `(x2_i, x3_j)`.
    pub fn coordinates(&self, node: [usize; 2]) -> [f64; 2] {
        [self.x2(node[0]), self.x3(node[1])]
    }
    /// Node number `i2 n3 + i3` (`x3` fastest).
    pub fn node_index(&self, node: [usize; 2]) -> usize {
        node[0] * self.n3 + node[1]
    }
    /// Node `(i2, i3)` of node number `k`.
    pub fn node(&self, k: usize) -> [usize; 2] {
        [k / self.n3, k % self.n3]
    }
    /// Trapezoidal quadrature weight of a node on the parameter rectangle (sums to its area).
    pub fn quadrature_weight(&self, node: [usize; 2]) -> f64 {
        let end2 = !self.periodic && (node[0] == 0 || node[0] == self.n2 - 1);
        let end3 = node[1] == 0 || node[1] == self.n3 - 1;
        let w2 = if end2 { 0.5 } else { 1.0 };
        let w3 = if end3 { 0.5 } else { 1.0 };
        w2 * w3 * self.dx2() * self.dx3()
    }

    /// Nodal difference `d_2` at `(i, .)`: `(i2, weight)` pairs ([`difference_stencil`]).
    pub(crate) fn d2_stencil(&self, i: usize) -> [(usize, f64); 3] {
        difference_stencil(i, self.n2(), self.dx2(), self.is_periodic())
    }

    /// Nodal difference `d_3` at `(., j)`: `(i3, weight)` pairs ([`difference_stencil`]).
    pub(crate) fn d3_stencil(&self, j: usize) -> [(usize, f64); 3] {
        difference_stencil(j, self.n3(), self.dx3(), false)
    }

    /// The gradient-recovery stencil at a node, `(node, [value, d_2, d_3])` weights, in place
    /// of what `out` held: the node itself, then second-order differences in `x2` and `x3`
    /// (central inside, one-sided `(-3, 4, -1) / (2 h)` at a bounded end; see
    /// [`crate::kinematics::LocalDisplacement::from_stencil`]).
    pub fn node_stencil(&self, [i, j]: [usize; 2], out: &mut Vec<([usize; 2], [f64; 3])>) {
        out.clear();
        out.push(([i, j], [1.0, 0.0, 0.0]));
        for (ii, w) in self.d2_stencil(i) {
            out.push(([ii, j], [0.0, w, 0.0]));
        }
        for (jj, w) in self.d3_stencil(j) {
            out.push(([i, jj], [0.0, 0.0, w]));
        }
    }
}

/// Second-order nodal difference weights `(index, weight)` at node `i` of `n` nodes spaced `h`
/// along a grid direction: central (wrapping round when `periodic`), or second-order one-sided
/// at a bounded end; the first-order difference on a line of two nodes.
pub(crate) fn difference_stencil(i: usize, n: usize, h: f64, periodic: bool) -> [(usize, f64); 3] {
    let w = 0.5 / h;
    if !periodic && n == 2 {
        // two nodes: the one difference there is
        return [(0, -2.0 * w), (1, 2.0 * w), (i, 0.0)];
    }
    if periodic {
        [((i + n - 1) % n, -w), ((i + 1) % n, w), (i, 0.0)]
    } else if i == 0 {
        [(0, -3.0 * w), (1, 4.0 * w), (2, -w)]
    } else if i == n - 1 {
        [(n - 1, 3.0 * w), (n - 2, -4.0 * w), (n - 3, w)]
    } else {
        [(i - 1, -w), (i + 1, w), (i, 0.0)]
    }
}
