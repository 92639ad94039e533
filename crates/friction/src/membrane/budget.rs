//! The work budgets of the membrane models' numerics: each ends in a typed error naming its
//! scene key.

use crate::error::{FrictionError, check};
use crate::quadrature::DEFAULT_MAX_SUBDIVISIONS;

/// How much work the membrane models may do before they give up with a typed error.
///
/// Each field is a scene key of `[membrane]`; the error that ends a run names it, the value
/// reached and what to change. Build as `MembraneBudget { max_steps: 10, ..Default::default() }`.
///
/// # Example
/// ```
/// use capstan_friction::membrane::{MembraneBudget, MembraneProblem, tension_profile_within};
/// use capstan_friction::FrictionError;
/// use capstan_geometry::{EllipticalPrism, Obstacle};
/// let ellipse = Obstacle::Ellipse(EllipticalPrism::new(2.0, 1.0).unwrap());
/// let problem = MembraneProblem {
///     loads: capstan_friction::membrane::MembraneLoads { gravity: 9.81, density: 1.0, ..Default::default() },
///     ..Default::default()
/// };
/// let budget = MembraneBudget { max_steps: 2, ..Default::default() };
/// let e = tension_profile_within(&ellipse, &problem, &budget).unwrap_err();
/// assert!(matches!(e, FrictionError::TooManySteps { max_steps: 2, .. }));
/// assert!(e.to_string().contains("membrane.max_steps"));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MembraneBudget {
    /// Panels of adaptive quadrature (turning angle of a prism, the nested quadrature of a
    /// general cone; `membrane.max_subdivisions`, default `2^16`).
    pub max_subdivisions: usize,
    /// Steps (accepted and rejected) of the ODE integrator (`membrane.max_steps`, default
    /// 100,000).
    pub max_steps: usize,
    /// Smallest ODE step size before giving up (`membrane.min_step`, default 0: only the
    /// round-off floor `10 eps |t|`).
    pub min_step: f64,
    /// Iterations of the root finder of the inverse problem, `infer-mu`
    /// (`membrane.max_root_iterations`, default 200).
    pub max_root_iterations: usize,
}

impl Default for MembraneBudget {
    fn default() -> Self {
        Self {
            max_subdivisions: DEFAULT_MAX_SUBDIVISIONS,
            max_steps: 100_000,
            min_step: 0.0,
            max_root_iterations: 200,
        }
    }
}

impl MembraneBudget {
    /// Checks every field: counts at least 1, `min_step` finite and `>= 0`.
    ///
    /// # Errors
    /// [`FrictionError::InvalidParameter`] naming the scene key.
    pub fn validate(&self) -> Result<(), FrictionError> {
        for (key, n) in [
            ("membrane.max_subdivisions", self.max_subdivisions),
            ("membrane.max_steps", self.max_steps),
            ("membrane.max_root_iterations", self.max_root_iterations),
        ] {
            check(key, n as f64, "[1, inf)", |v| v >= 1.0)?;
        }
        check("membrane.min_step", self.min_step, "[0, inf)", |v| v >= 0.0)?;
        Ok(())
    }
}
