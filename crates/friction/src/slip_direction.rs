//! The slip-direction kernels shared by the isotropic friction laws: a traction `s u r` along
//! the slip with a radial scale `r` (`1 / max(|u|, eps)`, `1 / sqrt(|u|^2 + eps^2)`, ...).

use capstan_geometry::Real;

use crate::friction_law::ContactState;

/// `|u|^2 = u_1^2 + u_2^2`, the squared slip length.
pub(crate) fn slip_norm_squared<F: Real>(u: [F; 2]) -> F {
    u[0] * u[0] + u[1] * u[1]
}

/// `mu p u / rho`: the Coulomb traction with the regularised slip length `rho` (`max(|u|,
/// eps)`, `sqrt(|u|^2 + eps^2)`), `p = sigma_n` the normal stress of `c`.
pub(crate) fn coulomb_traction<F: Real>(c: &ContactState<F>, mu: F, rho: F) -> [F; 2] {
    let s = mu * c.normal_pressure / rho;
    [s * c.slip[0], s * c.slip[1]]
}

/// `k u r`: a vector along the slip `u`, scaled by `k` and the radial factor `r`.
///
/// # Math
/// ```text
/// along(u, k, r)_i = k u_i r
/// ```
/// The traction of a law with magnitude `k`, or its pressure derivative with `k = d|t|/dp`.
pub(crate) fn along<F: Real>(u: [F; 2], k: F, r: F) -> [F; 2] {
    [k * u[0] * r, k * u[1] * r]
}

/// The slip derivative of `s u / rho(u)` where `r = 1 / rho` and `d rho / d u_j = u_j r`
/// (`rho = |u|` or `rho = sqrt(|u|^2 + eps^2)`).
///
/// # Math
/// ```text
/// d(s u_i r)/d u_j = s (delta_ij r - u_i u_j r^3)
/// ```
pub(crate) fn radial_tangent<F: Real>(u: [F; 2], s: F, r: F) -> [[F; 2]; 2] {
    let [u1, u2] = u;
    let r3 = r * r * r;
    [
        [s * (r - u1 * u1 * r3), -s * u1 * u2 * r3],
        [-s * u2 * u1 * r3, s * (r - u2 * u2 * r3)],
    ]
}

/// `s u / max(|u|, eps)` and its slip derivatives: the direction kernel shared by the
/// isotropic laws whose magnitude `s` does not depend on the slip.
///
/// # Math
/// ```text
/// r = 1 / max(|u|, eps)
/// t = s u r
/// dt_i/du_j = s (delta_ij r - u_i u_j r^3)   if |u| >= eps
/// dt_i/du_j = s delta_ij r                   if |u| <  eps
/// ```
/// Returns `(t, dt/du, r)`.
pub(crate) fn direction_kernel<F: Real>(u: [F; 2], s: F, eps: F) -> ([F; 2], [[F; 2]; 2], F) {
    let norm = slip_norm_squared(u).sqrt();
    if norm >= eps {
        let r = F::one() / norm;
        (along(u, s, r), radial_tangent(u, s, r), r)
    } else {
        let r = F::one() / eps;
        (along(u, s, r), [[s * r, F::zero()], [F::zero(), s * r]], r)
    }
}
