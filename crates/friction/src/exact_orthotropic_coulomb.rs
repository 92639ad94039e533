//! Exact orthotropic Coulomb friction: the return map onto the friction ellipse.

use capstan_geometry::Real;

use crate::error::{FrictionError, check, check_non_negative, to_f64};
use crate::nonsmooth_law::{
    FrictionState, NonsmoothFrictionLaw, Projection, RegisteredNonsmoothLaw, bind_nonsmooth,
    check_finite_input,
};

/// Largest number of Newton steps on the ellipse projection's multiplier (it converges
/// monotonically and quadratically; 60 steps are far more than any `f64` input needs).
pub const ELLIPSE_MAX_ITERATIONS: usize = 60;

/// Exact orthotropic Coulomb friction: the Euclidean projection onto the ellipse
/// `(t'_1/mu_1)^2 + (t'_2/mu_2)^2 <= sigma_n^2` in the orthotropy axes (the `eps -> 0` limit
/// of [`crate::OrthotropicCoulomb`], with the same associated slip rule).
///
/// # Math
/// In the axes (`s = R(-phi) t*`, `t = R(phi) t'`), with semi-axes `a_i = mu_i p`,
/// `p = max(-sigma_n, 0)`: inside (`sum s_i^2/a_i^2 <= 1`) stick, `t' = s`; outside
/// ```text
/// t'_i = a_i^2 s_i / (a_i^2 + lambda),   lambda > 0 the root of
/// phi(lambda) = sum_i a_i^2 s_i^2 / (a_i^2 + lambda)^2 - 1 = 0
/// ```
/// (Newton from `lambda_0 = max(0, max_i(a_i |s_i| - a_i^2))`, where `phi >= 0`; `phi` is
/// convex and decreasing, so the iterates rise monotonically to the root). Implicit
/// differentiation gives, with `D = diag(a_i^2/(a_i^2 + lambda))`, `q_i = s_i/(a_i^2 + lambda)`,
/// ```text
/// dt'/ds       = D - (D q)(D q)^T / (q^T D q)        (symmetric, rank 1 on the boundary)
/// dt'/dsigma_n = -(t' - (dt'/ds) s) / p             (the set scales with p)
/// ```
/// and `dt/dt* = R (dt'/ds) R^T`. One zero coefficient makes the ellipse a segment, on which the
/// projection is a clamp. The Euclidean projection makes the slip increment normal to the
/// ellipse (`du' ∥ (t'_1/mu_1^2, t'_2/mu_2^2)`): sliding along axis `k` meets `mu_k |sigma_n|`.
///
/// # Example
/// ```
/// use capstan_friction::{ExactOrthotropicCoulomb, ExactOrthotropicCoulombParams, NonsmoothFrictionLaw};
/// let p = ExactOrthotropicCoulombParams::<f64>::new([0.2, 0.6], 0.0).unwrap();
/// let pr = ExactOrthotropicCoulomb.project([0.0, 5.0], -2.0, &p).unwrap();
/// assert!((pr.traction[1] - 1.2).abs() < 1e-14 && pr.traction[0].abs() < 1e-15); // mu_2 |sigma_n|
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ExactOrthotropicCoulomb;

/// Parameters of [`ExactOrthotropicCoulomb`]: `mu_1, mu_2 >= 0`, not both zero, and the first
/// axis's angle `phi` from the slip frame's first axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExactOrthotropicCoulombParams<F> {
    mu: [F; 2],
    axis: [F; 2], // (cos phi, sin phi)
}

impl<F: Real> ExactOrthotropicCoulombParams<F> {
    /// Coefficients along the two orthotropy axes and the first axis's angle (radians).
    ///
    /// # Errors
    /// [`FrictionError::InvalidParameter`] naming `mu`, `mu2` or `axis_angle`
    /// (the API parameters; scenes: `friction.mu`, ...).
    pub fn new(mu: [F; 2], axis_angle: F) -> Result<Self, FrictionError> {
        check_non_negative("mu", mu[0])?;
        let m1 = to_f64(mu[0]);
        check(
            "mu2",
            to_f64(mu[1]),
            "[0, inf), not both coefficients zero",
            |v| v >= 0.0 && (v > 0.0 || m1 > 0.0),
        )?;
        check("axis_angle", to_f64(axis_angle), "(-inf, inf)", |_| true)?;
        Ok(Self {
            mu,
            axis: [axis_angle.cos(), axis_angle.sin()],
        })
    }
    /// `[mu_1, mu_2]`.
    pub fn mu(&self) -> [F; 2] {
        self.mu
    }
}

/// `R v` for the rotation by `(c, s) = (cos phi, sin phi)`.
fn rotate<F: Real>([c, s]: [F; 2], v: [F; 2]) -> [F; 2] {
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

/// A projection in the orthotropy axes: `(t', dt'/ds, state)`.
type AxisProjection<F> = ([F; 2], [[F; 2]; 2], FrictionState);

/// The projection of `s` onto the ellipse with semi-axes `a` (both `> 0`) in its axes:
/// `(t', dt'/ds, state)`.
fn project_ellipse<F: Real>(s: [F; 2], a: [F; 2]) -> Result<AxisProjection<F>, FrictionError> {
    let (zero, one) = (F::zero(), F::one());
    let a2 = [a[0] * a[0], a[1] * a[1]];
    let two = one + one;
    // within round-off of the ellipse counts as on it (as for the disc)
    if s[0] * s[0] / a2[0] + s[1] * s[1] / a2[1] <= one + two * two * two * F::epsilon() {
        let p = Projection::stick(s);
        return Ok((p.traction, p.d_trial, FrictionState::Stick));
    }
    let phi = |l: F| {
        let r = [a[0] * s[0] / (a2[0] + l), a[1] * s[1] / (a2[1] + l)];
        // phi and phi' = -2 sum a_i^2 s_i^2 / (a_i^2 + l)^3
        let d = -(r[0] * r[0] / (a2[0] + l) + r[1] * r[1] / (a2[1] + l)) * (one + one);
        (r[0] * r[0] + r[1] * r[1] - one, d)
    };
    let mut lambda = (a[0] * s[0].abs() - a2[0])
        .max(a[1] * s[1].abs() - a2[1])
        .max(zero);
    let mut converged = false;
    let mut residual = zero;
    let tolerance = F::epsilon() * two * two * two;
    for _ in 0..ELLIPSE_MAX_ITERATIONS {
        let (f, df) = phi(lambda);
        residual = f;
        // phi is relative to 1: |phi| at round-off puts t' on the ellipse to round-off
        if f.abs() <= tolerance {
            converged = true;
            break;
        }
        let next = lambda - f / df;
        if !next.is_finite() {
            break;
        }
        // monotone from the left; round-off can only overshoot back
        lambda = next.max(lambda);
    }
    if !converged {
        return Err(FrictionError::ProjectionNotConverged {
            iterations: ELLIPSE_MAX_ITERATIONS,
            residual: to_f64(residual),
        });
    }
    let d = [a2[0] / (a2[0] + lambda), a2[1] / (a2[1] + lambda)];
    let q = [s[0] / (a2[0] + lambda), s[1] / (a2[1] + lambda)];
    let dq = [d[0] * q[0], d[1] * q[1]];
    let qdq = q[0] * dq[0] + q[1] * dq[1];
    let jac = [
        [d[0] - dq[0] * dq[0] / qdq, -dq[0] * dq[1] / qdq],
        [-dq[1] * dq[0] / qdq, d[1] - dq[1] * dq[1] / qdq],
    ];
    Ok(([d[0] * s[0], d[1] * s[1]], jac, FrictionState::Slip))
}

/// The projection onto the segment `|t'_k| <= a_k`, `t'_other = 0` (one coefficient zero).
fn project_segment<F: Real>(s: [F; 2], a: [F; 2]) -> AxisProjection<F> {
    let k = if a[0] > F::zero() { 0 } else { 1 };
    let (zero, one) = (F::zero(), F::one());
    let mut t = [zero; 2];
    let mut jac = [[zero; 2]; 2];
    t[k] = s[k].max(-a[k]).min(a[k]);
    if s[k].abs() <= a[k] {
        jac[k][k] = one;
    }
    let stick = s[k].abs() <= a[k] && s[1 - k] == zero;
    let state = if stick {
        jac[1 - k][1 - k] = one; // the stick branch of the generalised Jacobian
        FrictionState::Stick
    } else {
        FrictionState::Slip
    };
    (t, jac, state)
}

impl<F: Real> NonsmoothFrictionLaw<F> for ExactOrthotropicCoulomb {
    type Params = ExactOrthotropicCoulombParams<F>;

    fn project(
        &self,
        trial: [F; 2],
        normal_pressure: F,
        params: &Self::Params,
    ) -> Result<Projection<F>, FrictionError> {
        check_finite_input(trial, normal_pressure)?;
        if normal_pressure >= F::zero() {
            return Ok(Projection::separated());
        }
        let p = -normal_pressure;
        let [c, sn] = params.axis;
        let s = rotate([c, -sn], trial);
        let a = [params.mu[0] * p, params.mu[1] * p];
        let (t, jac, state) = if a[0] > F::zero() && a[1] > F::zero() {
            project_ellipse(s, a)?
        } else {
            project_segment(s, a)
        };
        // dt'/dsigma_n = -(t' - J s)/p
        let js = [
            jac[0][0] * s[0] + jac[0][1] * s[1],
            jac[1][0] * s[0] + jac[1][1] * s[1],
        ];
        let dp = [-(t[0] - js[0]) / p, -(t[1] - js[1]) / p];
        // J = R J' R^T
        let r = [[c, -sn], [sn, c]];
        let mut out = [[F::zero(); 2]; 2];
        for (i, row) in out.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                for k in 0..2 {
                    for l in 0..2 {
                        *x += r[i][k] * jac[k][l] * r[j][l];
                    }
                }
            }
        }
        Ok(Projection::new(
            rotate([c, sn], t),
            out,
            rotate([c, sn], dp),
            state,
        ))
    }
}

/// `friction.law = "exact-orthotropic-coulomb"`: [`ExactOrthotropicCoulomb`] from
/// `friction.mu`, `friction.mu2`, `friction.axis_angle` (no `eps`).
pub(crate) const REGISTRATION: RegisteredNonsmoothLaw = RegisteredNonsmoothLaw {
    name: "exact-orthotropic-coulomb",
    summary: "exact orthotropic Coulomb friction (no eps): projection onto the ellipse of mu, mu2 at axis_angle",
    parameters: &["mu", "mu2", "axis_angle"],
    build: |s| {
        let p = ExactOrthotropicCoulombParams::new([s.mu, s.mu2], s.axis_angle)?;
        Ok(bind_nonsmooth(ExactOrthotropicCoulomb, p))
    },
};
