//! The hexahedral tensor elements of the 3-D body: Q1/Q2 with uniformly spaced nodes and Qp
//! (any degree `p = 1 ... 10`) with Gauss–Lobatto–Legendre (GLL) nodes, and the per-line
//! tables (node weights, nodal derivatives) the contact rows and the output fields share.

use crate::error::ElasticityError;
use crate::finite_element::high_order::{
    check_order, elements_along, gauss_legendre, gll_rule, lagrange_basis,
};
use crate::finite_element::{ElementOrder, check_whole_elements, lumped_weight};
use crate::grid::difference_stencil;

/// Report names of the Qp hexahedra, by degree (`solid-qp1` ... `solid-qp10`).
const QP_NAMES: [&str; 11] = [
    "solid-qp0",
    "solid-qp1",
    "solid-qp2",
    "solid-qp3",
    "solid-qp4",
    "solid-qp5",
    "solid-qp6",
    "solid-qp7",
    "solid-qp8",
    "solid-qp9",
    "solid-qp10",
];

/// The hexahedral element of a 3-D body: the tensor product of one 1-D Lagrange element of
/// degree `p` per direction.
///
/// # Math
/// ```text
/// N_(a1 a2 a3)(xi, eta, zeta) = l_a1(xi) l_a2(eta) l_a3(zeta),  l_a the Lagrange basis
///                               through the reference nodes xi_0 < ... < xi_p of [-1, 1]
/// Uniform(Q1/Q2):  xi_a = -1 + 2a/p          (fem-q1, fem-q2)
/// Gll(p):          xi_a the GLL points: -1, 1 and the roots of P_p'   (fem-qp)
/// ```
/// Quadrature `(p + 1)^3` Gauss points (`p^3` for the volumetric part with selective reduced
/// integration). For `p = 1, 2` the GLL points are the uniform ones, so `Gll(1)`, `Gll(2)`
/// assemble the Q1/Q2 operator to round-off; they differ in the recovery of nodal
/// derivatives (`LineTables`): second-order differences for Q1/Q2, the element polynomials
/// for Qp.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum HexElement {
    /// Q1 or Q2 with uniformly spaced nodes.
    Uniform(ElementOrder),
    /// Qp with GLL nodes, `p` in `1..=10`.
    Gll(usize),
}

impl From<ElementOrder> for HexElement {
    fn from(order: ElementOrder) -> Self {
        Self::Uniform(order)
    }
}

impl HexElement {
    /// Qp hexahedra with GLL nodes.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `discretisation.order` outside `1..=10`.
    pub fn gll(p: usize) -> Result<Self, ElasticityError> {
        check_order(p)?;
        Ok(Self::Gll(p))
    }

    /// Polynomial degree `p` per direction.
    pub fn degree(self) -> usize {
        match self {
            Self::Uniform(order) => order.degree(),
            Self::Gll(p) => p,
        }
    }

    /// Nodes per element direction, `p + 1`.
    pub fn nodes_per_direction(self) -> usize {
        self.degree() + 1
    }

    /// Nodes per element, `(p + 1)^3`.
    pub fn nodes_per_element(self) -> usize {
        self.nodes_per_direction().pow(3)
    }

    /// Report name: `solid-q1`, `solid-q2`, `solid-qp1` ... `solid-qp10`.
    pub fn method_name(self) -> &'static str {
        match self {
            Self::Uniform(ElementOrder::Q1) => "solid-q1",
            Self::Uniform(ElementOrder::Q2) => "solid-q2",
            Self::Gll(p) => QP_NAMES[p.min(10)],
        }
    }

    /// The reference nodes `xi_0 < ... < xi_p` on `[-1, 1]`.
    pub fn reference_nodes(self) -> Vec<f64> {
        match self {
            Self::Uniform(order) => {
                let k = order.degree();
                (0..=k).map(|a| -1.0 + 2.0 * a as f64 / k as f64).collect()
            }
            Self::Gll(p) => gll_rule(p).0,
        }
    }

    /// The 1-D basis and its `xi` derivative at `xi`: `(l_a(xi), l_a'(xi))`, `a = 0 ... p`
    /// (Q1/Q2: the closed forms of [`ElementOrder::shape_1d`]).
    pub fn shape_1d(self, xi: f64) -> (Vec<f64>, Vec<f64>) {
        match self {
            Self::Uniform(order) => {
                let np = order.nodes_per_direction();
                let (n, d) = order.shape_1d(xi);
                (n[..np].to_vec(), d[..np].to_vec())
            }
            Self::Gll(p) => lagrange_basis(&gll_rule(p).0, xi),
        }
    }

    /// The full 1-D rule: `p + 1` Gauss points (exact for degree `2p + 1`).
    pub fn gauss_1d(self) -> (Vec<f64>, Vec<f64>) {
        gauss_legendre(self.nodes_per_direction())
    }

    /// The reduced 1-D rule of the volumetric part: `p` Gauss points.
    pub fn reduced_1d(self) -> (Vec<f64>, Vec<f64>) {
        gauss_legendre(self.degree())
    }

    /// Checks that the grid of `n = [n1, n2, n3]` nodes (`x2` periodic when `periodic_x2`)
    /// is a whole number of elements in every direction.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `grid.n1`, `grid.n2` or `grid.n3` if
    /// `n - 1` (bounded) or `n` (periodic) is not a positive multiple of `p` (Q2: odd node
    /// counts, even `n2` when periodic).
    pub fn check_grid(self, n: [usize; 3], periodic_x2: bool) -> Result<(), ElasticityError> {
        for (field, n, periodic) in [
            ("grid.n1", n[0], false),
            ("grid.n2", n[1], periodic_x2),
            ("grid.n3", n[2], false),
        ] {
            match self {
                Self::Uniform(order) => order.check_nodes(field, n, periodic)?,
                Self::Gll(p) => check_whole_elements(
                    field,
                    n,
                    periodic,
                    p,
                    [
                        "p e + 1 nodes (e elements of order p = discretisation.order) with fem-qp",
                        "p e nodes (e elements of order p) on a periodic direction with fem-qp",
                    ],
                )?,
            }
        }
        Ok(())
    }
}

/// A tensor Gauss rule on elements of lengths `[L1, L2, L3]` with the basis at its points.
///
/// # Math
/// ```text
/// int_element f dx = sum_q w_q1 w_q2 w_q3 det f(x_q),   det = L1 L2 L3 / 8
/// ```
/// point `q = (q1 nq + q2) nq + q3`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ElementRule {
    /// The 1-D abscissae on `[-1, 1]`.
    pub(super) points: Vec<f64>,
    weights: Vec<f64>,
    det: f64,
    /// Nodes per element.
    pub(super) nen: usize,
    shape: Vec<[f64; 4]>,
}

impl ElementRule {
    /// The rule `(points, weights)` (1-D) on the elements of `element` with `lengths`.
    pub(super) fn new(
        element: HexElement,
        (points, weights): (Vec<f64>, Vec<f64>),
        lengths: [f64; 3],
    ) -> Self {
        let shape = shape_table(element, &points, lengths);
        Self {
            points,
            weights,
            det: lengths.iter().product::<f64>() / 8.0,
            nen: element.nodes_per_element(),
            shape,
        }
    }

    /// The weight `w_q1 w_q2 w_q3 det` of point `q`.
    pub(crate) fn weight(&self, q: usize) -> f64 {
        let n = self.points.len();
        let w = &self.weights;
        w[q / (n * n)] * w[(q / n) % n] * w[q % n] * self.det
    }

    /// `[N_a, d_1 N_a, d_2 N_a, d_3 N_a]` of every node `a` at point `q`.
    pub(super) fn shape_at(&self, q: usize) -> &[[f64; 4]] {
        &self.shape[q * self.nen..(q + 1) * self.nen]
    }
}

/// `[N_a, d_1 N_a, d_2 N_a, d_3 N_a]` of the tensor element at the tensor points `gp^3`
/// (index `q nen + a`, `q = (q1 np + q2) np + q3`, `a = (a1 np + a2) np + a3`), for element
/// lengths `lengths`.
fn shape_table(element: HexElement, gp: &[f64], lengths: [f64; 3]) -> Vec<[f64; 4]> {
    let np = element.nodes_per_direction();
    let one: Vec<(Vec<f64>, Vec<f64>)> = gp.iter().map(|&x| element.shape_1d(x)).collect();
    let mut out = Vec::with_capacity(gp.len().pow(3) * np.pow(3));
    for (n1, d1) in &one {
        for (n2, d2) in &one {
            for (n3, d3) in &one {
                for a1 in 0..np {
                    for a2 in 0..np {
                        for a3 in 0..np {
                            out.push([
                                n1[a1] * n2[a2] * n3[a3],
                                d1[a1] * n2[a2] * n3[a3] * 2.0 / lengths[0],
                                n1[a1] * d2[a2] * n3[a3] * 2.0 / lengths[1],
                                n1[a1] * n2[a2] * d3[a3] * 2.0 / lengths[2],
                            ]);
                        }
                    }
                }
            }
        }
    }
    out
}

/// The per-line tables of an element: where the node lines of a grid direction carry
/// weight and how nodal derivatives are recovered.
///
/// # Math
/// Along a direction of `n` node lines spaced `dx` (element length `p dx`):
/// ```text
/// weight(i) = int l_i dx                      (the basis of node line i integrated)
///   Q1/Q2: the lumped weights dx, 2dx/3, 4dx/3 (halved at the ends)
///   Qp:    sum over the elements sharing line i of w_a p dx / 2  (w_a the GLL weight:
///          exact, the GLL rule integrates degree 2p - 1)
/// d v / dx at line i = sum_j c_j v_j:
///   Q1/Q2: second-order differences (one-sided at the ends)
///   Qp:    (1 / #E) sum_(e sharing i) (2 / (p dx)) sum_b l_b'(xi_a) v(p e + b)
///          (the element polynomials, averaged over the elements sharing the line; exact
///          for polynomials of degree p)
/// ```
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct LineTables {
    element: HexElement,
    /// `int_-1^1 l_a`, `a = 0 ... p`.
    weights: Vec<f64>,
    /// `l_b'(xi_a)` at index `b (p + 1) + a`.
    derivatives: Vec<f64>,
}

impl LineTables {
    /// The tables of `element`.
    pub(super) fn new(element: HexElement) -> Self {
        let nodes = element.reference_nodes();
        let np = nodes.len();
        let weights = match element {
            HexElement::Gll(p) => gll_rule(p).1,
            HexElement::Uniform(_) => vec![],
        };
        let mut derivatives = vec![0.0; np * np];
        for (a, &xa) in nodes.iter().enumerate() {
            let (_, d) = lagrange_basis(&nodes, xa);
            for (b, db) in d.iter().enumerate() {
                derivatives[b * np + a] = *db;
            }
        }
        Self {
            element,
            weights,
            derivatives,
        }
    }

    /// The element.
    pub(super) fn element(&self) -> HexElement {
        self.element
    }

    /// `int l_i dx` of node line `i` of `n` spaced `dx` (see [`LineTables`]).
    pub(crate) fn weight(&self, i: usize, n: usize, dx: f64, periodic: bool) -> f64 {
        match self.element {
            HexElement::Uniform(order) => lumped_weight(order, i, n, dx, periodic),
            HexElement::Gll(p) => {
                let count = if periodic { n / p } else { (n - 1) / p };
                elements_along(p, i, count, periodic)
                    .iter()
                    .map(|&(_, a)| self.weights[a] * 0.5 * p as f64 * dx)
                    .sum()
            }
        }
    }

    /// The derivative at node line `i` of `n` spaced `dx` as weights of the nodal values on
    /// the line: `(line, c_j)` (see [`LineTables`]).
    pub(crate) fn derivative(
        &self,
        i: usize,
        n: usize,
        dx: f64,
        periodic: bool,
    ) -> Vec<(usize, f64)> {
        match self.element {
            HexElement::Uniform(_) => difference_stencil(i, n, dx, periodic).to_vec(),
            HexElement::Gll(p) => {
                let np = p + 1;
                let count = if periodic { n / p } else { (n - 1) / p };
                let along = elements_along(p, i, count, periodic);
                let share = 1.0 / along.len() as f64;
                let scale = 2.0 / (p as f64 * dx) * share;
                let mut out = Vec::with_capacity(along.len() * np);
                for (e, a) in along {
                    for b in 0..np {
                        out.push(((p * e + b) % n, self.derivatives[b * np + a] * scale));
                    }
                }
                out
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gll_lines_integrate_and_differentiate_polynomials_of_degree_p() {
        // 3 elements of degree p on [0, 3 p dx], node lines at the GLL points
        let dx = 0.25;
        for p in 1..=6 {
            let tables = LineTables::new(HexElement::Gll(p));
            let nodes = HexElement::Gll(p).reference_nodes();
            let n = 3 * p + 1;
            let x =
                |i: usize| ((i / p) * p) as f64 * dx + 0.5 * (nodes[i % p] + 1.0) * p as f64 * dx;
            let total: f64 = (0..n).map(|i| tables.weight(i, n, dx, false)).sum();
            assert!(
                (total - 3.0 * p as f64 * dx).abs() < 1e-13,
                "p {p}: {total}"
            );
            // d/dx x^p at every node line
            for i in 0..n {
                let d: f64 = tables
                    .derivative(i, n, dx, false)
                    .iter()
                    .map(|&(j, c)| c * x(j).powi(p as i32))
                    .sum();
                let exact = p as f64 * x(i).powi(p as i32 - 1);
                assert!(
                    (d - exact).abs() < 1e-11 * (1.0 + exact.abs()),
                    "p {p} i {i}"
                );
            }
        }
    }

    #[test]
    fn gll_nodes_of_degree_one_and_two_are_the_uniform_ones() {
        for (order, p) in [(ElementOrder::Q1, 1), (ElementOrder::Q2, 2)] {
            let u = HexElement::from(order).reference_nodes();
            let g = HexElement::Gll(p).reference_nodes();
            assert_eq!(u.len(), g.len());
            for (a, b) in u.iter().zip(&g) {
                assert!((a - b).abs() < 1e-15);
            }
            let (nu, du) = HexElement::from(order).shape_1d(0.3);
            let (ng, dg) = HexElement::Gll(p).shape_1d(0.3);
            for a in 0..=p {
                assert!((nu[a] - ng[a]).abs() < 1e-15 && (du[a] - dg[a]).abs() < 1e-14);
            }
        }
    }

    #[test]
    fn node_counts_name_the_key() {
        assert!(HexElement::Gll(3).check_grid([10, 9, 4], true).is_ok());
        assert!(HexElement::Gll(3).check_grid([10, 10, 4], false).is_ok());
        match HexElement::Gll(3).check_grid([10, 10, 9], false) {
            Err(ElasticityError::InvalidParameter { field, .. }) => assert_eq!(field, "grid.n3"),
            other => panic!("{other:?}"),
        }
        assert!(HexElement::gll(11).is_err());
        assert_eq!(HexElement::Gll(4).method_name(), "solid-qp4");
    }
}
