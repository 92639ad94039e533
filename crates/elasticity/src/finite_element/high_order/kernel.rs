//! The sum-factorised element stiffness of the tensor-product elements: the `6 x 6` pointwise
//! energy matrix of the plane-strain inputs contracted with one-dimensional basis tables,
//! one direction at a time.

/// One-dimensional tables of an element's basis at the points of a tensor rule, scaled to the
/// element: `value[a][q] = l_a(xi_q)`, `d2[a][q] = (2 / L2) l_a'(xi_q)`,
/// `d3[a][q] = (2 / L3) l_a'(xi_q)` (row-major, `n` basis functions by `nq` points).
#[derive(Debug, Clone, PartialEq)]
pub struct ElementTables {
    /// Basis functions per direction, `p + 1`.
    pub n: usize,
    /// Points per direction.
    pub nq: usize,
    /// `l_a(xi_q)`, index `a nq + q`.
    pub value: Vec<f64>,
    /// `(2 / L2) l_a'(xi_q)`, index `a nq + q`.
    pub d2: Vec<f64>,
    /// `(2 / L3) l_a'(xi_q)`, index `a nq + q`.
    pub d3: Vec<f64>,
}

impl ElementTables {
    /// The tables of the Lagrange basis through `nodes` at the points `at`, on an element of
    /// size `[L2, L3]`.
    pub fn new(nodes: &[f64], at: &[f64], size: [f64; 2]) -> Self {
        let (b, d) = super::gll::basis_tables(nodes, at);
        let flat = |t: &[Vec<f64>], s: f64| t.iter().flatten().map(|x| x * s).collect();
        Self {
            n: nodes.len(),
            nq: at.len(),
            value: flat(&b, 1.0),
            d2: flat(&d, 2.0 / size[0]),
            d3: flat(&d, 2.0 / size[1]),
        }
    }

    /// The `x2` factor of input type `t` (0 value, 1 `d_2`, 2 `d_3`).
    fn factor2(&self, t: usize) -> &[f64] {
        if t == 1 { &self.d2 } else { &self.value }
    }
}

/// Adds the element matrix of the pointwise energy matrices `kq` (index `q2 nq + q3`, each
/// already times `sqrt(g)`, the weights and `det J`) to `out` (`l x l`, `l = 2 n^2`, row-major,
/// local dof `2 (a2 n + a3) + c`), by sum factorisation.
///
/// # Math
/// Input `k = 2 t + c` of component `c` (`t = 0` value, `1` `d_2`, `2` `d_3`) at node
/// `(a2, a3)` is `X_t(a2, q2) Y_t(a3, q3)` with `(X, Y) = (B, B), (D2, B), (B, D3)`. Then
/// ```text
/// K[(a2 a3 c), (b2 b3 d)] = sum_(q2, q3) sum_(t, s) X_t(a2,q2) Y_t(a3,q3) Kq[2t+c][2s+d] X_s(b2,q2) Y_s(b3,q3)
/// T_(alpha beta)[a2][b2][q3] = sum_q2 sum_(t: Y_t = alpha, s: Y_s = beta) X_t(a2,q2) Kq[..] X_s(b2,q2)
/// K[(a2 a3 c), (b2 b3 d)] = sum_(alpha, beta in {B, D3}) sum_q3 alpha(a3,q3) beta(b3,q3) T_(alpha beta)[a2][b2][q3]
/// ```
/// `36 n^2 nq^2 + 16 n^4 nq` multiply-adds against `~8 n^4 nq^2 * 6` for the dense `B^T K B`:
/// `O(p^5)` instead of `O(p^6)`.
pub fn add_element_matrix(t: &ElementTables, kq: &[[[f64; 6]; 6]], out: &mut [f64]) {
    let (n, nq) = (t.n, t.nq);
    let l = 2 * n * n;
    debug_assert_eq!(kq.len(), nq * nq);
    debug_assert_eq!(out.len(), l * l);
    // T[cd][alpha][beta][a2][b2][q3]
    let block = n * n * nq;
    let mut tt = vec![0.0; 16 * block];
    for q2 in 0..nq {
        for q3 in 0..nq {
            let k = &kq[q2 * nq + q3];
            for c in 0..2 {
                for d in 0..2 {
                    for ti in 0..3 {
                        let x = t.factor2(ti);
                        let alpha = usize::from(ti == 2);
                        for si in 0..3 {
                            let coef = k[2 * ti + c][2 * si + d];
                            if coef == 0.0 {
                                continue;
                            }
                            let y = t.factor2(si);
                            let beta = usize::from(si == 2);
                            let base = ((2 * c + d) * 4 + 2 * alpha + beta) * block;
                            for a2 in 0..n {
                                let xa = x[a2 * nq + q2] * coef;
                                let row = base + a2 * n * nq;
                                for b2 in 0..n {
                                    tt[row + b2 * nq + q3] += xa * y[b2 * nq + q2];
                                }
                            }
                        }
                    }
                }
            }
        }
    }
    // P[alpha][beta][a3][b3][q3] = alpha(a3, q3) beta(b3, q3)
    let y3 = [&t.value, &t.d3];
    let mut pp = vec![0.0; 4 * block];
    for alpha in 0..2 {
        for beta in 0..2 {
            for a3 in 0..n {
                for b3 in 0..n {
                    for q3 in 0..nq {
                        pp[((2 * alpha + beta) * n * n + a3 * n + b3) * nq + q3] =
                            y3[alpha][a3 * nq + q3] * y3[beta][b3 * nq + q3];
                    }
                }
            }
        }
    }
    for c in 0..2 {
        for d in 0..2 {
            for ab in 0..4 {
                let tb = &tt[((2 * c + d) * 4 + ab) * block..][..block];
                let pb = &pp[ab * n * n * nq..][..n * n * nq];
                for a2 in 0..n {
                    for b2 in 0..n {
                        let tv = &tb[(a2 * n + b2) * nq..][..nq];
                        for a3 in 0..n {
                            let r = 2 * (a2 * n + a3) + c;
                            for b3 in 0..n {
                                let pv = &pb[(a3 * n + b3) * nq..][..nq];
                                let s: f64 = tv.iter().zip(pv).map(|(x, y)| x * y).sum();
                                out[r * l + 2 * (b2 * n + b3) + d] += s;
                            }
                        }
                    }
                }
            }
        }
    }
}

/// The orders up to which [`add_element_matrix_direct`] is the faster kernel (measured with
/// `examples/bench_qp_vs_qk.rs`: at `p = 1, 2` the sum factorisation's bookkeeping costs more
/// than the products it saves).
pub const DIRECT_KERNEL_ORDERS: usize = 2;

/// Adds the element matrix of the pointwise energy matrices `kq` to `out` as
/// [`add_element_matrix`] does, by the direct quadrature loop over the nodes' inputs, for
/// small elements (`(p + 1)^2 <= 9` nodes: `p <= 2`); the fast path of Q1 and Q2.
///
/// # Math
/// With `phi_a = [N_a, d_2 N_a, d_3 N_a]` at point `q` (reference tables, `kq` scaled to
/// the reference element) and `Kq` the point's energy matrix,
/// ```text
/// B[b][r][d] = sum_s Kq[r][2 s + d] phi_b[s]
/// K[(a c), (b d)] += sum_t phi_a[t] B[b][2 t + c][d]        (b d) >= (a c) only
/// ```
/// `36 n^2 + 6 n^2 (2 n^2 + 1)` multiply-adds per point: fewer loops and no scratch
/// allocation against the sum factorisation at these sizes. The upper triangle is computed
/// and added to both triangles, so the result is symmetric as computed.
///
/// # Panics
/// For elements of more than 9 nodes (a programmer error: use [`add_element_matrix`]).
#[track_caller]
pub fn add_element_matrix_direct(t: &ElementTables, kq: &[[[f64; 6]; 6]], out: &mut [f64]) {
    // the sizes as constants: loops of known length, the upper triangle on the stack
    match t.n {
        2 => direct::<4, 64>(t, kq, out),
        3 => direct::<9, 324>(t, kq, out),
        n => panic!("add_element_matrix_direct: {} nodes (4 or 9)", n * n),
    }
}

/// [`add_element_matrix_direct`] for `NEN` nodes, `LL = (2 NEN)^2` local entries.
fn direct<const NEN: usize, const LL: usize>(
    t: &ElementTables,
    kq: &[[[f64; 6]; 6]],
    out: &mut [f64],
) {
    let (n, nq) = (t.n, t.nq);
    let l = 2 * NEN;
    debug_assert_eq!((n * n, l * l), (NEN, LL));
    debug_assert_eq!(kq.len(), nq * nq);
    debug_assert_eq!(out.len(), LL);
    let mut upper = [0.0f64; LL];
    let mut phi = [[0.0f64; 3]; NEN];
    let mut kb = [[[0.0f64; 2]; 6]; NEN];
    for q2 in 0..nq {
        for q3 in 0..nq {
            let k = &kq[q2 * nq + q3];
            for a2 in 0..n {
                let (x, dx) = (t.value[a2 * nq + q2], t.d2[a2 * nq + q2]);
                for a3 in 0..n {
                    let (y, dy) = (t.value[a3 * nq + q3], t.d3[a3 * nq + q3]);
                    phi[a2 * n + a3] = [x * y, dx * y, x * dy];
                }
            }
            for (f, kbb) in phi.iter().zip(kb.iter_mut()) {
                for (kr, krow) in kbb.iter_mut().zip(k) {
                    for (d, x) in kr.iter_mut().enumerate() {
                        *x = krow[d] * f[0] + krow[2 + d] * f[1] + krow[4 + d] * f[2];
                    }
                }
            }
            for (a, f) in phi.iter().enumerate() {
                for c in 0..2 {
                    let r = 2 * a + c;
                    let row = &mut upper[r * l..(r + 1) * l];
                    for (b, kbb) in kb.iter().enumerate().skip(a) {
                        for d in usize::from(b == a && c == 1)..2 {
                            row[2 * b + d] +=
                                f[0] * kbb[c][d] + f[1] * kbb[2 + c][d] + f[2] * kbb[4 + c][d];
                        }
                    }
                }
            }
        }
    }
    for r in 0..l {
        out[r * l + r] += upper[r * l + r];
        for c in r + 1..l {
            let x = upper[r * l + c];
            out[r * l + c] += x;
            out[c * l + r] += x;
        }
    }
}

/// `out <- (out + out^T) / 2`: bitwise symmetric element matrices (the assembly and the
/// Cholesky backend rely on it).
pub fn symmetrise(out: &mut [f64], l: usize) {
    for r in 0..l {
        for c in r + 1..l {
            let s = 0.5 * (out[r * l + c] + out[c * l + r]);
            out[r * l + c] = s;
            out[c * l + r] = s;
        }
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::finite_element::high_order::gll::{gauss_legendre, gll_rule};

    /// `count` deterministic symmetric point matrices without zero entries, for the kernel
    /// tests.
    pub(crate) fn sample_point_matrices(count: usize) -> Vec<[[f64; 6]; 6]> {
        (0..count)
            .map(|q| {
                core::array::from_fn(|a| {
                    core::array::from_fn(|b| {
                        let (i, j) = (a.min(b) as f64, a.max(b) as f64);
                        (1.0 + q as f64 * 0.1 + i * 0.7 + j * 0.3).sin()
                    })
                })
            })
            .collect()
    }

    /// The dense `B^T K B` of the same tables: what the sum factorisation must reproduce.
    fn dense(t: &ElementTables, kq: &[[[f64; 6]; 6]]) -> Vec<f64> {
        let (n, nq) = (t.n, t.nq);
        let l = 2 * n * n;
        let mut out = vec![0.0; l * l];
        for q2 in 0..nq {
            for q3 in 0..nq {
                // phi[k][dof]
                let mut phi = vec![[0.0; 6]; l];
                for a2 in 0..n {
                    for a3 in 0..n {
                        let v = t.value[a2 * nq + q2] * t.value[a3 * nq + q3];
                        let g2 = t.d2[a2 * nq + q2] * t.value[a3 * nq + q3];
                        let g3 = t.value[a2 * nq + q2] * t.d3[a3 * nq + q3];
                        for c in 0..2 {
                            let dof = 2 * (a2 * n + a3) + c;
                            phi[dof][c] = v;
                            phi[dof][2 + c] = g2;
                            phi[dof][4 + c] = g3;
                        }
                    }
                }
                let k = &kq[q2 * nq + q3];
                for i in 0..l {
                    for j in 0..l {
                        let mut s = 0.0;
                        for a in 0..6 {
                            for b in 0..6 {
                                s += phi[i][a] * k[a][b] * phi[j][b];
                            }
                        }
                        out[i * l + j] += s;
                    }
                }
            }
        }
        out
    }

    #[test]
    fn direct_kernel_equals_the_sum_factorisation_for_p_1_and_2() {
        for p in 1..=DIRECT_KERNEL_ORDERS {
            let (x, _) = gll_rule(p);
            // the full rule and the reduced one of selective reduced integration
            for nq in [p + 1, p] {
                let (g, _) = gauss_legendre(nq);
                let t = ElementTables::new(&x, &g, [0.3, 0.7]);
                let kq = sample_point_matrices(nq * nq);
                let l = 2 * (p + 1) * (p + 1);
                let start: Vec<f64> = (0..l * l).map(|i| (i as f64 * 0.37).cos()).collect();
                let (mut direct, mut factorised) = (start.clone(), start);
                add_element_matrix_direct(&t, &kq, &mut direct);
                add_element_matrix(&t, &kq, &mut factorised);
                let scale = factorised.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                for (a, b) in direct.iter().zip(&factorised) {
                    assert!((a - b).abs() < 1e-13 * scale, "p {p}: {a} vs {b}"); // summation order only
                }
            }
        }
    }

    #[test]
    fn sum_factorised_matrix_equals_dense_product() {
        for p in [1, 2, 3, 5] {
            let (x, _) = gll_rule(p);
            let (g, _) = gauss_legendre(p + 1);
            let t = ElementTables::new(&x, &g, [0.3, 0.7]);
            let kq = sample_point_matrices(g.len() * g.len());
            let l = 2 * (p + 1) * (p + 1);
            let mut fast = vec![0.0; l * l];
            add_element_matrix(&t, &kq, &mut fast);
            let slow = dense(&t, &kq);
            let scale = slow.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            for (a, b) in fast.iter().zip(&slow) {
                assert!((a - b).abs() < 1e-12 * scale, "p {p}: {a} vs {b}"); // summation order only
            }
        }
    }
}
