//! Pointwise plane-strain kinematics: covariant derivatives, strain and stress of a displacement
//! `v = (0, v^2(x2, x3), v^3(x2, x3))` at one point of a shell chart.

use capstan_geometry::ShellPoint;

use crate::material::Material;

/// The displacement and its coordinate derivatives at one point (plane strain: `v^1 = 0`,
/// `d_1 = 0`).
///
/// `value = [v^2, v^3]` (contravariant components; `v^2` in radians on an angular chart) and
/// `gradient[a][c] = d_{a+2} v^{c+2}`, i.e. `gradient[0]` holds `d_2`, `gradient[1]` holds `d_3`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LocalDisplacement {
    /// `[v^2, v^3]`.
    pub value: [f64; 2],
    /// `[[d_2 v^2, d_2 v^3], [d_3 v^2, d_3 v^3]]`.
    pub gradient: [[f64; 2]; 2],
}

impl LocalDisplacement {
    /// Number of scalar inputs (`v^2, v^3, d_2 v^2, d_2 v^3, d_3 v^2, d_3 v^3`).
    pub const INPUTS: usize = 6;

    /// The inputs as one vector `[v^2, v^3, d_2 v^2, d_2 v^3, d_3 v^2, d_3 v^3]`.
    pub fn to_inputs(&self) -> [f64; 6] {
        let [v, [a, b], [c, d]] = [self.value, self.gradient[0], self.gradient[1]];
        [v[0], v[1], a, b, c, d]
    }

    /// The local displacement recovered by a nodal stencil: `stencil` gives, per node, the
    /// weights `[value, d_2, d_3]`, `value(node, c)` the nodal value of `v^(c+2)`.
    ///
    /// # Math
    /// ```text
    /// v^c = sum_n w0_n v^c_n,   d_2 v^c = sum_n w2_n v^c_n,   d_3 v^c = sum_n w3_n v^c_n
    /// ```
    pub fn from_stencil<'a>(
        stencil: impl IntoIterator<Item = &'a ([usize; 2], [f64; 3])>,
        value: impl Fn([usize; 2], usize) -> f64,
    ) -> Self {
        let mut u = [0.0; 6];
        for (n, w) in stencil {
            for c in 0..2 {
                let x = value(*n, c);
                u[c] += w[0] * x;
                u[2 + c] += w[1] * x;
                u[4 + c] += w[2] * x;
            }
        }
        Self {
            value: [u[0], u[1]],
            gradient: [[u[2], u[3]], [u[4], u[5]]],
        }
    }

    /// The unit displacement whose input number `k` is one and all others zero.
    pub fn unit(k: usize) -> Self {
        let mut u = [0.0; 6];
        u[k] = 1.0;
        Self {
            value: [u[0], u[1]],
            gradient: [[u[2], u[3]], [u[4], u[5]]],
        }
    }
}

/// Covariant derivative of the covariant displacement, `nabla_k v_l`, indexed `[k][l]`.
///
/// # Math
/// ```text
/// nabla_k v^n = d_k v^n + Gamma^n_km v^m        (d_1 = 0, v^1 = 0)
/// nabla_k v_l = g_ln nabla_k v^n
/// ```
#[allow(clippy::needless_range_loop)] // index loops mirror the tensor formulas
pub fn covariant_derivative(p: &ShellPoint<f64>, u: &LocalDisplacement) -> [[f64; 3]; 3] {
    let v = [0.0, u.value[0], u.value[1]];
    let mut d = [[0.0; 3]; 3]; // d[k][n] = d_k v^n
    for a in 0..2 {
        for c in 0..2 {
            d[a + 1][c + 1] = u.gradient[a][c];
        }
    }
    let mut mixed = [[0.0; 3]; 3]; // mixed[k][n] = nabla_k v^n
    for k in 0..3 {
        for n in 0..3 {
            let mut s = d[k][n];
            for m in 1..3 {
                s += p.christoffel[n][k][m] * v[m];
            }
            mixed[k][n] = s;
        }
    }
    let mut out = [[0.0; 3]; 3];
    for k in 0..3 {
        for l in 0..3 {
            out[k][l] = (0..3).map(|n| p.metric[l][n] * mixed[k][n]).sum();
        }
    }
    out
}

/// Linearised strain `E_kl = (nabla_k v_l + nabla_l v_k) / 2`, indexed `[k][l]`.
pub fn strain(p: &ShellPoint<f64>, u: &LocalDisplacement) -> [[f64; 3]; 3] {
    let d = covariant_derivative(p, u);
    let mut e = [[0.0; 3]; 3];
    for (k, row) in e.iter_mut().enumerate() {
        for (l, x) in row.iter_mut().enumerate() {
            *x = 0.5 * (d[k][l] + d[l][k]);
        }
    }
    e
}

/// Contravariant stress `T^ij = A^ijkl E_kl = lambda g^ij E^m_m + 2 mu g^ik g^jl E_kl`.
#[allow(clippy::needless_range_loop)] // index loops mirror the tensor formulas
pub fn contravariant_stress(
    p: &ShellPoint<f64>,
    m: &Material,
    u: &LocalDisplacement,
) -> [[f64; 3]; 3] {
    let e = strain(p, u);
    let g = &p.inverse_metric;
    // mixed strain E^i_l = g^ik E_kl
    let mut em = [[0.0; 3]; 3];
    for i in 0..3 {
        for l in 0..3 {
            em[i][l] = (0..3).map(|k| g[i][k] * e[k][l]).sum();
        }
    }
    let trace = em[0][0] + em[1][1] + em[2][2];
    let (lambda, mu) = (m.lambda(), m.mu());
    let mut t = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            let eij: f64 = (0..3).map(|l| em[i][l] * g[l][j]).sum();
            t[i][j] = lambda * g[i][j] * trace + 2.0 * mu * eij;
        }
    }
    t
}

/// Mixed stress `T^i_j = T^ik g_kj`, indexed `[i][j]`.
#[allow(clippy::needless_range_loop)] // index loops mirror the tensor formulas
pub fn mixed_stress(p: &ShellPoint<f64>, m: &Material, u: &LocalDisplacement) -> [[f64; 3]; 3] {
    let t = contravariant_stress(p, m, u);
    let mut out = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            out[i][j] = (0..3).map(|k| t[i][k] * p.metric[k][j]).sum();
        }
    }
    out
}

/// The non-derivative part of the divergence in conservative form, `Gamma^k_ij T^i_k`, for `j`.
///
/// # Math
/// ```text
/// nabla_i T^i_j = (1/sqrt(g)) d_i (sqrt(g) T^i_j) - Gamma^k_ij T^i_k
/// ```
pub fn christoffel_contraction(p: &ShellPoint<f64>, mixed: &[[f64; 3]; 3], j: usize) -> f64 {
    let mut s = 0.0;
    for (i, row) in mixed.iter().enumerate() {
        for (k, t) in row.iter().enumerate() {
            s += p.christoffel[k][i][j] * t;
        }
    }
    s
}

/// `T^i_j` for each of the six unit inputs of [`LocalDisplacement`]: by linearity,
/// `T^i_j(u) = sum_k u_k coefficients[k][i][j]`.
pub fn mixed_stress_coefficients(p: &ShellPoint<f64>, m: &Material) -> [[[f64; 3]; 3]; 6] {
    core::array::from_fn(|k| mixed_stress(p, m, &LocalDisplacement::unit(k)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use capstan_geometry::{EllipticalPrism, ShellChart};

    fn sample() -> (ShellPoint<f64>, Material, LocalDisplacement) {
        let chart = ShellChart::new(EllipticalPrism::new(2.0, 1.0).unwrap());
        let p = chart.point([0.0, 0.4, 0.3]).unwrap();
        let u = LocalDisplacement {
            value: [0.3, -0.2],
            gradient: [[0.7, 0.1], [-0.4, 0.25]],
        };
        (p, Material::new(3.0, 0.3).unwrap(), u)
    }

    #[test]
    #[allow(clippy::needless_range_loop)] // mirrors A^ijkl E_kl
    fn stress_equals_elasticity_tensor_contraction() {
        let (p, m, u) = sample();
        let a = m.elasticity_tensor(&p.inverse_metric);
        let e = strain(&p, &u);
        let t = contravariant_stress(&p, &m, &u);
        for i in 0..3 {
            for j in 0..3 {
                let mut s = 0.0;
                for k in 0..3 {
                    for l in 0..3 {
                        s += a[i][j][k][l] * e[k][l];
                    }
                }
                assert!((s - t[i][j]).abs() < 1e-12, "T^{i}{j}"); // round-off only
            }
        }
    }

    #[test]
    fn strain_matches_cartesian_displacement_gradient() {
        // E_kl = sym(g_k . d_l U) with U = v^i g_i the Cartesian displacement.
        let (p, _, u) = sample();
        let chart = ShellChart::new(EllipticalPrism::new(2.0, 1.0).unwrap());
        let cart = |x2: f64, x3: f64| {
            let q = chart.point([0.0, x2, x3]).unwrap();
            let v2 = u.value[0] + u.gradient[0][0] * (x2 - 0.4) + u.gradient[1][0] * (x3 - 0.3);
            let v3 = u.value[1] + u.gradient[0][1] * (x2 - 0.4) + u.gradient[1][1] * (x3 - 0.3);
            [0, 1, 2].map(|k| v2 * q.covariant_basis[1][k] + v3 * q.covariant_basis[2][k])
        };
        let h = 1e-5;
        let d2: [f64; 3] = {
            let (a, b) = (cart(0.4 + h, 0.3), cart(0.4 - h, 0.3));
            [0, 1, 2].map(|k| (a[k] - b[k]) / (2.0 * h))
        };
        let d3: [f64; 3] = {
            let (a, b) = (cart(0.4, 0.3 + h), cart(0.4, 0.3 - h));
            [0, 1, 2].map(|k| (a[k] - b[k]) / (2.0 * h))
        };
        let dot = |a: &[f64; 3], b: &[f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let g = &p.covariant_basis;
        let e = strain(&p, &u);
        let e22 = dot(&g[1], &d2);
        let e33 = dot(&g[2], &d3);
        let e23 = 0.5 * (dot(&g[1], &d3) + dot(&g[2], &d2));
        // central differences with h = 1e-5: error ~1e-10
        assert!((e[1][1] - e22).abs() < 1e-8);
        assert!((e[2][2] - e33).abs() < 1e-8);
        assert!((e[1][2] - e23).abs() < 1e-8);
        assert!(e[0].iter().all(|x| x.abs() < 1e-14));
    }

    #[test]
    fn coefficients_reproduce_stress_by_linearity() {
        let (p, m, u) = sample();
        let c = mixed_stress_coefficients(&p, &m);
        let t = mixed_stress(&p, &m, &u);
        let inputs = u.to_inputs();
        for i in 0..3 {
            for j in 0..3 {
                let s: f64 = (0..6).map(|k| inputs[k] * c[k][i][j]).sum();
                assert!((s - t[i][j]).abs() < 1e-12);
            }
        }
    }
}
