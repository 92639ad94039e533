//! One-dimensional ingredients of the tensor-product elements: Gauss–Lobatto–Legendre (GLL)
//! nodes and weights, Gauss–Legendre rules of any size, and the Lagrange basis through a set
//! of nodes with its derivative.

use crate::finite_element::gauss_rule;

/// Legendre polynomials `P_(n-1)(x)`, `P_n(x)` by the three-term recurrence.
///
/// # Math
/// ```text
/// P_0 = 1,  P_1 = x,  k P_k = (2k - 1) x P_(k-1) - (k - 1) P_(k-2)
/// ```
fn legendre_pair(n: usize, x: f64) -> (f64, f64) {
    let (mut prev, mut cur) = (1.0, x);
    if n == 0 {
        return (0.0, 1.0);
    }
    for k in 2..=n {
        let kf = k as f64;
        let next = ((2.0 * kf - 1.0) * x * cur - (kf - 1.0) * prev) / kf;
        prev = cur;
        cur = next;
    }
    (prev, cur)
}

/// The `p + 1` Gauss–Lobatto–Legendre nodes and weights on `[-1, 1]` (`p >= 1`), increasing.
///
/// # Math
/// ```text
/// nodes:   x_0 = -1,  x_p = 1,  P_p'(x_j) = 0 for 0 < j < p
/// weights: w_j = 2 / (p (p + 1) P_p(x_j)^2)
/// ```
/// exact for polynomials of degree `2p - 1`. The interior nodes are found by Newton's method
/// on `(1 - x^2) P_p'(x) = p (P_(p-1) - x P_p)`, started from the Chebyshev–Gauss–Lobatto
/// points `-cos(pi j / p)`: the iteration `x <- x - (x P_p - P_(p-1)) / ((p + 1) P_p)`
/// converges quadratically from them.
///
/// # Panics
/// If `p == 0`.
///
/// # Example
/// ```
/// use capstan_elasticity::finite_element::gll_rule;
/// let (x, w) = gll_rule(2);
/// assert!((x[1]).abs() < 1e-15 && (w[1] - 4.0 / 3.0).abs() < 1e-15); // Simpson's rule
/// ```
#[track_caller]
pub fn gll_rule(p: usize) -> (Vec<f64>, Vec<f64>) {
    assert!(p >= 1, "gll_rule: p = 0 has no Lobatto rule");
    let pf = p as f64;
    let mut x: Vec<f64> = (0..=p)
        .map(|j| -(core::f64::consts::PI * j as f64 / pf).cos())
        .collect();
    x[0] = -1.0;
    x[p] = 1.0;
    for xj in x.iter_mut().take(p).skip(1) {
        for _ in 0..100 {
            let (pm, pp) = legendre_pair(p, *xj);
            let dx = (*xj * pp - pm) / ((pf + 1.0) * pp);
            *xj -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
    }
    // symmetrise: x_(p - j) = -x_j exactly
    for j in 0..=p / 2 {
        let s = 0.5 * (x[p - j] - x[j]);
        x[j] = -s;
        x[p - j] = s;
    }
    let w = x
        .iter()
        .map(|&xj| {
            let (_, pp) = legendre_pair(p, xj);
            2.0 / (pf * (pf + 1.0) * pp * pp)
        })
        .collect();
    (x, w)
}

/// The `n`-point Gauss–Legendre rule on `[-1, 1]` (`n >= 1`), exact for degree `2n - 1`:
/// the tabulated [`gauss_rule`] for `n <= 5` (the rules of the Q1/Q2 elements, bit for bit),
/// Newton's method on `P_n` beyond.
///
/// # Math
/// ```text
/// P_n(x_i) = 0,   w_i = 2 / ((1 - x_i^2) P_n'(x_i)^2),   P_n' = n (x P_n - P_(n-1)) / (x^2 - 1)
/// ```
///
/// # Panics
/// If `n == 0`.
#[track_caller]
pub fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    assert!(n >= 1, "gauss_legendre: no rule with 0 points");
    if n <= 5 {
        return gauss_rule(n);
    }
    let nf = n as f64;
    let mut x = vec![0.0; n];
    let mut w = vec![0.0; n];
    for i in 0..n.div_ceil(2) {
        let mut z = (core::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (pm, pn) = legendre_pair(n, z);
            dp = nf * (z * pn - pm) / (z * z - 1.0);
            let dz = pn / dp;
            z -= dz;
            if dz.abs() < 1e-16 {
                break;
            }
        }
        let (pm, pn) = legendre_pair(n, z);
        dp = if (z * z - 1.0).abs() > 0.0 {
            nf * (z * pn - pm) / (z * z - 1.0)
        } else {
            dp
        };
        let wi = 2.0 / ((1.0 - z * z) * dp * dp);
        x[i] = -z;
        x[n - 1 - i] = z;
        w[i] = wi;
        w[n - 1 - i] = wi;
    }
    if n % 2 == 1 {
        x[n / 2] = 0.0;
    }
    (x, w)
}

/// The Lagrange basis through `nodes` and its derivative at `s`: `(l_j(s), l_j'(s))`.
///
/// # Math
/// ```text
/// l_j(s)  = prod_(k != j) (s - x_k) / (x_j - x_k)
/// l_j'(s) = sum_(m != j) 1 / (x_j - x_m) prod_(k != j, m) (s - x_k) / (x_j - x_k)
/// ```
/// (the product form, well defined at the nodes themselves; `O(n^3)` per point, `n <= 11`).
pub fn lagrange_basis(nodes: &[f64], s: f64) -> (Vec<f64>, Vec<f64>) {
    let n = nodes.len();
    let mut value = vec![0.0; n];
    let mut derivative = vec![0.0; n];
    for j in 0..n {
        let xj = nodes[j];
        let mut v = 1.0;
        for (k, &xk) in nodes.iter().enumerate() {
            if k != j {
                v *= (s - xk) / (xj - xk);
            }
        }
        value[j] = v;
        let mut d = 0.0;
        for (m, &xm) in nodes.iter().enumerate() {
            if m == j {
                continue;
            }
            let mut t = 1.0 / (xj - xm);
            for (k, &xk) in nodes.iter().enumerate() {
                if k != j && k != m {
                    t *= (s - xk) / (xj - xk);
                }
            }
            d += t;
        }
        derivative[j] = d;
    }
    (value, derivative)
}

/// Tables of the Lagrange basis through `nodes` at the points `at`: `(B, D)` with
/// `B[j][q] = l_j(at_q)`, `D[j][q] = l_j'(at_q)` (row `j` a basis function, column `q` a point).
pub fn basis_tables(nodes: &[f64], at: &[f64]) -> (Vec<Vec<f64>>, Vec<Vec<f64>>) {
    let n = nodes.len();
    let mut b = vec![vec![0.0; at.len()]; n];
    let mut d = vec![vec![0.0; at.len()]; n];
    for (q, &s) in at.iter().enumerate() {
        let (v, dv) = lagrange_basis(nodes, s);
        for j in 0..n {
            b[j][q] = v[j];
            d[j][q] = dv[j];
        }
    }
    (b, d)
}

/// The elements of degree `p` along one direction of `count` elements that contain node
/// line `i` (node lines `p e ... p e + p` belong to element `e`): `(element, local index)` —
/// one element inside, two at a shared element boundary (one at an end of a bounded line;
/// periodic lines wrap).
pub fn elements_along(p: usize, i: usize, count: usize, periodic: bool) -> Vec<(usize, usize)> {
    if !i.is_multiple_of(p) {
        return vec![(i / p, i % p)];
    }
    let mut out = Vec::with_capacity(2);
    if periodic {
        out.push(((i / p) % count, 0));
        out.push(((i / p + count - 1) % count, p));
    } else {
        if i / p < count {
            out.push((i / p, 0));
        }
        if i > 0 {
            out.push((i / p - 1, p));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn monomial_integral(deg: usize) -> f64 {
        if deg % 2 == 1 {
            0.0
        } else {
            2.0 / (deg as f64 + 1.0)
        }
    }

    #[test]
    fn gll_rule_is_exact_for_degree_2p_minus_1_and_not_2p() {
        for p in 1..=10 {
            let (x, w) = gll_rule(p);
            assert!(x.windows(2).all(|s| s[0] < s[1]), "p {p}: increasing nodes");
            for deg in 0..2 * p {
                let q: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(deg as i32)).sum();
                // round-off of the Newton nodes and the sum
                assert!(
                    (q - monomial_integral(deg)).abs() < 1e-14,
                    "p {p} degree {deg}: {q}"
                );
            }
            // degree 2p is not integrated exactly (the rule has p + 1 points with fixed ends)
            let q: f64 = x
                .iter()
                .zip(&w)
                .map(|(x, w)| w * x.powi(2 * p as i32))
                .sum();
            assert!((q - monomial_integral(2 * p)).abs() > 1e-10, "p {p}");
        }
    }

    #[test]
    fn gauss_legendre_is_exact_for_degree_2n_minus_1() {
        for n in 1..=14 {
            let (x, w) = gauss_legendre(n);
            for deg in 0..2 * n {
                let q: f64 = x.iter().zip(&w).map(|(x, w)| w * x.powi(deg as i32)).sum();
                assert!(
                    (q - monomial_integral(deg)).abs() < 1e-14,
                    "n {n} degree {deg}: {q}"
                );
            }
        }
    }

    #[test]
    fn derivative_matrix_differentiates_polynomials_of_degree_p_exactly() {
        for p in 1..=10 {
            let (x, _) = gll_rule(p);
            let at = [-0.93, -0.31, 0.0, 0.47, 0.999];
            let (b, d) = basis_tables(&x, &at);
            for deg in 0..=p {
                let f = |s: f64| (s + 0.3).powi(deg as i32);
                let df = |s: f64| {
                    if deg == 0 {
                        0.0
                    } else {
                        deg as f64 * (s + 0.3).powi(deg as i32 - 1)
                    }
                };
                for (q, &s) in at.iter().enumerate() {
                    let value: f64 = (0..=p).map(|j| b[j][q] * f(x[j])).sum();
                    let slope: f64 = (0..=p).map(|j| d[j][q] * f(x[j])).sum();
                    // conditioning of the GLL Lagrange basis: round-off times a small constant
                    assert!((value - f(s)).abs() < 1e-12, "p {p} deg {deg} at {s}");
                    assert!(
                        (slope - df(s)).abs() < 1e-11,
                        "p {p} deg {deg} at {s}: {slope}"
                    );
                }
            }
            // at the nodes themselves: the derivative matrix D_ij = l_j'(x_i)
            let (_, dn) = basis_tables(&x, &x);
            for i in 0..=p {
                let slope: f64 = (0..=p).map(|j| dn[j][i] * x[j].powi(p as i32)).sum();
                let exact = p as f64 * x[i].powi(p as i32 - 1);
                assert!((slope - exact).abs() < 1e-11, "p {p} node {i}");
            }
        }
    }

    #[test]
    fn gll_nodes_of_degree_two_are_the_q2_nodes() {
        let (x, w) = gll_rule(2);
        assert_eq!(x, vec![-1.0, 0.0, 1.0]);
        for (wi, e) in w.iter().zip([1.0 / 3.0, 4.0 / 3.0, 1.0 / 3.0]) {
            assert!((wi - e).abs() < 1e-15);
        }
    }
}
