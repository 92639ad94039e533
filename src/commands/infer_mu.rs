//! `capstan infer-mu`: the coefficient of friction implied by a tension pair `{T0, T_max}`.

use capstan_friction::FrictionError;
use capstan_friction::membrane;
use serde::Serialize;

use crate::commands::tension::membrane_problem;
use crate::error::CliError;
use crate::scene::Scene;

/// The implied coefficient of friction.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InferMuReport {
    /// The implied `mu`.
    pub mu: f64,
    /// The forward model that was inverted: `closed-form`, `quadrature` or `ode`.
    pub method: &'static str,
    /// `membrane.t0`.
    pub t0: f64,
    /// `membrane.t_max`.
    pub t_max: f64,
    /// `T_max / T0`.
    pub tension_ratio: f64,
}

/// Computes the report (`friction.mu` is ignored).
///
/// # Errors
/// `membrane.t_max` missing or invalid (exit code 2); a pair no `mu` produces (3);
/// non-convergence (4); see [`capstan_friction::membrane::infer_mu`].
pub fn report(scene: &Scene) -> Result<InferMuReport, CliError> {
    let t_max = scene.membrane.t_max.ok_or(FrictionError::MissingParameter {
        field: "membrane.t_max",
        why: "infer-mu needs the measured tension at theta_max (e.g. --set membrane.t_max=2.75)",
    })?;
    let obstacle = scene.obstacle.build()?;
    let e = membrane::infer_mu(&obstacle, &membrane_problem(scene), t_max)?;
    Ok(InferMuReport {
        mu: e.mu,
        method: e.method.as_str(),
        t0: scene.membrane.t0,
        t_max,
        tension_ratio: t_max / scene.membrane.t0,
    })
}

/// Human-readable summary.
pub fn table(r: &InferMuReport, scene: &Scene) -> String {
    format!(
        "membrane on {:?} over [{:.6}, {:.6}]: T0 = {}, T_max = {} (ratio {:.9})\n  mu = {:.12}   ({})\n",
        scene.obstacle.shape,
        scene.membrane.theta0,
        scene.membrane.theta_max,
        r.t0,
        r.t_max,
        r.tension_ratio,
        r.mu,
        r.method
    )
}
