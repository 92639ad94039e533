//! Lagrange elements on the parameter rectangle: Q1 and Q2 shape functions and the tensor
//! Gauss rules that integrate them.

use crate::error::ElasticityError;

/// The polynomial degree of the tensor-product Lagrange element.
///
/// # Math
/// One-dimensional shape functions on the reference interval `xi in [-1, 1]`:
/// ```text
/// Q1: N_0 = (1 - xi)/2,       N_1 = (1 + xi)/2
/// Q2: N_0 = xi (xi - 1)/2,    N_1 = 1 - xi^2,      N_2 = xi (xi + 1)/2
/// ```
/// and `N_(a2, a3)(xi, eta) = N_a2(xi) N_a3(eta)` on the rectangle.
///
/// Quadrature: `k + 1` Gauss points per direction (2 x 2 for Q1, 3 x 3 for Q2), exact for
/// polynomials of degree `2k + 1` per direction. The constant-coefficient stiffness integrand
/// `d N_a d N_b` and the mass-like Christoffel terms `N_a N_b` have degree `2k` per direction,
/// so they are integrated exactly; with the smooth curvilinear coefficients
/// (`A^ijkl sqrt(g)`, Christoffel symbols) the quadrature error is `O(h^(2k+2))` per unit
/// area, below the `O(h^(k+1))` L2 discretisation error (Ciarlet's condition: exactness for
/// degree `2k - 1` keeps the optimal orders).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ElementOrder {
    /// Bilinear (4 nodes).
    Q1,
    /// Biquadratic (9 nodes).
    Q2,
}

impl ElementOrder {
    /// Polynomial degree `k`.
    pub fn degree(self) -> usize {
        match self {
            Self::Q1 => 1,
            Self::Q2 => 2,
        }
    }

    /// The fill-reducing ordering for a sparse Cholesky of these elements on `grid` (2
    /// unknowns per node, numbered as [`crate::Discretisation::dof`]): nested dissection along
    /// element boundaries, one node line per separator
    /// ([`capstan_solvers::nested_dissection_elements`]).
    ///
    /// # Math
    /// ```text
    /// element boundaries: node lines i = 0 mod k;  one such line separates the two sides
    /// ```
    /// Measured on the Lamé cylinder (Q2, `examples/profile_fem_lame.rs`): against AMD on the
    /// node quotient graph, 3% less fill at 33,280 unknowns (2.83e6 against 2.92e6 values of
    /// `L`) and about half the analyse time (no minimum-degree search), the factor time equal
    /// or lower; at 8,448 unknowns the same fill to 0.4%.
    ///
    /// # Example
    /// ```
    /// use capstan_elasticity::Grid;
    /// use capstan_elasticity::finite_element::ElementOrder;
    /// use capstan_elasticity::solvers::{ColumnOrdering, GridShape};
    /// let grid = Grid::new([0.0, 1.0], 1.0, 9, 5, false).unwrap();
    /// let ordering = ElementOrder::Q2.cholesky_ordering(&grid);
    /// let shape = GridShape { n2: 9, n3: 5, dofs_per_node: 2, periodic: false };
    /// assert_eq!(ordering, ColumnOrdering::ElementNestedDissection { grid: shape, degree: 2 });
    /// ```
    pub fn cholesky_ordering(self, grid: &crate::grid::Grid) -> capstan_solvers::ColumnOrdering {
        capstan_solvers::ColumnOrdering::ElementNestedDissection {
            grid: grid.shape(),
            degree: self.degree(),
        }
    }

    /// Nodes per direction, `k + 1`.
    pub fn nodes_per_direction(self) -> usize {
        self.degree() + 1
    }

    /// Nodes per element, `(k + 1)^2`.
    pub fn nodes_per_element(self) -> usize {
        self.nodes_per_direction().pow(2)
    }

    /// Name of the discretisation (`"fem-q1"`, `"fem-q2"`).
    pub fn method_name(self) -> &'static str {
        match self {
            Self::Q1 => "fem-q1",
            Self::Q2 => "fem-q2",
        }
    }

    /// The one-dimensional shape functions and their `xi` derivatives at `xi`.
    pub fn shape_1d(self, xi: f64) -> ([f64; 3], [f64; 3]) {
        match self {
            Self::Q1 => ([0.5 * (1.0 - xi), 0.5 * (1.0 + xi), 0.0], [-0.5, 0.5, 0.0]),
            Self::Q2 => (
                [0.5 * xi * (xi - 1.0), 1.0 - xi * xi, 0.5 * xi * (xi + 1.0)],
                [xi - 0.5, -2.0 * xi, xi + 0.5],
            ),
        }
    }

    /// The one-dimensional Gauss rule with `k + 1` points: `(points, weights)` on `[-1, 1]`.
    pub fn gauss_1d(self) -> (Vec<f64>, Vec<f64>) {
        gauss_rule(self.nodes_per_direction())
    }

    /// Checks that an `n`-node grid direction is a whole number of elements.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `field` if `n - 1` (bounded) or `n`
    /// (periodic) is not a multiple of `k` (Q2 needs odd `n` on a bounded direction, even `n`
    /// on a periodic one).
    pub fn check_nodes(
        self,
        field: &'static str,
        n: usize,
        periodic: bool,
    ) -> Result<(), ElasticityError> {
        check_whole_elements(
            field,
            n,
            periodic,
            self.degree(),
            [
                "odd node counts for Q2",
                "even node counts for Q2 on a periodic direction",
            ],
        )
    }
}

/// Checks that `n` nodes along a direction make whole elements of degree `k`: `n - 1`
/// (bounded) or `n` (periodic) a positive multiple of `k`.
///
/// # Errors
/// [`ElasticityError::InvalidParameter`] naming `field`, with `allowed[0]` (bounded) or
/// `allowed[1]` (periodic) as the allowed range.
pub(crate) fn check_whole_elements(
    field: &'static str,
    n: usize,
    periodic: bool,
    k: usize,
    allowed: [&'static str; 2],
) -> Result<(), ElasticityError> {
    let intervals = if periodic { n } else { n.saturating_sub(1) };
    if intervals > 0 && intervals.is_multiple_of(k) {
        Ok(())
    } else {
        Err(ElasticityError::InvalidParameter {
            field,
            value: n as f64,
            allowed: allowed[usize::from(periodic)],
        })
    }
}

/// Gauss–Legendre rule with `n` points (`1 <= n <= 5`) on `[-1, 1]`.
///
/// # Panics
/// For other `n` (a programmer error: the elements use 2 to 4 points).
#[track_caller]
pub fn gauss_rule(n: usize) -> (Vec<f64>, Vec<f64>) {
    let (p, w): (&[f64], &[f64]) = match n {
        1 => (&[0.0], &[2.0]),
        2 => {
            const A: f64 = 0.577_350_269_189_625_8; // 1/sqrt(3)
            (&[-A, A], &[1.0, 1.0])
        }
        3 => {
            const A: f64 = 0.774_596_669_241_483_4; // sqrt(3/5)
            (&[-A, 0.0, A], &[5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0])
        }
        4 => (
            &[
                -0.861_136_311_594_052_6,
                -0.339_981_043_584_856_3,
                0.339_981_043_584_856_3,
                0.861_136_311_594_052_6,
            ],
            &[
                0.347_854_845_137_453_9,
                0.652_145_154_862_546_1,
                0.652_145_154_862_546_1,
                0.347_854_845_137_453_9,
            ],
        ),
        5 => (
            &[
                -0.906_179_845_938_664,
                -0.538_469_310_105_683_1,
                0.0,
                0.538_469_310_105_683_1,
                0.906_179_845_938_664,
            ],
            &[
                0.236_926_885_056_189_1,
                0.478_628_670_499_366_5,
                0.568_888_888_888_888_9,
                0.478_628_670_499_366_5,
                0.236_926_885_056_189_1,
            ],
        ),
        _ => panic!("gauss_rule: {n} points not tabulated (1..=5)"),
    };
    (p.to_vec(), w.to_vec())
}

/// The Lagrange basis `l_r(s) = prod_(q != r) (s - x_q) / (x_r - x_q)` through `points`, at
/// `s` (one point: the constant `1`).
pub(crate) fn lagrange_weights(points: &[f64], s: f64) -> Vec<f64> {
    points
        .iter()
        .enumerate()
        .map(|(r, &xr)| {
            points
                .iter()
                .enumerate()
                .filter(|&(q, _)| q != r)
                .map(|(_, &xq)| (s - xq) / (xr - xq))
                .product()
        })
        .collect()
}

/// The lumped boundary weight `int N_i dx` of node `i` of `n` on a line of spacing `dx` (row
/// sums of the 1-D mass matrix): Q1 `dx` (`dx/2` at an end), Q2 `2 dx/3` at element ends and
/// `4 dx/3` at midpoints (halved at an end of a non-periodic line).
pub(crate) fn lumped_weight(
    order: ElementOrder,
    i: usize,
    n: usize,
    dx: f64,
    periodic: bool,
) -> f64 {
    let interior = match (order.degree(), i % 2) {
        (1, _) => dx,
        (_, 0) => 2.0 * dx / 3.0,
        _ => 4.0 * dx / 3.0,
    };
    let end = !periodic && (i == 0 || i == n - 1);
    if end { 0.5 * interior } else { interior }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tabulated_gauss_rules_are_the_computed_gauss_legendre_rules() {
        // the computed rules' exactness (degree 2n - 1) is tested in high_order::gll
        for n in 1..=5 {
            let (p, w) = gauss_rule(n);
            let (q, v) = crate::finite_element::high_order::gauss_legendre(n);
            for (a, b) in p.iter().chain(&w).zip(q.iter().chain(&v)) {
                assert!((a - b).abs() < 1e-15, "n {n}: {a} vs {b}"); // tables to 16 digits
            }
        }
    }

    #[test]
    fn shape_functions_are_a_partition_of_unity_and_interpolate_at_nodes() {
        for order in [ElementOrder::Q1, ElementOrder::Q2] {
            let k = order.degree();
            for a in 0..=k {
                let xi = -1.0 + 2.0 * a as f64 / k as f64;
                let (n, d) = order.shape_1d(xi);
                for (b, nb) in n.iter().enumerate().take(k + 1) {
                    assert!((nb - if a == b { 1.0 } else { 0.0 }).abs() < 1e-15);
                }
                assert!(d[..=k].iter().sum::<f64>().abs() < 1e-15);
            }
            let (n, _) = order.shape_1d(0.3);
            assert!((n[..=k].iter().sum::<f64>() - 1.0).abs() < 1e-15);
        }
    }

    #[test]
    fn lagrange_weights_extrapolate_from_the_gauss_points() {
        assert_eq!(lagrange_weights(&[0.0], -1.0), vec![1.0]);
        let (gp, _) = gauss_rule(2);
        let s3 = 3.0f64.sqrt();
        for (s, want) in [
            (-1.0, [0.5 * (1.0 + s3), 0.5 * (1.0 - s3)]),
            (0.0, [0.5, 0.5]),
            (1.0, [0.5 * (1.0 - s3), 0.5 * (1.0 + s3)]),
        ] {
            let w = lagrange_weights(&gp, s);
            for (a, b) in w.iter().zip(want) {
                assert!((a - b).abs() < 1e-15, "{s}: {w:?}"); // closed form: round-off
            }
        }
    }

    #[test]
    fn q2_rejects_even_bounded_and_odd_periodic_node_counts() {
        assert!(ElementOrder::Q2.check_nodes("grid.n2", 10, false).is_err());
        assert!(ElementOrder::Q2.check_nodes("grid.n2", 11, false).is_ok());
        assert!(ElementOrder::Q2.check_nodes("grid.n2", 11, true).is_err());
        assert!(ElementOrder::Q2.check_nodes("grid.n2", 12, true).is_ok());
        assert!(ElementOrder::Q1.check_nodes("grid.n2", 10, false).is_ok());
    }
}
