//! The L2 error norms of the 3-D operators and studies: lengths in the metric `g_ij`.

/// The physical length squared of the contravariant vector `d` at a point of metric `g_ij`:
/// `|d|^2 = g_ij d^i d^j` (the error norms of the 3-D operators and studies).
pub(crate) fn length_squared(metric: &[[f64; 3]; 3], d: [f64; 3]) -> f64 {
    (0..3)
        .map(|i| (0..3).map(|j| metric[i][j] * d[i] * d[j]).sum::<f64>())
        .sum()
}

/// Adds one quadrature point of weight `w` (including `sqrt(g)`) to the error sums
/// `s = [int |u_h - u|^2, int |u|^2]` of the 3-D error norms, lengths by [`length_squared`].
pub(crate) fn add_error_point(
    s: &mut [f64; 2],
    w: f64,
    metric: &[[f64; 3]; 3],
    uh: [f64; 3],
    u: [f64; 3],
) {
    s[0] += w * length_squared(metric, [uh[0] - u[0], uh[1] - u[1], uh[2] - u[2]]);
    s[1] += w * length_squared(metric, u);
}

/// `(l2, l2_exact) = (sqrt(sum s_0), sqrt(sum s_1))` over the elements' error sums, added
/// sequentially in element order (reproducible under any thread count).
pub(crate) fn error_norms(sums: &[[f64; 2]]) -> (f64, f64) {
    let s = sums
        .iter()
        .fold([0.0; 2], |acc, x| [acc[0] + x[0], acc[1] + x[1]]);
    (s[0].sqrt(), s[1].sqrt())
}
