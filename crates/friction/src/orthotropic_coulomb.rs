//! Orthotropic (elliptic) Coulomb friction: different coefficients along two tangent axes.

use capstan_geometry::Real;

use crate::error::{FrictionError, check, check_non_negative, check_width, to_f64};
use crate::friction_law::{ContactState, FrictionLaw, TractionDerivatives};
use crate::registration::{RegisteredLaw, bind};

/// Orthotropic Coulomb friction with an elliptic limit surface and the associated slip rule
/// (Konyukhov's generalised orthotropic law, paper section 1), regularised like
/// [`crate::RegularisedCoulomb`].
///
/// # Math
/// In the orthotropy axes (`u' = R(-phi) u`, `t = R(phi) t'`, `phi` = `axis_angle` from the
/// slip frame's first axis), with `M = diag(mu_1^2, mu_2^2)`:
/// ```text
/// limit surface  (t'_1/mu_1)^2 + (t'_2/mu_2)^2 = p^2
/// slip rule      u' parallel to (t'_1/mu_1^2, t'_2/mu_2^2)
/// t' = p M u' / max(m(u'), mu_bar eps),   m(u') = sqrt(mu_1^2 u'_1^2 + mu_2^2 u'_2^2),
///                                         mu_bar = max(mu_1, mu_2)
/// dt'_i/du'_j = p M_ii (delta_ij / m - u'_i M_jj u'_j / m^3)     (m >= mu_bar eps)
/// dt'_i/du'_j = p M_ii delta_ij / (mu_bar eps)                   (m <  mu_bar eps)
/// dt'/dp      = M u' / max(m, mu_bar eps)
/// ```
/// With `mu_1 = mu_2 = mu` it is exactly [`crate::RegularisedCoulomb`]. Sliding along axis
/// `k` meets the resistance `mu_k |p|`.
///
/// # Example
/// ```
/// use capstan_friction::{ContactState, FrictionLaw, OrthotropicCoulomb, OrthotropicCoulombParams};
/// let p = OrthotropicCoulombParams::new([0.2, 0.6], 0.0, 1e-4).unwrap();
/// let t: [f64; 2] = OrthotropicCoulomb.traction(&ContactState::new([0.0, 1.0], -2.0), &p);
/// assert!((t[1] + 1.2).abs() < 1e-15 && t[0] == 0.0); // mu_2 |p|
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct OrthotropicCoulomb;

/// Parameters of [`OrthotropicCoulomb`]: `mu_1, mu_2 >= 0` (`friction.mu`, `friction.mu2`), not
/// both zero; `axis_angle` finite (`friction.axis_angle`); `eps > 0` (`friction.eps`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrthotropicCoulombParams<F> {
    mu: [F; 2],
    axis: [F; 2], // (cos phi, sin phi)
    angle: F,
    eps: F,
}

impl<F: Real> OrthotropicCoulombParams<F> {
    /// Coefficients along the two orthotropy axes, the first axis's angle from the slip
    /// frame's first axis, and the regularisation width.
    ///
    /// # Errors
    /// [`FrictionError::InvalidParameter`] naming `mu`, `mu2`, `axis_angle` or
    /// `eps` (the API parameters; scenes: `friction.mu`, ...).
    pub fn new(mu: [F; 2], axis_angle: F, eps: F) -> Result<Self, FrictionError> {
        check_non_negative("mu", mu[0])?;
        let m1 = to_f64(mu[0]);
        check(
            "mu2",
            to_f64(mu[1]),
            "[0, inf), not both coefficients zero",
            |v| v >= 0.0 && (v > 0.0 || m1 > 0.0),
        )?;
        check("axis_angle", to_f64(axis_angle), "(-inf, inf)", |_| true)?;
        check_width(eps)?;
        Ok(Self {
            mu,
            axis: [axis_angle.cos(), axis_angle.sin()],
            angle: axis_angle,
            eps,
        })
    }
    /// `[mu_1, mu_2]`.
    pub fn mu(&self) -> [F; 2] {
        self.mu
    }
    /// The first orthotropy axis's angle `phi`.
    pub fn axis_angle(&self) -> F {
        self.angle
    }
    /// The regularisation width.
    pub fn eps(&self) -> F {
        self.eps
    }
    fn rotate_into_axes(&self, v: [F; 2]) -> [F; 2] {
        let [c, s] = self.axis;
        [c * v[0] + s * v[1], -s * v[0] + c * v[1]]
    }
    fn rotate_out_of_axes(&self, v: [F; 2]) -> [F; 2] {
        let [c, s] = self.axis;
        [c * v[0] - s * v[1], s * v[0] + c * v[1]]
    }
}

impl<F: Real> FrictionLaw<F> for OrthotropicCoulomb {
    type Params = OrthotropicCoulombParams<F>;

    fn traction(&self, c: &ContactState<F>, p: &Self::Params) -> [F; 2] {
        let u = p.rotate_into_axes(c.slip);
        let m2 = [p.mu[0] * p.mu[0], p.mu[1] * p.mu[1]];
        let m = (m2[0] * u[0] * u[0] + m2[1] * u[1] * u[1]).sqrt();
        let floor = p.mu[0].max(p.mu[1]) * p.eps;
        let s = c.normal_pressure / m.max(floor);
        p.rotate_out_of_axes([s * m2[0] * u[0], s * m2[1] * u[1]])
    }

    fn traction_derivatives(
        &self,
        c: &ContactState<F>,
        p: &Self::Params,
    ) -> TractionDerivatives<F> {
        let u = p.rotate_into_axes(c.slip);
        let m2 = [p.mu[0] * p.mu[0], p.mu[1] * p.mu[1]];
        let m = (m2[0] * u[0] * u[0] + m2[1] * u[1] * u[1]).sqrt();
        let floor = p.mu[0].max(p.mu[1]) * p.eps;
        let pr = c.normal_pressure;
        let mut d = [[F::zero(); 2]; 2];
        let inv = F::one() / m.max(floor);
        if m >= floor {
            let inv3 = inv * inv * inv;
            for i in 0..2 {
                for j in 0..2 {
                    let delta = if i == j { inv } else { F::zero() };
                    d[i][j] = pr * m2[i] * (delta - u[i] * m2[j] * u[j] * inv3);
                }
            }
        } else {
            d[0][0] = pr * m2[0] * inv;
            d[1][1] = pr * m2[1] * inv;
        }
        // Rotate back: D = R D' R^T.
        let [co, si] = p.axis;
        let r = [[co, -si], [si, co]];
        let mut out = [[F::zero(); 2]; 2];
        for i in 0..2 {
            for j in 0..2 {
                let mut acc = F::zero();
                for k in 0..2 {
                    for l in 0..2 {
                        acc += r[i][k] * d[k][l] * r[j][l];
                    }
                }
                out[i][j] = acc;
            }
        }
        let dp = p.rotate_out_of_axes([m2[0] * u[0] * inv, m2[1] * u[1] * inv]);
        TractionDerivatives::new(out, dp)
    }
}

/// `friction.law = "orthotropic-coulomb"`: [`OrthotropicCoulomb`] from `friction.mu`,
/// `friction.mu2`, `friction.axis_angle`, `friction.eps`.
pub(crate) const REGISTRATION: RegisteredLaw = RegisteredLaw {
    name: "orthotropic-coulomb",
    summary: "orthotropic Coulomb friction: mu_1, mu_2 along axes at axis_angle",
    parameters: &["mu", "mu2", "axis_angle", "eps"],
    build: |s| {
        let p = OrthotropicCoulombParams::new([s.mu, s.mu2], s.axis_angle, s.eps)?;
        Ok(bind(OrthotropicCoulomb, p))
    },
};
