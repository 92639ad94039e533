//! The pointwise energy matrix of linear elasticity in the scalar inputs of a layout.

use capstan_geometry::{Scalar, ShellPoint};

use crate::material::Material;

/// One scalar input of the pointwise operator (paper indices 1, 2, 3 are 0, 1, 2).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Input {
    /// The contravariant component `v^c`.
    Value(usize),
    /// The coordinate derivative `d_p v^c`.
    Derivative {
        /// `p`, the coordinate differentiated along.
        direction: usize,
        /// `c`, the component differentiated.
        component: usize,
    },
}

/// The ordered scalar inputs a discretisation feeds the pointwise operator with.
pub type InputLayout<const N: usize> = [Input; N];

/// The layout of the components and directions `first..3`: the values `v^c`, then the
/// derivatives `d_p v^c` with `p` outer and `c` inner (`n = 3 - first` of each; `N = n + n^2`).
const fn layout<const N: usize>(first: usize) -> InputLayout<N> {
    let n = 3 - first;
    assert!(N == n + n * n, "N must be n + n^2");
    let mut out = [Input::Value(0); N];
    let mut k = 0;
    while k < n {
        out[k] = Input::Value(first + k);
        k += 1;
    }
    let mut k = 0;
    while k < n * n {
        out[n + k] = Input::Derivative {
            direction: first + k / n,
            component: first + k % n,
        };
        k += 1;
    }
    out
}

/// Plane strain (`v^1 = 0`, `d_1 = 0`): `[v^2, v^3, d_2 v^2, d_2 v^3, d_3 v^2, d_3 v^3]`.
pub const PLANE_STRAIN: InputLayout<6> = layout(1);

/// A 3-D body: `[v^1, v^2, v^3, d_1 v^1, d_1 v^2, d_1 v^3, d_2 v^1, ..., d_3 v^3]`
/// (input `3 + 3 p + c` is `d_p v^c`).
pub const SOLID: InputLayout<12> = layout(0);

/// The mixed strains `M_k = g^-1 E_k` of the unit inputs of `layout`.
///
/// # Math
/// ```text
/// N_k[i][n] = nabla_i v^n    Gamma^n_{i m} for the value v^m,  delta_i^p delta^n_c for d_p v^c
/// E_k[i][l] = (N_k[i][n] g_nl + N_k[l][n] g_ni) / 2        covariant strain
/// M_k[i][l] = g^ij E_k[j][l]                               mixed strain E^i_l
/// ```
/// For any scalar `S` (`f64`, or dual numbers for the exact derivatives of the manufactured
/// forcing).
#[allow(clippy::needless_range_loop)] // index loops mirror the tensor formulas
pub fn mixed_strains<S: Scalar<f64>, const N: usize>(
    p: &ShellPoint<S>,
    layout: &InputLayout<N>,
) -> [[[S; 3]; 3]; N] {
    let (g, gi, gamma) = (&p.metric, &p.inverse_metric, &p.christoffel);
    let mut mixed = [[[S::zero(); 3]; 3]; N];
    for (mk, input) in mixed.iter_mut().zip(layout) {
        // h[i][l] = N_k[i][n] g_nl
        let mut h = [[S::zero(); 3]; 3];
        match *input {
            Input::Value(m) => {
                for i in 0..3 {
                    for l in 0..3 {
                        h[i][l] = gamma[0][i][m] * g[0][l]
                            + gamma[1][i][m] * g[1][l]
                            + gamma[2][i][m] * g[2][l];
                    }
                }
            }
            Input::Derivative {
                direction,
                component,
            } => h[direction] = g[component],
        }
        let mut e = [[S::zero(); 3]; 3];
        for i in 0..3 {
            for l in 0..3 {
                e[i][l] = (h[i][l] + h[l][i]) * 0.5;
            }
        }
        for i in 0..3 {
            for l in 0..3 {
                mk[i][l] = gi[i][0] * e[0][l] + gi[i][1] * e[1][l] + gi[i][2] * e[2][l];
            }
        }
    }
    mixed
}

/// The symmetric energy matrix `K[k][l]` of the unit inputs of `layout`, times `scale`: the
/// integrand of the weak form is `u^T K w` for inputs `u` of the displacement and `w` of the
/// test function.
///
/// # Math
/// ```text
/// K[k][l] = scale sqrt(g) (lambda tr M_k tr M_l + 2 mu tr(M_k M_l))
///         = scale sqrt(g) T^i_j(u_k) nabla_i w_l^j        (T^ij symmetric)
/// ```
/// with `M_k` of [`mixed_strains`]; `lambda = 0` leaves the shear part of selective reduced
/// integration. Equal to the contraction with the mixed stress of
/// [`super::kinematics::mixed_stress_coefficients`] to round-off (tested), at a fifth of
/// the cost.
#[allow(clippy::needless_range_loop)] // index loops mirror the tensor formulas
pub fn energy_matrix<const N: usize>(
    p: &ShellPoint<f64>,
    layout: &InputLayout<N>,
    lambda: f64,
    mu: f64,
    scale: f64,
) -> [[f64; N]; N] {
    let mixed = mixed_strains(p, layout);
    let trace = mixed.map(|m| m[0][0] + m[1][1] + m[2][2]);
    let two_mu = 2.0 * mu;
    let w = p.sqrt_g * scale;
    let mut k = [[0.0; N]; N];
    for a in 0..N {
        for b in a..N {
            let mut s = 0.0;
            for i in 0..3 {
                for l in 0..3 {
                    s += mixed[a][i][l] * mixed[b][l][i];
                }
            }
            k[a][b] = (lambda * trace[a] * trace[b] + two_mu * s) * w;
            k[b][a] = k[a][b];
        }
    }
    k
}

/// [`energy_matrix`] with the Lamé constants of `material`.
pub fn stiffness_matrix<const N: usize>(
    p: &ShellPoint<f64>,
    layout: &InputLayout<N>,
    material: &Material,
    scale: f64,
) -> [[f64; N]; N] {
    energy_matrix(p, layout, material.lambda(), material.mu(), scale)
}

/// The traces `tr M_k = nabla_i v^i` of the unit inputs: the divergence is
/// `div v = sum_k u_k tr M_k` (`tr M_k = Gamma^i_im` for the value `v^m`, `delta_pc` for
/// `d_p v^c`).
pub fn divergence_coefficients<const N: usize>(
    p: &ShellPoint<f64>,
    layout: &InputLayout<N>,
) -> [f64; N] {
    mixed_strains(p, layout).map(|m| m[0][0] + m[1][1] + m[2][2])
}

/// The mixed stress `T^i_j` of a displacement whose inputs (values of the unit inputs of
/// `layout`) are `u`.
///
/// # Math
/// ```text
/// M = sum_k u_k M_k          mixed strain E^i_j
/// T^i_j = lambda delta^i_j tr M + 2 mu M^i_j
/// ```
/// For any scalar `S`, like [`mixed_strains`].
pub fn mixed_stress_of<S: Scalar<f64>, const N: usize>(
    p: &ShellPoint<S>,
    layout: &InputLayout<N>,
    material: &Material,
    u: &[S; N],
) -> [[S; 3]; 3] {
    let strains = mixed_strains(p, layout);
    let mut m = [[S::zero(); 3]; 3];
    for (mk, uk) in strains.iter().zip(u) {
        for (row, rk) in m.iter_mut().zip(mk) {
            for (x, y) in row.iter_mut().zip(rk) {
                *x += *uk * *y;
            }
        }
    }
    let trace = m[0][0] + m[1][1] + m[2][2];
    let (lambda, two_mu) = (material.lambda(), 2.0 * material.mu());
    core::array::from_fn(|i| {
        core::array::from_fn(|j| {
            let delta = if i == j { trace * lambda } else { S::zero() };
            delta + m[i][j] * two_mu
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use capstan_geometry::{EllipticalPrism, ShellChart};

    use crate::continuum::kinematics::{LocalDisplacement, mixed_stress_coefficients};

    fn point() -> ShellPoint<f64> {
        ShellChart::new(EllipticalPrism::new(2.0, 1.0).unwrap())
            .point([0.0, 0.4, 0.3])
            .unwrap()
    }

    #[test]
    fn layouts_are_the_documented_orders() {
        let d = |direction, component| Input::Derivative {
            direction,
            component,
        };
        for c in 0..3 {
            assert_eq!(SOLID[c], Input::Value(c));
            for p in 0..3 {
                assert_eq!(SOLID[3 + 3 * p + c], d(p, c));
            }
        }
        let plane = [1, 2].map(Input::Value);
        assert_eq!(PLANE_STRAIN[..2], plane);
        assert_eq!(PLANE_STRAIN[2..], [d(1, 1), d(1, 2), d(2, 1), d(2, 2)]);
    }

    #[test]
    #[allow(clippy::needless_range_loop)] // mirrors sqrt(g) T^i_j(u_k) nabla_i w_l^j
    fn plane_strain_energy_matrix_is_the_stress_contraction() {
        let p = point();
        let m = Material::new(3.0, 0.3).unwrap();
        let k = stiffness_matrix(&p, &PLANE_STRAIN, &m, 1.0);
        let c = mixed_stress_coefficients(&p, &m);
        for a in 0..6 {
            for b in 0..6 {
                let w = LocalDisplacement::unit(b);
                let grad = crate::continuum::kinematics::covariant_derivative(&p, &w);
                // nabla_i w^j = g^jl nabla_i w_l
                let mut s = 0.0;
                for i in 0..3 {
                    for j in 0..3 {
                        let nab: f64 = (0..3).map(|l| p.inverse_metric[j][l] * grad[i][l]).sum();
                        s += c[a][i][j] * nab;
                    }
                }
                // round-off of a few hundred operations on O(1) numbers
                assert!((p.sqrt_g * s - k[a][b]).abs() < 1e-12, "K[{a}][{b}]");
            }
        }
    }

    #[test]
    fn solid_layout_restricted_to_plane_strain_inputs_is_the_plane_strain_matrix() {
        // on a prism the 3-D matrix at the plane-strain inputs equals the plane-strain matrix
        let p = point();
        let k2 = energy_matrix(&p, &PLANE_STRAIN, 1.3, 0.7, 2.0);
        let k3 = energy_matrix(&p, &SOLID, 1.3, 0.7, 2.0);
        let map = [1, 2, 7, 8, 10, 11]; // v^2, v^3, d_2 v^2, d_2 v^3, d_3 v^2, d_3 v^3
        for a in 0..6 {
            for b in 0..6 {
                assert_eq!(k2[a][b], k3[map[a]][map[b]]); // same arithmetic
            }
        }
        // the stress of plane-strain inputs is the plane-strain stress
        let m = Material::new(3.0, 0.3).unwrap();
        let u = LocalDisplacement {
            value: [0.3, -0.2],
            gradient: [[0.7, 0.1], [-0.4, 0.25]],
        };
        let mut inputs = [0.0; 12];
        for (k, x) in map.iter().zip(u.to_inputs()) {
            inputs[*k] = x;
        }
        let t3 = mixed_stress_of(&p, &SOLID, &m, &inputs);
        let t2 = crate::continuum::kinematics::mixed_stress(&p, &m, &u);
        for i in 0..3 {
            for j in 0..3 {
                assert!((t3[i][j] - t2[i][j]).abs() < 1e-13, "T^{i}_{j}"); // round-off
            }
        }
        let d3 = divergence_coefficients(&p, &SOLID);
        // tr M of d_p v^c is g^pl g_lc = delta_pc: round-off of a 3 x 3 product
        assert!((d3[3] + d3[7] + d3[11] - 3.0).abs() < 1e-14);
        assert!(d3[4].abs() < 1e-14 && d3[6].abs() < 1e-14);
    }
}
