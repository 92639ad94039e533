//! External force fields `(0, g_r2, g_r3)` on the membrane (Theorem 1).

use capstan_geometry::expression::Expression;
use capstan_geometry::{GeometryError, SurfaceGeometry};

use crate::error::FrictionError;

/// An external force per unit length of membrane, in the curvilinear components of Theorem 1.
///
/// # Math
/// For a Euclidean force `q` per unit length at the point with tangent `a_2` and normal `N`:
/// ```text
/// g_r2 = q . a_2      covariant tangential component (per unit x2, = sqrt(a_22) q . t)
/// g_r3 = q . N        normal component (per unit length)
/// ```
/// These enter the prism equilibrium (eq. PrismEqn02) as
/// `dT/dx2 = mu sqrt(a_22) (kappa (T - c) - g_r3) - g_r2`, `c = rho_l V^2`.
pub trait LoadField {
    /// `[g_r2, g_r3]` at `x2 = theta`, given the surface's geometry there.
    fn load(&self, theta: f64, geometry: &SurfaceGeometry<f64>) -> [f64; 2];
}

/// No external force.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct NoLoad;

impl LoadField for NoLoad {
    fn load(&self, _theta: f64, _geometry: &SurfaceGeometry<f64>) -> [f64; 2] {
        [0.0, 0.0]
    }
}

/// Gravity `(0, 0, -g)`: a force `q = (0, 0, -w)` per unit length, `w = rho h l g`.
///
/// # Math
/// `g_r2 = -w (a_2)_z`, `g_r3 = -w N_z`; on the cylinder `(x1, a sin t, a cos t)` this is the
/// paper's `(0, a w sin t, -w cos t)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gravity {
    /// Weight per unit length `w`.
    pub weight_per_length: f64,
}

impl LoadField for Gravity {
    fn load(&self, _theta: f64, g: &SurfaceGeometry<f64>) -> [f64; 2] {
        let w = self.weight_per_length;
        [-w * g.tangents[1][2], -w * g.normal[2]]
    }
}

impl<G: Fn(f64, &SurfaceGeometry<f64>) -> [f64; 2]> LoadField for G {
    fn load(&self, theta: f64, geometry: &SurfaceGeometry<f64>) -> [f64; 2] {
        self(theta, geometry)
    }
}

/// Force densities along the membrane given as expressions in `t = x2 = theta` (scene keys
/// `loads.f_t`, `loads.f_n`): any load field of Theorem 1 (Corollary 1: volume densities).
///
/// # Math
/// `f_t(theta)` is the force per unit length along the unit tangent `t = a_2 / |a_2|`
/// (positive towards `theta_max`), `f_n(theta)` the force per unit length along the outward
/// unit normal `N` (positive away from the obstacle). Theorem 1's curvilinear components are
/// ```text
/// g_r2 = sqrt(a_22) f_t        covariant: per unit x2
/// g_r3 = f_n
/// ```
/// so the membrane equilibrium reads `dT/dx2 = mu sqrt(a_22) (kappa T - f_n) - sqrt(a_22) f_t`
/// and Theorem 1 (continuous turning angle `Psi`, paper-notes item 1) gives
/// ```text
/// T(theta) = exp(mu Psi(theta)) [T0 exp(-mu Psi(theta0))
///            - int_{theta0}^{theta} sqrt(a_22) (f_t + mu f_n) exp(-mu Psi) dx2]
/// ```
/// The expressions are functions of the profile parameter `theta`, the coordinate of the
/// contact interval (`membrane.theta0`, `membrane.theta_max`) and of Theorem 1's integral;
/// the membrane lies on one `x2` line, so `x1` plays no part. Gravity `(0, 0, -w)` on the
/// cylinder `(x1, a sin t, a cos t)` is `f_t = w sin(t)`, `f_n = -w cos(t)`.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ExpressionLoad {
    tangential: Option<Expression>,
    normal: Option<Expression>,
}

impl ExpressionLoad {
    /// The scene keys of the two expressions.
    pub const KEYS: [&'static str; 2] = ["loads.f_t", "loads.f_n"];

    /// Parses `f_t` and `f_n` (either may be absent: zero).
    ///
    /// # Errors
    /// [`FrictionError::Geometry`] ([`GeometryError::Expression`]) naming `loads.f_t` or
    /// `loads.f_n` and the byte position of the problem.
    pub fn parse(f_t: Option<&str>, f_n: Option<&str>) -> Result<Self, FrictionError> {
        let parse = |src: Option<&str>, field| -> Result<Option<Expression>, FrictionError> {
            src.map(|s| {
                Expression::parse(s)
                    .map_err(|source| GeometryError::Expression { field, source }.into())
            })
            .transpose()
        };
        Ok(Self {
            tangential: parse(f_t, Self::KEYS[0])?,
            normal: parse(f_n, Self::KEYS[1])?,
        })
    }

    /// Whether neither expression is given.
    pub fn is_empty(&self) -> bool {
        self.tangential.is_none() && self.normal.is_none()
    }

    /// Checks both expressions (value, first and second derivatives) finite at `samples`
    /// evenly spaced points of `[theta0, theta_max]`.
    ///
    /// # Errors
    /// [`FrictionError::Geometry`] naming the key and the first bad angle.
    pub fn check_finite_on(
        &self,
        theta0: f64,
        theta_max: f64,
        samples: usize,
    ) -> Result<(), FrictionError> {
        for (field, e) in Self::KEYS.into_iter().zip([&self.tangential, &self.normal]) {
            if let Some(e) = e {
                e.check_finite_on(theta0, theta_max, samples)
                    .map_err(|source| GeometryError::Expression { field, source })?;
            }
        }
        Ok(())
    }

    /// `[f_t(theta), f_n(theta)]`.
    pub fn densities(&self, theta: f64) -> [f64; 2] {
        let at = |e: &Option<Expression>| e.as_ref().map_or(0.0, |e| e.eval(theta));
        [at(&self.tangential), at(&self.normal)]
    }
}

impl LoadField for ExpressionLoad {
    fn load(&self, theta: f64, g: &SurfaceGeometry<f64>) -> [f64; 2] {
        let [f_t, f_n] = self.densities(theta);
        [g.first_form[1][1].sqrt() * f_t, f_n]
    }
}

/// The paper's printed steady-speed transform (`membrane.belt_speed_rule = "paper"`, erratum 4):
/// the extra covariant tangential load `g_r2 = -rho_l Gamma^2_22 V^2` that the paper adds to the
/// (correct) normal term `2 rho_l H V^2`.
///
/// # Math
/// For a belt at constant Euclidean speed the acceleration `-V^2 kappa N` is normal to the path,
/// so only the normal load changes; the printed `g_r2 -> g_r2 - rho_l Gamma^2_22 V^2` agrees
/// with that only where `Gamma^2_22 = 0` (a circle). This field adds the printed term, so that
/// the paper's rule can be computed beside ours.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PaperSpeedTransform {
    /// `c = rho_l V^2`.
    pub speed_tension: f64,
}

impl LoadField for PaperSpeedTransform {
    fn load(&self, _theta: f64, g: &SurfaceGeometry<f64>) -> [f64; 2] {
        [-self.speed_tension * g.christoffel[1][1][1], 0.0]
    }
}

/// The sum of two load fields.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoadSum<A, B>(pub A, pub B);

impl<A: LoadField, B: LoadField> LoadField for LoadSum<A, B> {
    fn load(&self, theta: f64, g: &SurfaceGeometry<f64>) -> [f64; 2] {
        let (a, b) = (self.0.load(theta, g), self.1.load(theta, g));
        [a[0] + b[0], a[1] + b[1]]
    }
}
