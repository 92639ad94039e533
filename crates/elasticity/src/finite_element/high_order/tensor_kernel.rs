//! The sum-factorised element stiffness as dense matrix products: the `x2` contraction of
//! the pointwise energy matrices by hand (`T`), the `x3` contraction as GEMMs against a table
//! `P` shared by every element of one size (faer's SIMD kernels), in the "tensor form" from
//! which the condensation gathers its blocks directly.

use faer::{Accum, MatMut, MatRef, Par};

use capstan_solvers::{CondensationScratch, CondensedBlock};
use rayon::prelude::*;

use super::kernel::ElementTables;
use crate::error::ElasticityError;

/// The component pairs `(c, d)` computed; `(1, 0)` is the transpose of `(0, 1)`.
const PAIRS: [(usize, usize); 3] = [(0, 0), (0, 1), (1, 1)];

/// The `x3` half of the kernel, the same for every element of one size:
/// `P[(ab, q3), (a3, b3)] = Y_alpha(a3, q3) Y_beta(b3, q3)`, `ab = 2 alpha + beta`,
/// `Y_0 = l_a`, `Y_1 = (2 / L3) l_a'` (column-major, `4 nq` rows, `n^2` columns).
#[derive(Debug, Clone, PartialEq)]
pub struct X3Factors {
    n: usize,
    nq: usize,
    p: Vec<f64>,
    /// `l_a(xi_q)`, `(2 / L2) l_a'(xi_q)`, index `q n + a` (transposed tables of the `x2` half).
    value_t: Vec<f64>,
    d2_t: Vec<f64>,
}

impl X3Factors {
    /// The factors of `t`.
    pub fn new(t: &ElementTables) -> Self {
        let (n, nq) = (t.n, t.nq);
        let y = [&t.value, &t.d3];
        let rows = 4 * nq;
        let mut p = vec![0.0; rows * n * n];
        for a3 in 0..n {
            for b3 in 0..n {
                let col = &mut p[(a3 * n + b3) * rows..][..rows];
                for alpha in 0..2 {
                    for beta in 0..2 {
                        for q3 in 0..nq {
                            col[(2 * alpha + beta) * nq + q3] =
                                y[alpha][a3 * nq + q3] * y[beta][b3 * nq + q3];
                        }
                    }
                }
            }
        }
        let transpose =
            |s: &[f64]| -> Vec<f64> { (0..nq * n).map(|k| s[(k % n) * nq + k / n]).collect() };
        Self {
            n,
            nq,
            p,
            value_t: transpose(&t.value),
            d2_t: transpose(&t.d2),
        }
    }

    /// Rows of the tensor form, `3 n^2`.
    pub fn rows(&self) -> usize {
        3 * self.n * self.n
    }

    /// Columns of the tensor form, `n^2`.
    pub fn cols(&self) -> usize {
        self.n * self.n
    }

    /// Length of the scratch: `T`, `3 n^2 4 nq`, and `w`, `2 n`.
    pub fn scratch_len(&self) -> usize {
        self.rows() * 4 * self.nq + 2 * self.n
    }

    /// Adds the element matrix of the pointwise energy matrices `kq` (index `q2 nq + q3`, as
    /// for [`super::kernel::add_element_matrix`]) to `out` in tensor form
    /// (column-major, [`Self::rows`] x [`Self::cols`]); `tt` is scratch of
    /// [`Self::scratch_len`].
    ///
    /// # Math
    /// With `X_t = B, D2, B` and `Y_t = B, B, D3` for the inputs `t = 0, 1, 2` (value, `d_2`,
    /// `d_3`) and `alpha(t) = [t = 2]`,
    /// ```text
    /// w_(t,beta)(b2) = sum_(s: alpha(s) = beta) Kq[2t+c][2s+d] X_s(b2, q2)
    /// T[(cd, a2, b2), (ab, q3)] = sum_q2 sum_t X_t(a2, q2) w_(t,beta)(b2),  ab = 2 alpha(t) + beta
    /// M[(cd, a2, b2), (a3, b3)] = sum_(ab, q3) T[(cd, a2, b2), (ab, q3)] P[(ab, q3), (a3, b3)]
    /// K[(a2 a3 c), (b2 b3 d)] = M[(cd, a2, b2), (a3, b3)]
    /// ```
    /// for `cd` in `(0,0), (0,1), (1,1)` ([`TensorIndex`] reads `(1,0)` by transposition):
    /// `(27 + 18 n) n nq^2` multiply-adds by hand and four `3 n^2 x nq x n^2` GEMMs, one per
    /// `ab` and added in turn (as the reference kernel sums: one GEMM over all `4 nq` columns
    /// raised the round-off floor of the Lamé study at `p = 5` from 8e-12 to 1e-11).
    pub fn add_tensor_matrix(&self, kq: &[[[f64; 6]; 6]], tt: &mut [f64], out: MatMut<'_, f64>) {
        let (n, nq, rows) = (self.n, self.nq, self.rows());
        debug_assert_eq!(kq.len(), nq * nq);
        debug_assert_eq!(tt.len(), self.scratch_len());
        let (tt, w) = tt.split_at_mut(rows * 4 * nq);
        let (w0, w1) = w.split_at_mut(n);
        tt.fill(0.0);
        for q2 in 0..nq {
            let x = [
                &self.value_t[q2 * n..][..n],
                &self.d2_t[q2 * n..][..n],
                &self.value_t[q2 * n..][..n],
            ];
            for q3 in 0..nq {
                let k = &kq[q2 * nq + q3];
                for (cd, &(c, d)) in PAIRS.iter().enumerate() {
                    for (ti, xt) in x.iter().enumerate() {
                        let coef = |si: usize| k[2 * ti + c][2 * si + d];
                        let (c0, c1, c2) = (coef(0), coef(1), coef(2));
                        for b2 in 0..n {
                            w0[b2] = c0 * x[0][b2] + c1 * x[1][b2];
                            w1[b2] = c2 * x[2][b2];
                        }
                        let alpha = usize::from(ti == 2);
                        for (beta, wb) in [&*w0, &*w1].into_iter().enumerate() {
                            let col = (2 * alpha + beta) * nq + q3;
                            let dst = &mut tt[col * rows + cd * n * n..][..n * n];
                            for (a2, row) in dst.chunks_exact_mut(n).enumerate() {
                                let xa = xt[a2];
                                for (r, wv) in row.iter_mut().zip(wb) {
                                    *r += xa * wv;
                                }
                            }
                        }
                    }
                }
            }
        }
        let t = MatRef::from_column_major_slice(&*tt, rows, 4 * nq);
        let p = MatRef::from_column_major_slice(&self.p, 4 * nq, n * n);
        let mut out = out;
        for ab in 0..4 {
            faer::linalg::matmul::matmul(
                out.as_mut(),
                Accum::Add,
                t.subcols(ab * nq, nq),
                p.subrows(ab * nq, nq),
                1.0,
                Par::Seq,
            );
        }
    }
}

/// Where local dof `2 (a2 n + a3) + c` of an element with `n` nodes per direction sits in the
/// tensor form `M` ([`X3Factors::add_tensor_matrix`], column-major `3 n^2 x n^2`).
///
/// # Math
/// `K[i, j] = M[(c_i + c_j) n^2 + a2_i n + a2_j, a3_i n + a3_j]` for `c_i <= c_j`, at the flat
/// index `row(i) + col(j)` with `row = a3 n 3n^2 + c n^2 + a2 n`, `col = a3 3n^2 + c n^2 + a2`;
/// for `c_i > c_j` the symmetric entry `K[j, i]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TensorIndex {
    c: usize,
    row: usize,
    col: usize,
}

impl TensorIndex {
    /// The index parts of local dof `dof`.
    pub fn new(dof: usize, n: usize) -> Self {
        let (c, a2, a3) = (dof % 2, dof / 2 / n, dof / 2 % n);
        let rows = 3 * n * n;
        Self {
            c,
            row: a3 * n * rows + c * n * n + a2 * n,
            col: a3 * rows + c * n * n + a2,
        }
    }

    /// `K[i, j]` from the tensor form `m`.
    #[inline]
    pub fn entry(m: &[f64], i: Self, j: Self) -> f64 {
        if i.c <= j.c {
            m[i.row + j.col]
        } else {
            m[j.row + i.col]
        }
    }
}

/// The static condensation of every element's interior (in parallel, one scratch per worker):
/// element `e`'s matrix in tensor form from `matrix(e, scratch, m)` (`m` of `matrix_len`
/// entries, overwritten), its local dofs split into `boundary` and `interior`, its interior
/// load from the global `load` (two components per node) at its nodes `nodes(e)`; see
/// [`CondensedBlock`].
///
/// # Errors
/// [`ElasticityError::Solver`] if an interior block is not positive definite.
pub(crate) fn condense_elements<N>(
    count: usize,
    n: usize,
    matrix_len: usize,
    (boundary, interior): (&[usize], &[usize]),
    matrix: impl Fn(usize, &mut Vec<f64>, &mut [f64]) + Sync,
    (load, nodes): (&[f64], impl Fn(usize) -> N + Sync),
) -> Result<Vec<CondensedBlock>, ElasticityError>
where
    N: AsRef<[usize]>,
{
    let dofs: Vec<TensorIndex> = (0..2 * n * n).map(|d| TensorIndex::new(d, n)).collect();
    (0..count)
        .into_par_iter()
        .map_init(
            || {
                let m = vec![0.0; matrix_len];
                (vec![], m, CondensationScratch::new(interior.len()))
            },
            |(tt, m, scratch), e| {
                matrix(e, tt, m);
                let nodes = nodes(e);
                let nodes = nodes.as_ref();
                let f: Vec<f64> = interior
                    .iter()
                    .map(|&d| load[2 * nodes[d / 2] + d % 2])
                    .collect();
                CondensedBlock::from_entries(
                    |i, j| TensorIndex::entry(m, dofs[i], dofs[j]),
                    boundary,
                    interior,
                    &f,
                    scratch,
                )
                .map_err(ElasticityError::from)
            },
        )
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::finite_element::high_order::gll::{gauss_legendre, gll_rule};
    use crate::finite_element::high_order::kernel::add_element_matrix;
    use crate::finite_element::high_order::kernel::tests::sample_point_matrices;

    #[test]
    fn tensor_form_equals_the_reference_kernel() {
        for p in [1, 2, 4, 6, 8] {
            for nq in [p, p + 1] {
                let (x, _) = gll_rule(p);
                let (g, _) = gauss_legendre(nq);
                let t = ElementTables::new(&x, &g, [0.3, 0.7]);
                let kq = sample_point_matrices(nq * nq);
                let l = 2 * (p + 1) * (p + 1);
                let mut reference = vec![0.0; l * l];
                add_element_matrix(&t, &kq, &mut reference);
                let f = X3Factors::new(&t);
                let mut tt = vec![0.0; f.scratch_len()];
                let mut m = vec![0.0; f.rows() * f.cols()];
                let out = MatMut::from_column_major_slice_mut(&mut m, f.rows(), f.cols());
                f.add_tensor_matrix(&kq, &mut tt, out);
                let dofs: Vec<TensorIndex> = (0..l).map(|d| TensorIndex::new(d, p + 1)).collect();
                let scale = reference.iter().fold(0.0f64, |s, x| s.max(x.abs()));
                for r in 0..l {
                    for c in 0..l {
                        let a = TensorIndex::entry(&m, dofs[r], dofs[c]);
                        let b = reference[r * l + c];
                        // summation order only
                        assert!((a - b).abs() < 1e-13 * scale, "p {p} nq {nq} ({r},{c})");
                    }
                }
            }
        }
    }
}
