//! The membrane on any provided [`Obstacle`]: the cheapest exact method for each, and the
//! inverse problem (the coefficient of friction implied by a tension pair).

use std::f64::consts::FRAC_PI_2;

use capstan_geometry::{Obstacle, ProfileCurve};

use super::budget::MembraneBudget;
use super::closed_form::{
    CylinderGravity, ellipse_turning_angle, right_circular_cone_exponent, right_circular_cone_phi,
};
use super::cone::{ConeMembrane, validate_cone_problem};
use super::equilibrium::MembraneEquilibrium;
use super::load_field::LoadField;
use super::prism::{PrismMembrane, check_speed};
use super::problem::{MembraneProblem, Method, TensionProfile, exp_tension};
use super::turning_angle::{ProfilePoint, turning_angles_within};
use super::validity::{first_failure, grid, merged};
use crate::error::{FrictionError, check};
use crate::root::Brent;

/// The tension profile of a membrane on `obstacle` (Hypothesis 1; Theorems 1 and 2).
///
/// Chooses the cheapest exact method:
/// - closed form: cylinder and ellipse without weight, cylinder with weight (eq. capGrav),
///   right circular cone;
/// - quadrature of the exponent (log-tension): expression prisms without weight, general cones;
/// - ODE: ellipses and expression prisms with weight.
///
/// A user prism or cone ([`Obstacle::prism_over`], [`Obstacle::cone_over`]) takes the general
/// method of its class, as expression prisms and cones do; a general user surface is refused.
///
/// Steady speed without weight is closed form on every prism: `T = c + (T0 - c) exp(mu dPsi)`.
///
/// # Errors
/// Invalid parameters (naming scene keys); [`FrictionError::NonPositiveCurvature`],
/// [`FrictionError::LiftOff`], [`FrictionError::NonPositiveTension`],
/// [`FrictionError::DevelopmentLimit`] naming the first bad angle; non-convergence.
///
/// # Example
/// ```
/// use capstan_friction::membrane::{MembraneProblem, Method, tension_profile};
/// use capstan_geometry::{CircularCylinder, Obstacle};
/// let cylinder = Obstacle::Cylinder(CircularCylinder::new(1.0).unwrap());
/// let problem = MembraneProblem { mu: 0.25, theta0: 0.0, theta_max: std::f64::consts::PI, ..Default::default() };
/// let p = tension_profile(&cylinder, &problem).unwrap();
/// assert_eq!(p.method, Method::ClosedForm);
/// assert!((p.tension_ratio() - (0.25 * std::f64::consts::PI).exp()).abs() < 1e-15);
/// ```
pub fn tension_profile(
    obstacle: &Obstacle,
    problem: &MembraneProblem,
) -> Result<TensionProfile, FrictionError> {
    tension_profile_within(obstacle, problem, &MembraneBudget::default())
}

/// [`tension_profile`] within `budget` (the scene keys `membrane.max_subdivisions`,
/// `membrane.max_steps`, `membrane.min_step`).
///
/// # Errors
/// As [`tension_profile`]; [`FrictionError::QuadratureNotConverged`],
/// [`FrictionError::TooManySteps`], [`FrictionError::StepSizeTooSmall`] when a budget runs out,
/// each naming its scene key.
pub fn tension_profile_within(
    obstacle: &Obstacle,
    problem: &MembraneProblem,
    budget: &MembraneBudget,
) -> Result<TensionProfile, FrictionError> {
    problem.validate()?;
    budget.validate()?;
    let weighted = problem.loads.weight_per_length() != 0.0;
    let c = problem.loads.speed_tension();
    let thetas = problem.thetas();
    let closed = |psi: &dyn Fn(f64) -> f64, h0: f64| -> Result<TensionProfile, FrictionError> {
        check_speed(problem, || Ok(h0))?;
        let base = psi(problem.theta0);
        let tension = thetas
            .iter()
            .map(|&t| exp_tension(problem.t0, c, problem.mu * (psi(t) - base), t))
            .collect::<Result<_, _>>()?;
        Ok(TensionProfile {
            theta: thetas.clone(),
            tension,
            method: Method::ClosedForm,
        })
    };
    match obstacle {
        Obstacle::Plane(_) => Err(FrictionError::NonPositiveCurvature {
            angle: problem.theta0,
            mean_curvature: 0.0,
        }),
        Obstacle::Cylinder(cyl) if weighted => cylinder_with_weight(cyl.radius(), problem),
        Obstacle::Cylinder(cyl) => closed(&|t| t, 0.5 / cyl.radius()),
        Obstacle::Ellipse(e) if !weighted => {
            let h0 = ProfilePoint::from_jet(e.profile_jet(problem.theta0)).mean_curvature;
            closed(&|t| ellipse_turning_angle(e.a(), e.b(), t), h0)
        }
        Obstacle::Ellipse(e) => MembraneEquilibrium::new(e, *problem)
            .with_budget(budget)
            .solve(),
        Obstacle::CircularCone(cone) => {
            validate_cone_problem(problem)?;
            let alpha = cone.half_angle();
            check_cone_development(alpha, problem.theta0, problem.theta_max)?;
            let tension = thetas
                .iter()
                .map(|&t| {
                    let x = problem.mu * right_circular_cone_exponent(alpha, problem.theta0, t);
                    exp_tension(problem.t0, 0.0, x, t)
                })
                .collect::<Result<_, _>>()?;
            Ok(TensionProfile {
                theta: thetas,
                tension,
                method: Method::ClosedForm,
            })
        }
        Obstacle::Prism(_)
        | Obstacle::Cone(_)
        | Obstacle::UserPrism(_)
        | Obstacle::UserCone(_)
        | Obstacle::UserSurface(_) => general_method(obstacle, problem, budget),
    }
}

/// Theorem 1 on a prism (quadrature of the exponent, or the ODE with weight) or Theorem 2 on
/// a cone, over the obstacle's profile curve: the general method of its class.
fn general_method(
    obstacle: &Obstacle,
    problem: &MembraneProblem,
    budget: &MembraneBudget,
) -> Result<TensionProfile, FrictionError> {
    let profile = obstacle.profile().ok_or_else(not_prism_or_cone)?;
    if obstacle.is_prism() {
        PrismMembrane::new(&profile).tension_profile_within(problem, budget)
    } else {
        ConeMembrane::new(&profile)
            .with_max_subdivisions(budget.max_subdivisions)
            .tension_profile(problem)
    }
}

/// The membrane models (Theorems 1 and 2) need a prism or a cone.
fn not_prism_or_cone() -> FrictionError {
    FrictionError::MissingParameter {
        field: "obstacle.shape",
        why: "the membrane models need a prism or a cone; this obstacle is a general surface",
    }
}

/// [`tension_profile_within`] with an extra load field along the membrane (Theorem 1 with
/// any `(0, g_r2, g_r3)`, e.g. [`ExpressionLoad`](super::ExpressionLoad)), on prisms.
///
/// # Math
/// The equilibrium ODE of [`MembraneEquilibrium`] with the problem's weight and steady speed
/// plus `extra`, integrated by Dormand–Prince 8(5,3) to `1e-13`:
/// `dT/dx2 = mu sqrt(a_22) (kappa (T - rho_l V^2) - g_r3) - g_r2`.
///
/// # Errors
/// As [`tension_profile_within`]; [`FrictionError::Unsupported`] on a cone (Theorem 2 has no
/// external load: the strip follows a geodesic, not an `x2` line) and on the plane.
pub fn tension_profile_with_load<L: LoadField + ?Sized>(
    obstacle: &Obstacle,
    problem: &MembraneProblem,
    budget: &MembraneBudget,
    extra: &L,
) -> Result<TensionProfile, FrictionError> {
    problem.validate()?;
    budget.validate()?;
    if obstacle.is_prism() {
        return MembraneEquilibrium::new(obstacle, *problem)
            .with_budget(budget)
            .solve_with(extra)
            .map(|(profile, _)| profile);
    }
    match obstacle {
        Obstacle::Plane(_) => Err(FrictionError::NonPositiveCurvature {
            angle: problem.theta0,
            mean_curvature: 0.0,
        }),
        _ if obstacle.is_cone() => Err(FrictionError::Unsupported {
            field: "loads.f_t, loads.f_n, membrane.belt_speed_rule",
            why: "Theorem 2 (cones) takes no external load or steady speed: the strip follows a geodesic, not an x2 line; use a prism obstacle",
        }),
        _ => Err(FrictionError::Unsupported {
            field: "obstacle.shape",
            why: "a general surface has no profile curve: the membrane models need a prism or a cone",
        }),
    }
}

/// `|phi| = |sin(alpha) theta| < pi/2` on `[theta0, theta_max]` for the right circular cone.
fn check_cone_development(alpha: f64, theta0: f64, theta_max: f64) -> Result<(), FrictionError> {
    let limit = FRAC_PI_2 / alpha.sin();
    let angle = if theta0 <= -limit {
        Some(theta0)
    } else if theta_max >= limit {
        Some(limit.max(theta0))
    } else {
        None
    };
    match angle {
        Some(angle) => Err(FrictionError::DevelopmentLimit {
            angle,
            phi: right_circular_cone_phi(alpha, angle),
        }),
        None => Ok(()),
    }
}

/// Eq. capGrav (generalised to `theta0` and steady speed) with its lift-off and slack checks.
fn cylinder_with_weight(
    radius: f64,
    problem: &MembraneProblem,
) -> Result<TensionProfile, FrictionError> {
    let cg = CylinderGravity {
        radius,
        mu: problem.mu,
        weight_per_length: problem.loads.weight_per_length(),
        speed_tension: problem.loads.speed_tension(),
    };
    let tension_at = |t: f64| cg.tension(problem.t0, problem.theta0, t);
    let thetas = problem.thetas();
    // R and T are smooth: 64 checks per radian resolve every sign change.
    let n = ((problem.theta_max - problem.theta0) * 64.0).ceil() as usize;
    let checks = merged(grid(problem.theta0, problem.theta_max, n.max(16)), &thetas);
    let failure = first_failure(&checks, |t| {
        let tension = tension_at(t);
        let r = cg.reaction(t, tension);
        let scale = (tension.abs() + cg.speed_tension) / radius + cg.weight_per_length;
        Ok(tension > 0.0 && r >= -1e-12 * scale)
    })?;
    if let Some(angle) = failure {
        let tension = tension_at(angle);
        return Err(if tension <= 0.0 {
            FrictionError::NonPositiveTension { angle, tension }
        } else {
            FrictionError::LiftOff {
                angle,
                reaction: cg.reaction(angle, tension),
            }
        });
    }
    let tension: Vec<f64> = thetas.iter().map(|&t| tension_at(t)).collect();
    if let Some(i) = tension.iter().position(|t| !t.is_finite()) {
        return Err(FrictionError::NonFinite {
            what: "tension (overflow)",
            angle: thetas[i],
        });
    }
    Ok(TensionProfile {
        theta: thetas,
        tension,
        method: Method::ClosedForm,
    })
}

/// The coefficient of friction implied by a tension pair, and how it was found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionEstimate {
    /// The implied `mu`.
    pub mu: f64,
    /// The method of the forward model that was inverted.
    pub method: Method,
}

/// The `mu = 1` exponent `E` with `ln((T - c)/(T0 - c)) = mu E` when no weight acts.
fn unit_exponent(
    obstacle: &Obstacle,
    problem: &MembraneProblem,
    budget: &MembraneBudget,
) -> Result<(f64, Method), FrictionError> {
    let (t0, t1) = (problem.theta0, problem.theta_max);
    Ok(match obstacle {
        Obstacle::Plane(_) => {
            return Err(FrictionError::NonPositiveCurvature {
                angle: t0,
                mean_curvature: 0.0,
            });
        }
        Obstacle::Cylinder(_) => (t1 - t0, Method::ClosedForm),
        Obstacle::Ellipse(e) => (
            ellipse_turning_angle(e.a(), e.b(), t1) - ellipse_turning_angle(e.a(), e.b(), t0),
            Method::ClosedForm,
        ),
        Obstacle::CircularCone(cone) => {
            check_cone_development(cone.half_angle(), t0, t1)?;
            (
                right_circular_cone_exponent(cone.half_angle(), t0, t1),
                Method::ClosedForm,
            )
        }
        Obstacle::Prism(_)
        | Obstacle::Cone(_)
        | Obstacle::UserPrism(_)
        | Obstacle::UserCone(_)
        | Obstacle::UserSurface(_) => {
            let profile = obstacle.profile().ok_or_else(not_prism_or_cone)?;
            let e = if obstacle.is_prism() {
                turning_angles_within(&profile, t0, &[t1], budget.max_subdivisions)?[0]
            } else {
                ConeMembrane::new(&profile)
                    .with_max_subdivisions(budget.max_subdivisions)
                    .exponents(t0, &[t1])?[0]
            };
            (e, Method::Quadrature)
        }
    })
}

/// The coefficient of friction `mu` for which the membrane, held at `T0 = problem.t0` at
/// `theta0`, is at limiting equilibrium with tension `t_max` at `theta_max` (`problem.mu` is
/// ignored).
///
/// # Math
/// Without weight (steady speed allowed, `c = rho_l V^2`):
/// `mu = ln((T_max - c)/(T0 - c)) / E`, `E = Psi(theta_max) - Psi(theta0)` on prisms and
/// Theorem 2's exponent on cones; e.g. `ln(2.75)/pi = 0.322` for a half wrap of a circle.
/// With weight, `T_max(mu)` is increasing (`dT_mu/ds = mu kappa T_mu + R`, `R >= 0`); the root of
/// `T_max(mu) = t_max` is bracketed by doubling `mu` (monotonicity checked on the way) and
/// found by Brent's method.
///
/// # Errors
/// [`FrictionError::InvalidParameter`] for `membrane.t_max` or other bad parameters;
/// [`FrictionError::TensionRatioBelowOne`] (no weight, `T_max < T0`);
/// [`FrictionError::NoFrictionCoefficient`] if no `mu >= 0` reaches `t_max`;
/// [`FrictionError::NotMonotone`]; forward-model errors.
///
/// # Example
/// ```
/// use capstan_friction::membrane::{MembraneProblem, infer_mu};
/// use capstan_geometry::{CircularCylinder, Obstacle};
/// let circle = Obstacle::Cylinder(CircularCylinder::new(1.0).unwrap());
/// let half_wrap = MembraneProblem { theta0: 0.0, theta_max: std::f64::consts::PI, ..Default::default() };
/// let mu = infer_mu(&circle, &half_wrap, 2.75).unwrap().mu;
/// assert!((mu - 0.322_002_571_059_795_8).abs() < 1e-15);
/// ```
pub fn infer_mu(
    obstacle: &Obstacle,
    problem: &MembraneProblem,
    t_max: f64,
) -> Result<FrictionEstimate, FrictionError> {
    infer_mu_within(obstacle, problem, t_max, &MembraneBudget::default())
}

/// [`infer_mu`] within `budget` (the forward model's budgets and
/// `membrane.max_root_iterations`).
///
/// # Errors
/// As [`infer_mu`]; [`FrictionError::RootNotConverged`] when the root finder's budget runs out.
pub fn infer_mu_within(
    obstacle: &Obstacle,
    problem: &MembraneProblem,
    t_max: f64,
    budget: &MembraneBudget,
) -> Result<FrictionEstimate, FrictionError> {
    problem.validate()?;
    budget.validate()?;
    check("membrane.t_max", t_max, "(0, inf)", |v| v > 0.0)?;
    let t0 = problem.t0;
    if obstacle.is_cone() {
        validate_cone_problem(problem)?;
    }
    if problem.loads.weight_per_length() == 0.0 {
        let c = problem.loads.speed_tension();
        if t_max < t0 {
            return Err(FrictionError::TensionRatioBelowOne { ratio: t_max / t0 });
        }
        let (e, method) = unit_exponent(obstacle, problem, budget)?;
        if t0 < c {
            let h0 = match obstacle.profile_jet(problem.theta0) {
                Some(jet) => ProfilePoint::from_jet(jet).mean_curvature,
                None => 0.0,
            };
            check_speed(problem, || Ok(h0))?;
        }
        if t0 == c {
            // T = c everywhere, whatever mu: only T_max = c is reachable.
            return Err(FrictionError::NoFrictionCoefficient {
                t_max,
                reachable_min: c,
                reachable_max: c,
                mu_limit: f64::INFINITY,
            });
        }
        let mu = ((t_max - c) / (t0 - c)).ln() / e;
        return Ok(FrictionEstimate { mu, method });
    }
    // With weight: bracket and solve T_max(mu) = t_max.
    let end = |mu: f64| -> Result<(f64, Method), FrictionError> {
        let p = tension_profile_within(
            obstacle,
            &MembraneProblem {
                mu,
                samples: 2,
                ..*problem
            },
            budget,
        )?;
        Ok((p.t_max(), p.method))
    };
    let (f0, method) = end(0.0)?;
    if t_max < f0 {
        return Err(FrictionError::NoFrictionCoefficient {
            t_max,
            reachable_min: f0,
            reachable_max: f0,
            mu_limit: 0.0,
        });
    }
    let span = problem.theta_max - problem.theta0;
    let (mut lo, mut f_lo) = (0.0, f0);
    let mut hi = 0.25;
    loop {
        let (f_hi, _) = end(hi)?;
        if f_hi < f_lo {
            return Err(FrictionError::NotMonotone {
                mu_low: lo,
                mu_high: hi,
            });
        }
        if f_hi >= t_max {
            let mu = Brent {
                x_tol: 1e-14,
                max_iterations: budget.max_root_iterations,
            }
            .solve(
                |mu| Ok(end(mu)?.0 - t_max),
                lo,
                f_lo - t_max,
                hi,
                f_hi - t_max,
            )?;
            return Ok(FrictionEstimate { mu, method });
        }
        // Stop before exp(mu * turning) could overflow.
        if hi * span.abs().max(1.0) > 300.0 {
            return Err(FrictionError::NoFrictionCoefficient {
                t_max,
                reachable_min: f0,
                reachable_max: f_hi,
                mu_limit: hi,
            });
        }
        (lo, f_lo) = (hi, f_hi);
        hi *= 2.0;
    }
}
