//! The pointwise stress kernel and the sum-factorised element action of the matrix-free
//! 3-D operator.

use capstan_geometry::ShellPoint;

use super::lanes::{Lane, Lanes};

/// Numbers stored per quadrature point: `s = sqrt(g) w det`, `g_ij` and `g^ij` (upper
/// triangles: `00, 01, 02, 11, 12, 22`) and `Gamma^n_im` (`n` outer, `(i, m)` upper triangle).
pub(super) const GEOMETRY: usize = 31;

/// `(i, j)` to the upper-triangle slot of a symmetric 3 x 3 matrix.
const SYM: [[usize; 3]; 3] = [[0, 1, 2], [1, 3, 4], [2, 4, 5]];

/// Packs the chart at one quadrature point (weight `weight`, including the element's
/// Jacobian determinant) into [`GEOMETRY`] numbers.
pub(super) fn pack(p: &ShellPoint<f64>, weight: f64, out: &mut [f64]) {
    out[0] = p.sqrt_g * weight;
    let upper = [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)];
    for (s, &(i, j)) in upper.iter().enumerate() {
        out[1 + s] = p.metric[i][j];
        out[7 + s] = p.inverse_metric[i][j];
        for n in 0..3 {
            out[13 + 6 * n + s] = p.christoffel[n][i][j];
        }
    }
}

/// The pointwise operator: for the values `v^m` and derivatives `d[i][n] = d_i v^n` of the
/// trial field at one point, the coefficients of the test inputs `w^m` (`out_v`) and
/// `d_i w^n` (`out_d[i][n]`) in the integrand `sqrt(g) w T^i_n(v) nabla_i w^n`.
///
/// # Math
/// ```text
/// N[i][n] = d_i v^n + Gamma^n_im v^m                 (nabla_i v^n)
/// E[i][l] = (N[i][n] g_nl + N[l][n] g_ni) / 2        (covariant strain)
/// M[i][l] = g^ij E[j][l]                             (mixed strain)
/// T[i][n] = s (lambda tr(M) delta_in + 2 mu M[i][n])
/// out_d[i][n] = T[i][n],   out_v[m] = T[i][n] Gamma^n_im
/// ```
/// so that `out . (w inputs) = u^T K w` with `K` the energy matrix of
/// [`crate::continuum::energy_matrix`] (`tr(M_u M_w) = M_u[j][n] nabla_j w^n`, `tr M_w =
/// nabla_j w^j`, for symmetric `g`).
#[allow(clippy::needless_range_loop)] // index loops mirror the tensor formulas
#[inline(always)]
pub(super) fn stress<T: Lane>(
    geo: &[T],
    lambda: f64,
    two_mu: f64,
    v: [T; 3],
    d: [[T; 3]; 3],
) -> ([T; 3], [[T; 3]; 3]) {
    let s = geo[0];
    let g = |i: usize, j: usize| geo[1 + SYM[i][j]];
    let gi = |i: usize, j: usize| geo[7 + SYM[i][j]];
    let gamma = |n: usize, i: usize, m: usize| geo[13 + 6 * n + SYM[i][m]];
    let zero = T::default();
    let mut nab = d;
    for i in 0..3 {
        for n in 0..3 {
            nab[i][n] += gamma(n, i, 0) * v[0] + gamma(n, i, 1) * v[1] + gamma(n, i, 2) * v[2];
        }
    }
    let mut h = [[zero; 3]; 3];
    for i in 0..3 {
        for l in 0..3 {
            h[i][l] = nab[i][0] * g(0, l) + nab[i][1] * g(1, l) + nab[i][2] * g(2, l);
        }
    }
    let mut e = [[zero; 3]; 3];
    for i in 0..3 {
        for l in 0..3 {
            e[i][l] = (h[i][l] + h[l][i]) * 0.5;
        }
    }
    let mut m = [[zero; 3]; 3];
    for i in 0..3 {
        for l in 0..3 {
            m[i][l] = gi(i, 0) * e[0][l] + gi(i, 1) * e[1][l] + gi(i, 2) * e[2][l];
        }
    }
    let tr = m[0][0] + m[1][1] + m[2][2];
    let mut t = [[zero; 3]; 3];
    for i in 0..3 {
        for n in 0..3 {
            t[i][n] = s * (m[i][n] * two_mu + if i == n { tr * lambda } else { zero });
        }
    }
    let mut out_v = [zero; 3];
    for (mm, o) in out_v.iter_mut().enumerate() {
        let mut acc = zero;
        for i in 0..3 {
            for n in 0..3 {
                acc += t[i][n] * gamma(n, i, mm);
            }
        }
        *o = acc;
    }
    (out_v, t)
}

/// `y (+)= M x` along `axis` of the row-major array `x` of dimensions `dims`: `M` is
/// `rows x dims[axis]` (row-major), `y` has `dims` with `dims[axis] = rows`. Always inlined:
/// with constant `rows` and `dims` (the Q1 and Q2 kernels) the loops unroll.
#[inline(always)]
pub(super) fn along<T: Lane>(
    m: &[f64],
    rows: usize,
    x: &[T],
    dims: [usize; 3],
    axis: usize,
    y: &mut [T],
    add: bool,
) {
    let k = dims[axis];
    let (outer, inner) = match axis {
        0 => (1, dims[1] * dims[2]),
        1 => (dims[0], dims[2]),
        _ => (dims[0] * dims[1], 1),
    };
    for o in 0..outer {
        for i in 0..rows {
            let mi = &m[i * k..(i + 1) * k];
            for r in 0..inner {
                let mut s = T::default();
                for (j, &mij) in mi.iter().enumerate() {
                    s += x[(o * k + j) * inner + r] * mij;
                }
                let at = &mut y[(o * rows + i) * inner + r];
                if add {
                    *at += s;
                } else {
                    *at = s;
                }
            }
        }
    }
}

/// The 1-D tables of the sum factorisation: basis values `B[q][a]` and reference
/// derivatives `D[q][a]` at the Gauss points, and their transposes.
#[derive(Debug, Clone)]
pub(super) struct Tables {
    /// Nodes per element direction.
    pub(super) np: usize,
    /// Gauss points per direction.
    pub(super) nq: usize,
    b: Vec<f64>,
    d: Vec<f64>,
    bt: Vec<f64>,
    dt: Vec<f64>,
    /// `2 / L_p`: reference to parameter derivative per direction.
    scale: [f64; 3],
    /// The CPU has AVX2: the batched kernels run compiled for it (4 lanes a register).
    avx2: bool,
}

/// Work arrays of one element application.
#[derive(Debug, Clone, Default)]
pub(super) struct Scratch {
    t0: Vec<f64>,
    t1: Vec<f64>,
    s00: Vec<f64>,
    s10: Vec<f64>,
    s01: Vec<f64>,
    /// `[v, d_1 v, d_2 v, d_3 v]` per component at the points (`4 * 3` arrays of `nq^3`).
    fields: Vec<f64>,
}

impl Tables {
    /// The tables of `shape_1d` (basis and derivative at a reference abscissa) at the Gauss
    /// points `gauss`, for elements of lengths `lengths`.
    pub(super) fn new(
        np: usize,
        gauss: &[f64],
        shape_1d: impl Fn(f64) -> (Vec<f64>, Vec<f64>),
        lengths: [f64; 3],
    ) -> Self {
        let nq = gauss.len();
        let mut b = vec![0.0; nq * np];
        let mut d = vec![0.0; nq * np];
        for (q, &xi) in gauss.iter().enumerate() {
            let (n, dn) = shape_1d(xi);
            b[q * np..(q + 1) * np].copy_from_slice(&n[..np]);
            d[q * np..(q + 1) * np].copy_from_slice(&dn[..np]);
        }
        let transpose = |m: &[f64]| {
            let mut t = vec![0.0; nq * np];
            for q in 0..nq {
                for a in 0..np {
                    t[a * nq + q] = m[q * np + a];
                }
            }
            t
        };
        Self {
            np,
            nq,
            bt: transpose(&b),
            dt: transpose(&d),
            b,
            d,
            scale: lengths.map(|l| 2.0 / l),
            #[cfg(target_arch = "x86_64")]
            avx2: std::arch::is_x86_feature_detected!("avx2"),
            #[cfg(not(target_arch = "x86_64"))]
            avx2: false,
        }
    }

    /// Work arrays sized for these tables.
    pub(super) fn scratch(&self) -> Scratch {
        let (np, nq) = (self.np, self.nq);
        let big = np.max(nq).pow(3);
        Scratch {
            t0: vec![0.0; big],
            t1: vec![0.0; big],
            s00: vec![0.0; big],
            s10: vec![0.0; big],
            s01: vec![0.0; big],
            fields: vec![0.0; 12 * nq.pow(3)],
        }
    }

    /// `y = sum_q B_q^T K_q B_q u` for a batch of [`super::lanes::LANES`] elements of `NP` nodes and `NQ`
    /// points per direction known at compile time (`NN = NP^3`, `QQ = NQ^3`,
    /// `NP * NQ <= 9`: Q1 and Q2), one element per lane: `u` and `y` as in
    /// [`Tables::element`], `geo` the points' [`GEOMETRY`] numbers (point outer). The same
    /// contractions and pointwise kernel as [`Tables::element`], lane by lane, with the
    /// tables and work arrays on the stack.
    pub(super) fn element_batch<
        const NP: usize,
        const NQ: usize,
        const NN: usize,
        const QQ: usize,
    >(
        &self,
        geo: &[Lanes],
        lambda: f64,
        two_mu: f64,
        u: &[Lanes],
        y: &mut [Lanes],
    ) {
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: `avx2` is set only when the CPU reports AVX2 (`Tables::new`).
            unsafe { self.batch_avx2::<NP, NQ, NN, QQ>(geo, lambda, two_mu, u, y) };
            return;
        }
        self.batch::<NP, NQ, NN, QQ>(geo, lambda, two_mu, u, y);
    }

    /// [`Tables::batch`] compiled for AVX2 (the same operations, wider registers).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn batch_avx2<const NP: usize, const NQ: usize, const NN: usize, const QQ: usize>(
        &self,
        geo: &[Lanes],
        lambda: f64,
        two_mu: f64,
        u: &[Lanes],
        y: &mut [Lanes],
    ) {
        self.batch::<NP, NQ, NN, QQ>(geo, lambda, two_mu, u, y);
    }

    /// The body of [`Tables::element_batch`].
    #[inline(always)]
    fn batch<const NP: usize, const NQ: usize, const NN: usize, const QQ: usize>(
        &self,
        geo: &[Lanes],
        lambda: f64,
        two_mu: f64,
        u: &[Lanes],
        y: &mut [Lanes],
    ) {
        const MAX: usize = 27;
        debug_assert!(NN == NP * NP * NP && QQ == NQ * NQ * NQ && NP * NQ <= 9);
        debug_assert!(self.np == NP && self.nq == NQ);
        let geo = &geo[..QQ * GEOMETRY];
        let u = &u[..3 * NN];
        let y = &mut y[..3 * NN];
        let mut b = [0.0; 9];
        let mut d = [0.0; 9];
        let mut bt = [0.0; 9];
        let mut dt = [0.0; 9];
        b[..NP * NQ].copy_from_slice(&self.b[..NP * NQ]);
        d[..NP * NQ].copy_from_slice(&self.d[..NP * NQ]);
        bt[..NP * NQ].copy_from_slice(&self.bt[..NP * NQ]);
        dt[..NP * NQ].copy_from_slice(&self.dt[..NP * NQ]);
        let (b, d, bt, dt) = (&b[..NP * NQ], &d[..NP * NQ], &bt[..NP * NQ], &dt[..NP * NQ]);
        // intermediate arrays have at most NP NQ^2 <= MAX entries
        let zero = Lanes::default();
        let mut t0 = [zero; MAX];
        let mut t1 = [zero; MAX];
        let mut s00 = [zero; MAX];
        let mut s10 = [zero; MAX];
        let mut s01 = [zero; MAX];
        // [v, d_1 v, d_2 v, d_3 v] of each component at the points
        let mut fields = [[zero; QQ]; 12];
        let (pn, qn) = ([NP, NP, NP], [NQ, NQ, NQ]);
        for c in 0..3 {
            let uc = &u[c * NN..(c + 1) * NN];
            along(b, NQ, uc, pn, 2, &mut t0, false);
            along(d, NQ, uc, pn, 2, &mut t1, false);
            along(b, NQ, &t0, [NP, NP, NQ], 1, &mut s00, false);
            along(d, NQ, &t0, [NP, NP, NQ], 1, &mut s10, false);
            along(b, NQ, &t1, [NP, NP, NQ], 1, &mut s01, false);
            let [val, g1, g2, g3] = &mut fields[4 * c..4 * c + 4] else {
                unreachable!("four fields per component")
            };
            along(b, NQ, &s00, [NP, NQ, NQ], 0, val, false);
            along(d, NQ, &s00, [NP, NQ, NQ], 0, g1, false);
            along(b, NQ, &s10, [NP, NQ, NQ], 0, g2, false);
            along(b, NQ, &s01, [NP, NQ, NQ], 0, g3, false);
        }
        let sc = self.scale;
        for q in 0..QQ {
            let v = [fields[0][q], fields[4][q], fields[8][q]];
            let dv: [[Lanes; 3]; 3] = core::array::from_fn(|i| {
                core::array::from_fn(|n| fields[4 * n + 1 + i][q] * sc[i])
            });
            let (ov, od) = stress(
                &geo[q * GEOMETRY..(q + 1) * GEOMETRY],
                lambda,
                two_mu,
                v,
                dv,
            );
            for c in 0..3 {
                fields[4 * c][q] = ov[c];
                for i in 0..3 {
                    fields[4 * c + 1 + i][q] = od[i][c] * sc[i];
                }
            }
        }
        for c in 0..3 {
            let [val, g1, g2, g3] = &fields[4 * c..4 * c + 4] else {
                unreachable!("four fields per component")
            };
            along(bt, NP, val, qn, 0, &mut s00, false);
            along(dt, NP, g1, qn, 0, &mut s00, true);
            along(bt, NP, g2, qn, 0, &mut s10, false);
            along(bt, NP, g3, qn, 0, &mut s01, false);
            along(bt, NP, &s00, [NP, NQ, NQ], 1, &mut t0, false);
            along(dt, NP, &s10, [NP, NQ, NQ], 1, &mut t0, true);
            along(bt, NP, &s01, [NP, NQ, NQ], 1, &mut t1, false);
            let yc = &mut y[c * NN..(c + 1) * NN];
            along(bt, NP, &t0, [NP, NP, NQ], 2, yc, false);
            along(dt, NP, &t1, [NP, NP, NQ], 2, yc, true);
        }
    }

    /// `y = sum_q B_q^T K_q B_q u` for one element of any order: `u` the local values (`3`
    /// components of `np^3`, component outer), `geo` its points' [`GEOMETRY`] numbers, `y`
    /// the local result (same layout), work arrays in `w`.
    pub(super) fn element(
        &self,
        geo: &[f64],
        lambda: f64,
        two_mu: f64,
        u: &[f64],
        y: &mut [f64],
        w: &mut Scratch,
    ) {
        let (np, nq) = (self.np, self.nq);
        let (nn, qq) = (np * np * np, nq * nq * nq);
        let (b, d) = (&self.b[..], &self.d[..]);
        let Scratch {
            t0,
            t1,
            s00,
            s10,
            s01,
            fields,
        } = w;
        // values and parameter derivatives of every component at the points
        for c in 0..3 {
            let uc = &u[c * nn..(c + 1) * nn];
            along(b, nq, uc, [np, np, np], 2, t0, false);
            along(d, nq, uc, [np, np, np], 2, t1, false);
            along(b, nq, t0, [np, np, nq], 1, s00, false);
            along(d, nq, t0, [np, np, nq], 1, s10, false);
            along(b, nq, t1, [np, np, nq], 1, s01, false);
            let f = &mut fields[4 * c * qq..4 * (c + 1) * qq];
            let (val, rest) = f.split_at_mut(qq);
            let (g1, rest) = rest.split_at_mut(qq);
            let (g2, g3) = rest.split_at_mut(qq);
            along(b, nq, s00, [np, nq, nq], 0, val, false);
            along(d, nq, s00, [np, nq, nq], 0, g1, false);
            along(b, nq, s10, [np, nq, nq], 0, g2, false);
            along(b, nq, s01, [np, nq, nq], 0, g3, false);
        }
        // the pointwise stress, written back in place as the test coefficients
        let sc = self.scale;
        for q in 0..qq {
            let at = |c: usize, k: usize| fields[(4 * c + k) * qq + q];
            let v = [at(0, 0), at(1, 0), at(2, 0)];
            let dv: [[f64; 3]; 3] =
                core::array::from_fn(|i| core::array::from_fn(|n| at(n, 1 + i) * sc[i]));
            let (ov, od) = stress(
                &geo[q * GEOMETRY..(q + 1) * GEOMETRY],
                lambda,
                two_mu,
                v,
                dv,
            );
            for c in 0..3 {
                fields[4 * c * qq + q] = ov[c];
                for i in 0..3 {
                    fields[(4 * c + 1 + i) * qq + q] = od[i][c] * sc[i];
                }
            }
        }
        // the transposed contractions
        let (bt, dt) = (&self.bt[..], &self.dt[..]);
        for c in 0..3 {
            let f = &fields[4 * c * qq..4 * (c + 1) * qq];
            let (val, g1, g2, g3) = (&f[..qq], &f[qq..2 * qq], &f[2 * qq..3 * qq], &f[3 * qq..]);
            along(bt, np, val, [nq, nq, nq], 0, s00, false);
            along(dt, np, g1, [nq, nq, nq], 0, s00, true);
            along(bt, np, g2, [nq, nq, nq], 0, s10, false);
            along(bt, np, g3, [nq, nq, nq], 0, s01, false);
            along(bt, np, s00, [np, nq, nq], 1, t0, false);
            along(dt, np, s10, [np, nq, nq], 1, t0, true);
            along(bt, np, s01, [np, nq, nq], 1, t1, false);
            let yc = &mut y[c * nn..(c + 1) * nn];
            along(bt, np, t0, [np, np, nq], 2, yc, false);
            along(dt, np, t1, [np, np, nq], 2, yc, true);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn along_contracts_each_axis() {
        // x[i][j][k] = i + 10 j + 100 k on 2 x 3 x 2; M = [1, 1, ...] sums the axis
        let dims = [2, 3, 2];
        let x: Vec<f64> = (0..12)
            .map(|n| {
                let (i, j, k) = (n / 6, (n / 2) % 3, n % 2);
                (i + 10 * j + 100 * k) as f64
            })
            .collect();
        let mut y = vec![0.0; 12];
        along(&[1.0, 1.0, 1.0], 1, &x, dims, 1, &mut y, false);
        // y[i][0][k] = 3 i + 30 + 300 k
        assert_eq!(&y[..4], &[30.0, 330.0, 33.0, 333.0]);
        along(&[1.0, -1.0], 1, &x, dims, 0, &mut y, false);
        assert!(y[..6].iter().all(|&v| v == -1.0));
        along(&[2.0, 0.0], 1, &x, dims, 2, &mut y, false);
        assert_eq!(&y[..3], &[0.0, 20.0, 40.0]);
    }
}
