//! The membrane equilibrium ODE along `x2`, built from the geometry layer.

use capstan_geometry::{Surface, SurfaceGeometry};

use super::budget::MembraneBudget;
use super::load_field::{Gravity, LoadField, NoLoad};
use super::problem::{MembraneProblem, Method, TensionProfile};
use super::validity::{first_failure, merged};
use crate::error::FrictionError;
use crate::ode::{Dop853, OdeSolution};

/// The membrane's equilibrium along the `x2` coordinate line of a surface, integrated with
/// Dormand–Prince 8(5,3) from `Surface::geometry` (fundamental forms and normal), with the
/// problem's gravity and steady speed plus any extra [`LoadField`].
///
/// # Math
/// Per unit arclength `s` (unit tangent `t`, outward normal `N`, normal curvature
/// `kappa = -b_22/a_22` of the `x2` line, load `q` per unit length, line density `rho_l`,
/// steady speed `V`, acceleration `-V^2 kappa N` normal to the path):
/// ```text
/// R     = kappa (T - rho_l V^2) - q . N         normal reaction (>= 0, else lift-off)
/// dT/ds = mu R - q . t                          friction opposes slip towards theta_max
/// ```
/// With `ds = sqrt(a_22) dx2`, `g_r2 = q . a_2`, `g_r3 = q . N`:
/// `dT/dx2 = mu sqrt(a_22) (kappa (T - rho_l V^2) - g_r3) - g_r2` (eq. PrismEqn02 with the
/// corrected steady transform, paper-notes item 4). On a prism `x2` lines are the profile and
/// `kappa = 2H`; on other surfaces this is the tension along the `x2` line held on it.
///
/// # Errors
/// See [`MembraneEquilibrium::solve_with`].
#[derive(Debug, Clone, Copy)]
pub struct MembraneEquilibrium<'a, S: ?Sized> {
    surface: &'a S,
    problem: MembraneProblem,
    x1: f64,
    ode: Dop853<f64>,
}

/// The local coefficients of the equilibrium at one angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalEquilibrium {
    /// `sqrt(a_22)`.
    pub sqrt_a22: f64,
    /// `kappa = -b_22 / a_22`.
    pub curvature: f64,
    /// Mean curvature `H`.
    pub mean_curvature: f64,
    /// `[g_r2, g_r3]` of all loads.
    pub load: [f64; 2],
}

impl<'a, S: Surface<f64> + ?Sized> MembraneEquilibrium<'a, S> {
    /// The equilibrium of `problem` on `surface` along `x1 = 0`, with tolerances `1e-13`.
    pub fn new(surface: &'a S, problem: MembraneProblem) -> Self {
        let tol = 1e-13;
        Self {
            surface,
            problem,
            x1: 0.0,
            ode: Dop853 {
                rel_tol: tol,
                abs_tol: tol * problem.t0.abs().max(f64::MIN_POSITIVE),
                ..Default::default()
            },
        }
    }
    /// The same within `budget` (`membrane.max_steps`, `membrane.min_step`).
    pub fn with_budget(self, budget: &MembraneBudget) -> Self {
        let ode = Dop853 {
            max_steps: budget.max_steps,
            min_step: budget.min_step,
            ..self.ode
        };
        Self { ode, ..self }
    }
    /// The same along `x1 = x1`.
    pub fn at_x1(self, x1: f64) -> Self {
        Self { x1, ..self }
    }
    /// The same with other integrator settings.
    pub fn with_ode(self, ode: Dop853<f64>) -> Self {
        Self { ode, ..self }
    }

    fn geometry(&self, theta: f64) -> Result<SurfaceGeometry<f64>, FrictionError> {
        Ok(self.surface.geometry([self.x1, theta])?)
    }

    /// The local coefficients at `theta` with an extra load.
    ///
    /// # Errors
    /// A geometry error at `theta`.
    pub fn local<L: LoadField + ?Sized>(
        &self,
        theta: f64,
        extra: &L,
    ) -> Result<LocalEquilibrium, FrictionError> {
        let g = self.geometry(theta)?;
        let a22 = g.first_form[1][1];
        let gravity = Gravity {
            weight_per_length: self.problem.loads.weight_per_length(),
        }
        .load(theta, &g);
        let more = extra.load(theta, &g);
        Ok(LocalEquilibrium {
            sqrt_a22: a22.sqrt(),
            curvature: -g.second_form[1][1] / a22,
            mean_curvature: g.mean_curvature,
            load: [gravity[0] + more[0], gravity[1] + more[1]],
        })
    }

    /// `(dT/dx2, R)` at `theta` for tension `t`.
    fn rates(&self, l: &LocalEquilibrium, t: f64) -> (f64, f64) {
        let c = self.problem.loads.speed_tension();
        let reaction = l.curvature * (t - c) - l.load[1];
        (
            self.problem.mu * l.sqrt_a22 * reaction - l.load[0],
            reaction,
        )
    }

    /// The tension profile with the problem's loads only.
    ///
    /// # Errors
    /// See [`MembraneEquilibrium::solve_with`].
    pub fn solve(&self) -> Result<TensionProfile, FrictionError> {
        self.solve_with(&NoLoad).map(|(p, _)| p)
    }

    /// The tension profile with an extra load field, and the ODE solution (dense output).
    ///
    /// # Errors
    /// [`FrictionError::InvalidParameter`] for a bad problem;
    /// [`FrictionError::NonPositiveCurvature`] where `kappa <= 0` on the interval;
    /// [`FrictionError::LiftOff`] where `R < 0`; [`FrictionError::NonPositiveTension`] where
    /// `T <= 0`; geometry and integrator errors.
    pub fn solve_with<L: LoadField + ?Sized>(
        &self,
        extra: &L,
    ) -> Result<(TensionProfile, OdeSolution<f64, 1>), FrictionError> {
        let p = &self.problem;
        p.validate()?;
        let mut bad_curvature: Option<f64> = None;
        let solution = self.ode.integrate(
            |theta, y: &[f64; 1]| {
                let l = self.local(theta, extra)?;
                if l.curvature <= 0.0 && bad_curvature.is_none_or(|b| theta < b) {
                    bad_curvature = Some(theta);
                }
                Ok([self.rates(&l, y[0]).0])
            },
            p.theta0,
            [p.t0],
            p.theta_max,
        )?;
        let thetas = p.thetas();
        let checks = merged(solution.times(), &thetas);
        if bad_curvature.is_some() || self.local(p.theta0, extra)?.curvature <= 0.0 {
            let at = first_failure(&checks, |t| Ok(self.local(t, extra)?.curvature > 0.0))?;
            let angle = at.or(bad_curvature).unwrap_or(p.theta0);
            return Err(FrictionError::NonPositiveCurvature {
                angle,
                mean_curvature: self.local(angle, extra)?.mean_curvature,
            });
        }
        let state = |t: f64| -> Result<(f64, f64, f64), FrictionError> {
            let l = self.local(t, extra)?;
            let tension = solution.eval(t)[0];
            let (_, r) = self.rates(&l, tension);
            let scale = l.curvature * (tension.abs() + p.loads.speed_tension()) + l.load[1].abs();
            Ok((tension, r, scale))
        };
        let failure = first_failure(&checks, |t| {
            let (tension, r, scale) = state(t)?;
            Ok(tension > 0.0 && r >= -1e-12 * scale)
        })?;
        if let Some(angle) = failure {
            let (tension, reaction, _) = state(angle)?;
            return Err(if tension <= 0.0 {
                FrictionError::NonPositiveTension { angle, tension }
            } else {
                FrictionError::LiftOff { angle, reaction }
            });
        }
        let tension = thetas.iter().map(|&t| solution.eval(t)[0]).collect();
        Ok((
            TensionProfile {
                theta: thetas,
                tension,
                method: Method::Ode,
            },
            solution,
        ))
    }
}
