//! The membrane capstan problem: parameters, loads and the computed tension profile.

use std::f64::consts::FRAC_PI_2;

use crate::error::{FrictionError, check, check_wrap};

/// External loads on the membrane and its steady speed (scene table `[loads]`).
///
/// # Math
/// ```text
/// rho_l = density * width * thickness          line density (mass per unit length)
/// w     = rho_l * gravity                      weight per unit length; gravity is (0, 0, -g)
/// c     = rho_l * speed^2                      the steady-speed tension rho_l V^2
/// ```
/// Theorem 1's loads are forces per unit length of membrane: volume densities times `h l`
/// (paper-notes item 8).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MembraneLoads {
    /// Gravitational acceleration `g >= 0` (`loads.gravity`); gravity is `(0, 0, -g)`.
    pub gravity: f64,
    /// Mass per unit volume `rho >= 0` (`loads.density`).
    pub density: f64,
    /// Membrane width `l > 0` (`loads.width`).
    pub width: f64,
    /// Membrane thickness `h > 0` (`loads.thickness`).
    pub thickness: f64,
    /// Steady belt speed `V` in the Euclidean sense (`loads.speed`).
    pub speed: f64,
}

impl Default for MembraneLoads {
    fn default() -> Self {
        Self {
            gravity: 0.0,
            density: 0.0,
            width: 1.0,
            thickness: 1.0,
            speed: 0.0,
        }
    }
}

impl MembraneLoads {
    /// Checks every field.
    ///
    /// # Errors
    /// [`FrictionError::InvalidParameter`] naming the scene key of the first bad field.
    pub fn validate(&self) -> Result<(), FrictionError> {
        check("loads.gravity", self.gravity, "[0, inf)", |v| v >= 0.0)?;
        check("loads.density", self.density, "[0, inf)", |v| v >= 0.0)?;
        check("loads.width", self.width, "(0, inf)", |v| v > 0.0)?;
        check("loads.thickness", self.thickness, "(0, inf)", |v| v > 0.0)?;
        check("loads.speed", self.speed, "(-inf, inf)", |_| true)?;
        Ok(())
    }
    /// Line density `rho_l = density * width * thickness`.
    pub fn line_density(&self) -> f64 {
        self.density * self.width * self.thickness
    }
    /// Weight per unit length `w = rho_l g`.
    pub fn weight_per_length(&self) -> f64 {
        self.line_density() * self.gravity
    }
    /// The steady-speed tension `c = rho_l V^2`.
    pub fn speed_tension(&self) -> f64 {
        self.line_density() * self.speed * self.speed
    }
    /// Whether any body force acts (weight or steady speed).
    pub fn any(&self) -> bool {
        self.weight_per_length() != 0.0 || self.speed_tension() != 0.0
    }
}

/// A membrane capstan problem on the contact interval `[theta0, theta_max]`.
///
/// Build as `MembraneProblem { mu: 0.3, ..Default::default() }`; the defaults are the scene
/// defaults (`mu = 1/2`, `T0 = 1`, `[-pi/2, pi/2]`, 101 samples, no loads).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MembraneProblem {
    /// Coefficient of friction `mu >= 0` (`friction.mu`).
    pub mu: f64,
    /// Tension `T0 > 0` at `theta0` (`membrane.t0`).
    pub t0: f64,
    /// Start of the contact interval (`membrane.theta0`).
    pub theta0: f64,
    /// End of the contact interval, `> theta0` (`membrane.theta_max`).
    pub theta_max: f64,
    /// Evenly spaced output samples on `[theta0, theta_max]`, both ends included, `>= 2`
    /// (`membrane.samples`).
    pub samples: usize,
    /// External loads and steady speed.
    pub loads: MembraneLoads,
}

impl Default for MembraneProblem {
    fn default() -> Self {
        Self {
            mu: 0.5,
            t0: 1.0,
            theta0: -FRAC_PI_2,
            theta_max: FRAC_PI_2,
            samples: 101,
            loads: MembraneLoads::default(),
        }
    }
}

impl MembraneProblem {
    /// Checks every field.
    ///
    /// # Errors
    /// [`FrictionError::InvalidParameter`] naming the scene key of the first bad field.
    pub fn validate(&self) -> Result<(), FrictionError> {
        check("friction.mu", self.mu, "[0, inf)", |v| v >= 0.0)?;
        check("membrane.t0", self.t0, "(0, inf)", |v| v > 0.0)?;
        check_wrap(
            self.theta0,
            self.theta_max,
            self.samples,
            (2.0, 1e7, "[2, 10^7]"),
        )?;
        self.loads.validate()
    }
    /// The output sample angles: `samples` evenly spaced points, both ends exact.
    pub fn thetas(&self) -> Vec<f64> {
        let n = self.samples.max(2);
        (0..n)
            .map(|i| {
                if i + 1 == n {
                    self.theta_max
                } else {
                    self.theta0 + (self.theta_max - self.theta0) * i as f64 / (n - 1) as f64
                }
            })
            .collect()
    }
}

/// How a tension profile was computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// A closed form (exact to rounding).
    ClosedForm,
    /// Adaptive Gauss–Kronrod quadrature of the exponent (no loads).
    Quadrature,
    /// Dormand–Prince 8(5,3) integration of the membrane equilibrium ODE.
    Ode,
}

impl Method {
    /// `closed-form`, `quadrature` or `ode`.
    pub fn as_str(&self) -> &'static str {
        match self {
            Self::ClosedForm => "closed-form",
            Self::Quadrature => "quadrature",
            Self::Ode => "ode",
        }
    }
}

impl core::fmt::Display for Method {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// A tension profile `T(theta)` sampled on the contact interval.
#[derive(Debug, Clone, PartialEq)]
pub struct TensionProfile {
    /// Sample angles, `theta[0] = theta0`, last `= theta_max`.
    pub theta: Vec<f64>,
    /// Tension `T(theta)` (force; stress for the infinite membrane of Corollary 1).
    pub tension: Vec<f64>,
    /// How it was computed.
    pub method: Method,
}

impl TensionProfile {
    /// `T(theta_max)`, the paper's `T_max`.
    ///
    /// # Panics
    /// Never for profiles built by this crate (they have at least two samples).
    pub fn t_max(&self) -> f64 {
        *self.tension.last().expect("a profile has samples")
    }
    /// `T(theta_max) / T(theta0)`, the paper's tension ratio `delta tau`.
    pub fn tension_ratio(&self) -> f64 {
        self.t_max() / self.tension[0]
    }
}

/// `T = c + (T0 - c) exp(x)` without overflow in the intermediate, or a typed error.
pub(crate) fn exp_tension(t0: f64, c: f64, x: f64, angle: f64) -> Result<f64, FrictionError> {
    let t = if c == 0.0 {
        (t0.ln() + x).exp()
    } else {
        c + (t0 - c) * x.exp()
    };
    if t.is_finite() {
        Ok(t)
    } else {
        Err(FrictionError::NonFinite {
            what: "tension (overflow)",
            angle,
        })
    }
}
