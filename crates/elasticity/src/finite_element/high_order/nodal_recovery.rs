//! How the Qp operator recovers values and gradients at the nodes (a setting of
//! [`super::QpSettings`]); the recovery itself is in `recovery.rs`.

use crate::error::ElasticityError;

/// How the Qp operator recovers the displacement gradient at a node for its contact rows and
/// output fields (the weak form, the matrix and the solution do not depend on it).
///
/// # Math
/// `Element` (`fem-qp`): the derivatives of the element polynomials at the node, averaged
/// over the elements sharing it (one-sided limits at element edges),
/// ```text
/// d_2 v (node) = (1 / #E2) sum_(e2 in E2) (2 / L2) sum_b l_b'(xi_a) v(p e2 + b, i3)
/// ```
/// exact for polynomials of degree `p` along the direction, so first order in `h` for
/// `p = 1` and order `p` in general.
///
/// `Differences` (`fem-q1`, `fem-q2`): second-order nodal differences on the node lines,
/// which for `p <= 2` on uniform elements are uniformly spaced (the GLL points of `p = 1, 2`
/// are `-1, 1` and `-1, 0, 1`): central inside, one-sided at a bounded end
/// ([`crate::Grid::node_stencil`]),
/// ```text
/// d v (i) = (v(i+1) - v(i-1)) / (2 h),   d v (0) = (-3 v(0) + 4 v(1) - v(2)) / (2 h)
/// ```
/// second order for both orders and the stencil of the finite differences, so both feed the
/// friction law the same kind of data. With selective reduced integration the normal stress
/// takes its volumetric part from the reduced points (the operator's `div_h`, see
/// [`NodalRecovery::Differences`] below); with `Element` the stress stays pointwise.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum NodalRecovery {
    /// The element polynomials' derivatives at the node, averaged over the elements sharing
    /// it (`fem-qp`).
    #[default]
    Element,
    /// Second-order nodal differences on the (uniform) node lines, and under selective
    /// reduced integration the divergence from the reduced points (`fem-q1`, `fem-q2`): for
    /// `p <= 2` on uniform elements only.
    ///
    /// # Math
    /// With [`crate::finite_element::VolumetricIntegration::Reduced`] the normal stress
    /// splits (mixed components, `T^i_j = lambda delta^i_j div v + 2 mu M^i_j`, `M = g^-1 E`):
    /// ```text
    /// T^3_3 = lambda div_h v (node) + 2 mu M^3_3 (node)        T^3_2 = 2 mu M^3_2 (node)
    /// ```
    /// `M` from the nodal differences, `div_h` the divergence SRI controls: the values at
    /// the `p x p` reduced Gauss points of the elements around the node extrapolated to the
    /// node with the tensor Lagrange interpolant of degree `p - 1` through them, averaged
    /// over those elements,
    /// ```text
    /// div_h v (node) = (1 / #E) sum_(e in E(node)) sum_(r, s) l_r(xi_node) l_s(eta_node) div v(xi_r, eta_s)
    /// ```
    /// (Q1: the element-centre value; at a bounded end the centres of the two nearest
    /// element rows extrapolated linearly, `1.5 c_near - 0.5 c_far`. Q2:
    /// `l_(0,1)(s) = (1 -+ sqrt(3) s) / 2`.) The pointwise `lambda div v` carries the
    /// unpenalised checkerboard of SRI amplified by `lambda / mu` (node-to-node oscillation of
    /// `T^3_3` 18-19 times its mean on the paper's contact case); `div_h` converges uniformly
    /// in `nu`. The output fields report `T^ij = lambda g^ij div_h v + 2 mu E^ij` the same
    /// way, so their `T^33 g_33` on `x3 = 0` is the contact row's `T^3_3`.
    Differences,
}

impl NodalRecovery {
    /// Checks that the recovery applies to order `p` on elements spaced as `uniform` says.
    ///
    /// # Errors
    /// [`ElasticityError::InvalidParameter`] naming `recovery` for `Differences` with
    /// `p > 2` or graded elements (the node lines are not uniformly spaced there).
    pub fn check(self, p: usize, uniform: bool) -> Result<(), ElasticityError> {
        if self == Self::Differences && (p > 2 || !uniform) {
            return Err(ElasticityError::InvalidParameter {
                field: "recovery",
                value: p as f64,
                allowed: "nodal differences for p <= 2 on uniform elements only",
            });
        }
        Ok(())
    }
}
