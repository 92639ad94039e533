//! Theorem 1: the membrane on a general prism `(x1, u(x2), v(x2))`.

use capstan_geometry::{GeneralPrism, ProfileCurve};

use super::budget::MembraneBudget;
use super::equilibrium::MembraneEquilibrium;
use super::problem::{MembraneProblem, Method, TensionProfile, exp_tension};
use super::turning_angle::{ProfilePoint, turning_angles, turning_angles_within};
use crate::error::FrictionError;

/// A membrane on the prism over `profile` (Theorem 1 of the paper).
///
/// # Math
/// Without weight (steady speed allowed), with `c = rho_l V^2`:
/// ```text
/// T(theta) = c + (T0 - c) exp(mu (Psi(theta) - Psi(theta0)))
/// Psi(t)   = int (v'u'' - u'v'')/(u'^2 + v'^2) dt          continuous turning angle
/// ```
/// (Theorem 1 with `-atan(v'/u')` replaced by the continuous `Psi`, paper-notes item 1.) With
/// weight the equilibrium ODE is integrated ([`MembraneEquilibrium`]).
///
/// # Example
/// ```
/// use capstan_friction::membrane::{MembraneProblem, PrismMembrane};
/// use capstan_geometry::ExpressionProfile;
/// let ellipse = ExpressionProfile::parse("2*sin(t)", "cos(t)").unwrap();
/// let problem = MembraneProblem { mu: 0.5, theta0: -0.25 * std::f64::consts::PI,
///     theta_max: 0.25 * std::f64::consts::PI, ..Default::default() };
/// let profile = PrismMembrane::new(&ellipse).tension_profile(&problem).unwrap();
/// // exp(2 mu atan(b/a)) with b/a = 1/2
/// assert!((profile.tension_ratio() - (0.5f64).atan().exp()).abs() < 1e-14);
/// ```
#[derive(Debug, Clone, Copy)]
pub struct PrismMembrane<'a, C: ?Sized> {
    profile: &'a C,
}

impl<'a, C: ProfileCurve<f64> + ?Sized> PrismMembrane<'a, C> {
    /// The membrane on the prism over `profile`.
    pub fn new(profile: &'a C) -> Self {
        Self { profile }
    }

    /// `Psi(theta) - Psi(theta0)` at the sorted angles `thetas`, by quadrature.
    ///
    /// # Errors
    /// See [`turning_angles`].
    pub fn turning_angles(&self, theta0: f64, thetas: &[f64]) -> Result<Vec<f64>, FrictionError> {
        turning_angles(self.profile, theta0, thetas)
    }

    /// The tension profile: quadrature without weight, ODE with weight.
    ///
    /// # Errors
    /// Invalid parameters; [`FrictionError::NonPositiveCurvature`];
    /// [`FrictionError::LiftOff`] (e.g. `T0 < rho_l V^2`); non-convergence.
    pub fn tension_profile(
        &self,
        problem: &MembraneProblem,
    ) -> Result<TensionProfile, FrictionError> {
        self.tension_profile_within(problem, &MembraneBudget::default())
    }

    /// [`PrismMembrane::tension_profile`] within `budget`.
    ///
    /// # Errors
    /// As [`PrismMembrane::tension_profile`]; the typed error of the budget that runs out.
    pub fn tension_profile_within(
        &self,
        problem: &MembraneProblem,
        budget: &MembraneBudget,
    ) -> Result<TensionProfile, FrictionError> {
        problem.validate()?;
        budget.validate()?;
        if problem.loads.weight_per_length() != 0.0 {
            let prism = GeneralPrism::new(self.profile);
            return MembraneEquilibrium::new(&prism, *problem)
                .with_budget(budget)
                .solve();
        }
        let thetas = problem.thetas();
        let psi = turning_angles_within(
            self.profile,
            problem.theta0,
            &thetas,
            budget.max_subdivisions,
        )?;
        let c = problem.loads.speed_tension();
        check_speed(problem, || {
            Ok(ProfilePoint::from_jet(self.profile.profile_jet(problem.theta0)).mean_curvature)
        })?;
        let tension = thetas
            .iter()
            .zip(&psi)
            .map(|(&t, &dpsi)| exp_tension(problem.t0, c, problem.mu * dpsi, t))
            .collect::<Result<_, _>>()?;
        Ok(TensionProfile {
            theta: thetas,
            tension,
            method: Method::Quadrature,
        })
    }
}

/// Without weight the reaction is `kappa (T - c)` with `T - c = (T0 - c) exp(...)`: the
/// membrane stays on the obstacle iff `T0 >= c = rho_l V^2`.
pub(crate) fn check_speed(
    problem: &MembraneProblem,
    mean_curvature_at_theta0: impl FnOnce() -> Result<f64, FrictionError>,
) -> Result<(), FrictionError> {
    let c = problem.loads.speed_tension();
    if problem.t0 < c {
        let h = mean_curvature_at_theta0()?;
        return Err(FrictionError::LiftOff {
            angle: problem.theta0,
            reaction: 2.0 * h * (problem.t0 - c),
        });
    }
    Ok(())
}
