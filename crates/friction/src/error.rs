//! The friction crate's error type.

use capstan_geometry::{GeometryError, Real};

/// What can go wrong in a friction law or a membrane capstan model.
///
/// [`FrictionError::category`] sorts the variants into bad input, no equilibrium (the model's
/// hypotheses fail on the interval) and numerical non-convergence.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum FrictionError {
    /// A parameter is non-finite or outside its allowed range.
    #[error("`{field}` = {value} is outside {allowed}")]
    InvalidParameter {
        /// The parameter's name: a constructor's API parameter (`mu`, `eps`); a scene-level
        /// builder (a registry entry) names the scene key (`friction.cap`). The `capstan`
        /// facade maps API names to scene keys (`mu` -> `friction.mu`).
        field: &'static str,
        /// The offending value.
        value: f64,
        /// The allowed range in words (e.g. `[0, inf)`).
        allowed: &'static str,
    },
    /// A friction law of this name is registered already
    /// ([`crate::registry::register`]).
    #[error("a friction law named `{name}` is registered already")]
    DuplicateLaw {
        /// The name.
        name: &'static str,
    },
    /// `friction.law` names no registered law.
    #[error("`friction.law` = \"{name}\" is not a registered law: expected one of {allowed}")]
    UnknownLaw {
        /// The name asked for.
        name: String,
        /// The registered names.
        allowed: String,
    },
    /// A parameter the computation needs was not given.
    #[error("`{field}` is required: {why}")]
    MissingParameter {
        /// The parameter's name, as in scene files (e.g. `membrane.t_max`).
        field: &'static str,
        /// What needs it.
        why: &'static str,
    },
    /// A parameter was given where the model has no place for it.
    #[error("`{field}` is not supported here: {why}")]
    Unsupported {
        /// The parameter's name, as in scene files (e.g. `loads.f_t`).
        field: &'static str,
        /// Why, and what to do instead.
        why: &'static str,
    },
    /// The obstacle could not be evaluated (invalid parameter, degenerate point, bad expression).
    #[error(transparent)]
    Geometry(#[from] GeometryError),
    /// The contact interval is not convex: the mean curvature is not positive at `angle`.
    #[error(
        "the contact interval is not convex: mean curvature H = {mean_curvature:.6e} <= 0 at theta = {angle:.9}"
    )]
    NonPositiveCurvature {
        /// The first angle `x2` found where `H <= 0`.
        angle: f64,
        /// `H` there.
        mean_curvature: f64,
    },
    /// The normal reaction is negative: the membrane lifts off the obstacle.
    #[error(
        "the membrane lifts off at theta = {angle:.9}: normal reaction {reaction:.6e} < 0 per unit length"
    )]
    LiftOff {
        /// The first angle found where the reaction is negative.
        angle: f64,
        /// The reaction there (force per unit length).
        reaction: f64,
    },
    /// The tension is not positive: the membrane goes slack.
    #[error("the membrane goes slack at theta = {angle:.9}: tension {tension:.6e} <= 0")]
    NonPositiveTension {
        /// The first angle found where `T <= 0`.
        angle: f64,
        /// `T` there.
        tension: f64,
    },
    /// On a cone the developed strip is a straight line only while `|phi| < pi/2` (Theorem 2).
    #[error(
        "Theorem 2 needs |phi| < pi/2 (the developed strip is a straight line): phi = {phi:.9} at theta = {angle:.9}"
    )]
    DevelopmentLimit {
        /// The first angle found where `|phi| >= pi/2`.
        angle: f64,
        /// `phi` there.
        phi: f64,
    },
    /// `T_max / T0 < 1`: no coefficient of friction `mu >= 0` gives a tension that falls.
    #[error("tension ratio T_max/T0 = {ratio:.9} is below 1: no mu >= 0 produces it")]
    TensionRatioBelowOne {
        /// `T_max / T0`.
        ratio: f64,
    },
    /// No coefficient of friction in `[0, mu_limit]` produces the measured tension pair.
    #[error(
        "no mu in [0, {mu_limit}] gives T_max = {t_max:.9}: reachable tensions are [{reachable_min:.9}, {reachable_max:.9}]"
    )]
    NoFrictionCoefficient {
        /// The measured `T_max`.
        t_max: f64,
        /// `T_max` at `mu = 0`.
        reachable_min: f64,
        /// `T_max` at `mu = mu_limit`.
        reachable_max: f64,
        /// The largest `mu` tried.
        mu_limit: f64,
    },
    /// `T_max(mu)` is not increasing, so the inverse problem is not well posed on the bracket.
    #[error("T_max(mu) is not increasing between mu = {mu_low} and mu = {mu_high}")]
    NotMonotone {
        /// Lower end.
        mu_low: f64,
        /// Upper end.
        mu_high: f64,
    },
    /// A value that must be finite is not (overflowing tension, non-finite integrand).
    #[error("{what} is not finite at theta = {angle:.9}")]
    NonFinite {
        /// Which quantity.
        what: &'static str,
        /// Where.
        angle: f64,
    },
    /// The ODE integrator's step size fell below its floor: `membrane.min_step`, or round-off
    /// (`10 eps |t|`) when that is larger.
    #[error(
        "ODE step size {step:.3e} fell below the minimum step {min_step:.3e} at t = {at:.9} (`membrane.min_step`, or round-off at t): the equilibrium is stiff or singular there; lower `membrane.min_step` (0: round-off only) or end the interval before t"
    )]
    StepSizeTooSmall {
        /// Where it stalled.
        at: f64,
        /// The step size.
        step: f64,
        /// The floor it fell below.
        min_step: f64,
    },
    /// The ODE integrator needed more steps than its budget `membrane.max_steps`.
    #[error(
        "ODE integration ran out of its work budget: `membrane.max_steps` = {max_steps} steps reached at t = {at:.9}; raise `membrane.max_steps` (e.g. --set membrane.max_steps={suggested}) or shorten the interval"
    )]
    TooManySteps {
        /// Where it stopped.
        at: f64,
        /// The limit.
        max_steps: usize,
        /// A larger budget to try (ten times the limit).
        suggested: usize,
    },
    /// Adaptive quadrature did not reach its tolerance within its panel budget
    /// `membrane.max_subdivisions` (or a panel could not be split further).
    #[error(
        "quadrature on [{a:.9}, {b:.9}] did not converge: error estimate {error:.3e} after {panels} panels (work budget `membrane.max_subdivisions` = {limit}); raise `membrane.max_subdivisions` if the profile is smooth there, otherwise end the interval before its singular point"
    )]
    QuadratureNotConverged {
        /// Lower limit.
        a: f64,
        /// Upper limit.
        b: f64,
        /// The final error estimate.
        error: f64,
        /// Panels used.
        panels: usize,
        /// The panel budget (`membrane.max_subdivisions`).
        limit: usize,
    },
    /// A bracketing root finder did not converge within `membrane.max_root_iterations`.
    #[error(
        "root finding ran out of its work budget: `membrane.max_root_iterations` = {iterations} iterations reached (bracket width {width:.3e}); raise `membrane.max_root_iterations`"
    )]
    RootNotConverged {
        /// Iterations done.
        iterations: usize,
        /// Final bracket width.
        width: f64,
    },
    /// The membrane displacement model's Newton iteration did not converge within
    /// `membrane.max_newton_iterations`.
    #[error(
        "membrane Newton ran out of its work budget: `membrane.max_newton_iterations` = {iterations} iterations reached at residual {residual:.3e}; raise `membrane.max_newton_iterations`"
    )]
    NewtonNotConverged {
        /// Iterations done.
        iterations: usize,
        /// The residual then (max norm).
        residual: f64,
    },
    /// The return map onto an orthotropic friction ellipse did not converge (its multiplier's
    /// Newton iteration, budget
    /// [`crate::exact_orthotropic_coulomb::ELLIPSE_MAX_ITERATIONS`]).
    #[error(
        "the projection onto the friction ellipse did not converge in {iterations} iterations (residual {residual:.3e})"
    )]
    ProjectionNotConverged {
        /// Iterations done.
        iterations: usize,
        /// The residual then.
        residual: f64,
    },
    /// `friction.law` names a nonsmooth law where only smooth (pointwise traction) laws are
    /// solved, or a smooth law where a nonsmooth one is needed.
    #[error("`friction.law` = \"{name}\" is {kind}: {hint}")]
    WrongLawKind {
        /// The law asked for.
        name: String,
        /// `"a nonsmooth law (a projection, no eps)"` or `"a smooth law"`.
        kind: &'static str,
        /// What solves it instead.
        hint: &'static str,
    },
    /// Every node of a membrane held by two end tensions slides: no static equilibrium (the
    /// tension ratio exceeds what friction can hold, the capstan ratio of the interval).
    #[error(
        "the membrane slides as a whole on [{theta0:.9}, {theta1:.9}]: no static equilibrium for these end tensions (their ratio exceeds the capstan ratio)"
    )]
    RigidSliding {
        /// Start of the contact interval.
        theta0: f64,
        /// End of the contact interval.
        theta1: f64,
    },
    /// The semismooth Newton iteration of the membrane displacement model did not converge
    /// within `membrane.max_newton_iterations`.
    #[error(
        "membrane semismooth Newton ran out of its work budget: `membrane.max_newton_iterations` = {iterations} iterations reached at residual {residual:.3e} ({changes} stick/slip changes in the last step); raise `membrane.max_newton_iterations`"
    )]
    SemismoothNotConverged {
        /// Iterations done.
        iterations: usize,
        /// The residual then (max norm).
        residual: f64,
        /// Nodes whose stick/slip state changed in the last step.
        changes: usize,
    },
}

/// The three kinds of failure, for callers that map errors to exit codes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum ErrorCategory {
    /// A parameter is invalid or missing, or the obstacle cannot be evaluated.
    InvalidInput,
    /// The model's hypotheses fail (non-convex interval, lift-off, slack membrane, no `mu`):
    /// no limiting equilibrium of this kind exists.
    NoEquilibrium,
    /// A numerical method did not converge.
    NotConverged,
}

impl FrictionError {
    /// Which kind of failure this is.
    pub fn category(&self) -> ErrorCategory {
        match self {
            Self::InvalidParameter { .. }
            | Self::MissingParameter { .. }
            | Self::Unsupported { .. }
            | Self::DuplicateLaw { .. }
            | Self::UnknownLaw { .. }
            | Self::WrongLawKind { .. }
            | Self::Geometry(_) => ErrorCategory::InvalidInput,
            Self::NonPositiveCurvature { .. }
            | Self::LiftOff { .. }
            | Self::NonPositiveTension { .. }
            | Self::DevelopmentLimit { .. }
            | Self::TensionRatioBelowOne { .. }
            | Self::NoFrictionCoefficient { .. }
            | Self::NotMonotone { .. }
            | Self::RigidSliding { .. } => ErrorCategory::NoEquilibrium,
            Self::NonFinite { .. }
            | Self::StepSizeTooSmall { .. }
            | Self::TooManySteps { .. }
            | Self::QuadratureNotConverged { .. }
            | Self::RootNotConverged { .. }
            | Self::NewtonNotConverged { .. }
            | Self::ProjectionNotConverged { .. }
            | Self::SemismoothNotConverged { .. } => ErrorCategory::NotConverged,
        }
    }
}

/// Checks that `value` is finite and in the range described by `ok`: the validation of a
/// scene parameter (`field` is its scene key, `allowed` the range in words).
///
/// # Errors
/// [`FrictionError::InvalidParameter`] naming `field`, the value and `allowed`.
pub fn check(
    field: &'static str,
    value: f64,
    allowed: &'static str,
    ok: impl Fn(f64) -> bool,
) -> Result<f64, FrictionError> {
    if value.is_finite() && ok(value) {
        Ok(value)
    } else {
        Err(FrictionError::InvalidParameter {
            field,
            value,
            allowed,
        })
    }
}

/// [`check`] of the wrap interval `[theta0, theta_max]` (`membrane.theta0` finite,
/// `membrane.theta_max > membrane.theta0`) and of the sample count `samples` in
/// `[min_samples, max_samples]` (`allowed` says that range in words).
///
/// # Errors
/// [`FrictionError::InvalidParameter`] naming the first bad key.
pub(crate) fn check_wrap(
    theta0: f64,
    theta_max: f64,
    samples: usize,
    (min_samples, max_samples, allowed): (f64, f64, &'static str),
) -> Result<(), FrictionError> {
    check("membrane.theta0", theta0, "(-inf, inf)", |_| true)?;
    check(
        "membrane.theta_max",
        theta_max,
        "(membrane.theta0, inf)",
        |v| v > theta0,
    )?;
    check("membrane.samples", samples as f64, allowed, |v| {
        (min_samples..=max_samples).contains(&v)
    })?;
    Ok(())
}

/// The value as `f64` for [`check`] (NaN when it does not convert, which `check` refuses).
pub(crate) fn to_f64<F: Real>(x: F) -> f64 {
    x.to_f64().unwrap_or(f64::NAN)
}

/// [`check`] of a law's parameter `field` that is finite and `>= 0` (a coefficient, a bound).
///
/// # Errors
/// [`FrictionError::InvalidParameter`] naming `field`.
pub(crate) fn check_non_negative<F: Real>(
    field: &'static str,
    value: F,
) -> Result<(), FrictionError> {
    check(field, to_f64(value), "[0, inf)", |v| v >= 0.0).map(drop)
}

/// [`check`] of `friction.eps`, a law's regularisation width: finite and `> 0`.
///
/// # Errors
/// [`FrictionError::InvalidParameter`] naming `eps`.
pub(crate) fn check_width<F: Real>(eps: F) -> Result<(), FrictionError> {
    check("eps", to_f64(eps), "(0, inf)", |v| v > 0.0).map(drop)
}

/// [`GeometryError::Degenerate`] of a profile point a membrane model integrates over: `what`
/// fails at the chart point `at`.
pub(crate) fn degenerate(what: &'static str, at: [f64; 3]) -> FrictionError {
    FrictionError::Geometry(GeometryError::Degenerate { what, at })
}
