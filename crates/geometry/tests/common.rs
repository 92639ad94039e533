//! Shared helpers for the geometry tests.
#![allow(clippy::needless_range_loop)] // tensor index loops mirror the formulas
#![allow(dead_code)]

use capstan_geometry::{ShellChart, Surface};

/// `Gamma^k_ij = 1/2 g^kl (d_i g_jl + d_j g_il - d_l g_ij)` with the metric's derivatives taken
/// by fourth-order central differences of `g_ij` at neighbouring points (independent of the
/// chart's own Christoffel formula, which uses second derivatives of the normal).
pub fn christoffel_from_metric<S: Surface<f64>>(
    chart: &ShellChart<S>,
    x: [f64; 3],
    h: f64,
) -> [[[f64; 3]; 3]; 3] {
    let metric = |y: [f64; 3]| chart.point(y).unwrap().metric;
    let mut dg = [[[0.0; 3]; 3]; 3]; // dg[l][i][j] = d_l g_ij
    for (l, dgl) in dg.iter_mut().enumerate() {
        let at = |s: f64| {
            let mut y = x;
            y[l] += s * h;
            metric(y)
        };
        let (p2, p1, m1, m2) = (at(2.0), at(1.0), at(-1.0), at(-2.0));
        for i in 0..3 {
            for j in 0..3 {
                dgl[i][j] = (-p2[i][j] + 8.0 * p1[i][j] - 8.0 * m1[i][j] + m2[i][j]) / (12.0 * h);
            }
        }
    }
    let ginv = chart.point(x).unwrap().inverse_metric;
    let mut gamma = [[[0.0; 3]; 3]; 3];
    for k in 0..3 {
        for i in 0..3 {
            for j in 0..3 {
                let mut s = 0.0;
                for l in 0..3 {
                    s += ginv[k][l] * (dg[i][j][l] + dg[j][i][l] - dg[l][i][j]);
                }
                gamma[k][i][j] = 0.5 * s;
            }
        }
    }
    gamma
}

/// Max-norm of the difference of two 3x3x3 arrays.
pub fn max_diff3(a: &[[[f64; 3]; 3]; 3], b: &[[[f64; 3]; 3]; 3]) -> f64 {
    let mut m: f64 = 0.0;
    for k in 0..3 {
        for i in 0..3 {
            for j in 0..3 {
                m = m.max((a[k][i][j] - b[k][i][j]).abs());
            }
        }
    }
    m
}
