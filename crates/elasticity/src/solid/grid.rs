//! The structured grid of the parametric box of a 3-D body.

use crate::error::ElasticityError;

/// An `n1 x n2 x n3` grid of nodes on the box `[x1a, x1b] x [x2a, x2b] x [0, h]`.
///
/// # Math
/// ```text
/// x1_i = x1a + i dx1,  dx1 = (x1b - x1a)/(n1 - 1)
/// x2_j = x2a + j dx2,  dx2 = (x2b - x2a)/(n2 - 1), or /n2 when periodic (node n2 == node 0)
/// x3_k = k dx3,        dx3 = h/(n3 - 1)
/// node (i, j, k) has number (i n2 + j) n3 + k
/// ```
/// With GLL node lines of degree `p` ([`BoxGrid::with_gll_lines`], the nodes of the Qp
/// hexahedra) the element boundaries stay every `p`-th line of that uniform grid and the
/// node lines inside an element sit at the Gauss–Lobatto–Legendre points:
/// ```text
/// i = p e + a:   x_i = x_(p e) + (1 + xi_a)/2 p dx,   xi_a the GLL points of [-1, 1]
/// ```
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct BoxGrid {
    x1: [f64; 2],
    x2: [f64; 2],
    thickness: f64,
    n: [usize; 3],
    periodic: bool,
    #[serde(skip)]
    lines: Option<GllLines>,
}

/// The GLL node lines of degree `p` inside an element: `offsets[a] = (1 + xi_a)/2`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct GllLines {
    degree: usize,
    offsets: [f64; 11],
}

impl BoxGrid {
    /// The grid with `n = [n1, n2, n3]` nodes; `periodic` wraps `x2` (then `x2b - x2a` is the
    /// period).
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming the scene key (`body.width` for the `x1`
    /// extent, `grid.n1`, `grid.n2`, `grid.n3`, `body.thickness`, `membrane.theta0`) of the
    /// first bad value: fewer than 2 nodes per direction (3 for periodic `x2`), an empty or
    /// non-finite interval, a non-positive thickness.
    pub fn new(
        x1: [f64; 2],
        x2: [f64; 2],
        thickness: f64,
        n: [usize; 3],
        periodic: bool,
    ) -> Result<Self, ElasticityError> {
        let bad = |field, value: f64, allowed| {
            Err(ElasticityError::InvalidParameter {
                field,
                value,
                allowed,
            })
        };
        if !(x1[0].is_finite() && x1[1].is_finite() && x1[1] > x1[0]) {
            return bad("body.width", x1[1] - x1[0], "(0, inf)");
        }
        if !(x2[0].is_finite() && x2[1].is_finite() && x2[1] > x2[0]) {
            return bad("membrane.theta0", x2[0], "below theta_max, finite");
        }
        if !(thickness.is_finite() && thickness > 0.0) {
            return bad("body.thickness", thickness, "(0, inf)");
        }
        if n[0] < 2 {
            return bad("grid.n1", n[0] as f64, "[2, inf)");
        }
        if n[1] < if periodic { 3 } else { 2 } {
            return bad("grid.n2", n[1] as f64, "[2, inf) ([3, inf) when periodic)");
        }
        if n[2] < 2 {
            return bad("grid.n3", n[2] as f64, "[2, inf)");
        }
        Ok(Self {
            x1,
            x2,
            thickness,
            n,
            periodic,
            lines: None,
        })
    }

    /// The same box (`x1` and `x2` ranges, thickness, periodicity) with `n` uniformly spaced
    /// nodes per direction: a coarser (or p-) level of a multigrid hierarchy on this body.
    ///
    /// # Errors
    /// As [`BoxGrid::new`] for the counts `n`.
    pub fn with_counts(&self, n: [usize; 3]) -> Result<Self, ElasticityError> {
        Self::new(
            self.x1_range(),
            self.x2_range(),
            self.thickness(),
            n,
            self.is_periodic(),
        )
    }

    /// The same grid with the node lines of every element of degree `p` at the GLL points
    /// (see [`BoxGrid`]); `p = 1` is the uniform grid.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `discretisation.order` outside `1..=10`,
    /// or `grid.n1`, `grid.n2`, `grid.n3` when `n - 1` (periodic `x2`: `n2`) is not a
    /// multiple of `p`.
    pub fn with_gll_lines(self, p: usize) -> Result<Self, ElasticityError> {
        let element = super::element::HexElement::gll(p)?;
        element.check_grid(self.n, self.periodic)?;
        let mut offsets = [0.0; 11];
        for (o, xi) in offsets.iter_mut().zip(element.reference_nodes()) {
            *o = 0.5 * (1.0 + xi);
        }
        Ok(Self {
            lines: Some(GllLines { degree: p, offsets }),
            ..self
        })
    }

    /// The degree of the GLL node lines (`None`: uniform nodes).
    pub fn gll_degree(&self) -> Option<usize> {
        self.lines.map(|l| l.degree)
    }

    /// Nodes per direction `[n1, n2, n3]`.
    pub fn counts(&self) -> [usize; 3] {
        self.n
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.n[0] * self.n[1] * self.n[2]
    }

    /// Whether `x2` is periodic.
    pub fn is_periodic(&self) -> bool {
        self.periodic
    }

    /// `[x1a, x1b]`.
    pub fn x1_range(&self) -> [f64; 2] {
        self.x1
    }

    /// `[x2a, x2b]`.
    pub fn x2_range(&self) -> [f64; 2] {
        self.x2
    }

    /// `h`.
    pub fn thickness(&self) -> f64 {
        self.thickness
    }

    /// Spacings `[dx1, dx2, dx3]` of the uniform grid (with GLL node lines: the element
    /// lengths divided by `p`).
    pub fn spacing(&self) -> [f64; 3] {
        let [n1, n2, n3] = self.n;
        let cells2 = if self.periodic { n2 } else { n2 - 1 };
        [
            (self.x1[1] - self.x1[0]) / (n1 - 1) as f64,
            (self.x2[1] - self.x2[0]) / cells2 as f64,
            self.thickness / (n3 - 1) as f64,
        ]
    }

    /// Coordinates of node `(i, j, k)` (at the GLL points inside the elements when the grid
    /// has GLL node lines).
    pub fn coordinates(&self, [i, j, k]: [usize; 3]) -> [f64; 3] {
        let d = self.spacing();
        let at = |start: f64, i: usize, d: f64| match self.lines {
            None => start + i as f64 * d,
            Some(GllLines { degree: p, offsets }) => {
                start + (i - i % p) as f64 * d + offsets[i % p] * p as f64 * d
            }
        };
        [
            at(self.x1[0], i, d[0]),
            at(self.x2[0], j, d[1]),
            at(0.0, k, d[2]),
        ]
    }

    /// Number of node `(i, j, k)`.
    pub fn node_index(&self, [i, j, k]: [usize; 3]) -> usize {
        (i * self.n[1] + j) * self.n[2] + k
    }

    /// Node `(i, j, k)` of number `m`.
    pub fn node(&self, m: usize) -> [usize; 3] {
        let k = m % self.n[2];
        let ij = m / self.n[2];
        [ij / self.n[1], ij % self.n[1], k]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbering_round_trips_and_periodic_spacing_wraps() {
        let g = BoxGrid::new([1.0, 2.0], [0.0, 6.0], 0.5, [3, 4, 5], true).unwrap();
        for m in 0..g.node_count() {
            assert_eq!(g.node_index(g.node(m)), m);
        }
        assert_eq!(g.spacing(), [0.5, 1.5, 0.125]);
        assert_eq!(g.coordinates([2, 3, 4]), [2.0, 4.5, 0.5]);
    }

    #[test]
    fn gll_lines_sit_at_the_gll_points_of_each_element() {
        let g = BoxGrid::new([1.0, 2.0], [0.0, 6.0], 0.5, [4, 6, 7], true)
            .unwrap()
            .with_gll_lines(3)
            .unwrap();
        let xi = 5f64.sqrt().recip(); // the interior GLL points of degree 3: -+1/sqrt(5)
        let x = g.coordinates([1, 4, 5]);
        assert!((x[0] - (1.0 + 0.5 * (1.0 - xi))).abs() < 1e-15);
        assert!((x[1] - (3.0 + 1.5 * (1.0 - xi))).abs() < 1e-15);
        assert!((x[2] - (0.25 + 0.125 * (1.0 + xi))).abs() < 1e-15);
        // element boundaries are those of the uniform grid
        assert_eq!(g.coordinates([3, 3, 3]), [2.0, 3.0, 0.25]);
        assert_eq!(g.gll_degree(), Some(3));
        let bad = BoxGrid::new([1.0, 2.0], [0.0, 6.0], 0.5, [4, 6, 6], false).unwrap();
        assert!(matches!(
            bad.with_gll_lines(3),
            Err(ElasticityError::InvalidParameter {
                field: "grid.n2",
                ..
            })
        ));
    }

    #[test]
    fn new_names_the_bad_key() {
        let field = |r: Result<BoxGrid, ElasticityError>| match r {
            Err(ElasticityError::InvalidParameter { field, .. }) => field,
            other => panic!("{other:?}"),
        };
        assert_eq!(
            field(BoxGrid::new([1.0, 1.0], [0.0, 1.0], 1.0, [2, 2, 2], false)),
            "body.width"
        );
        assert_eq!(
            field(BoxGrid::new([0.0, 1.0], [0.0, 1.0], 1.0, [1, 2, 2], false)),
            "grid.n1"
        );
        assert_eq!(
            field(BoxGrid::new([0.0, 1.0], [0.0, 1.0], 0.0, [2, 2, 2], false)),
            "body.thickness"
        );
    }
}
