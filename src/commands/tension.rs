//! `capstan tension`: the membrane's tension profile on the contact interval (paper section 2).

use capstan_friction::membrane::{self, MembraneProblem};
use serde::Serialize;

use crate::error::CliError;
use crate::scene::Scene;

/// The membrane problem a scene describes (`friction.mu`, `membrane.*`, `loads.*`).
pub fn membrane_problem(scene: &Scene) -> MembraneProblem {
    let m = &scene.membrane;
    MembraneProblem {
        mu: scene.friction.mu,
        t0: m.t0,
        theta0: m.theta0,
        theta_max: m.theta_max,
        samples: m.samples,
        loads: scene.loads.membrane(),
    }
}

/// The tension profile `T(theta)` of the scene's membrane.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TensionReport {
    /// `membrane.samples` evenly spaced angles on `[theta0, theta_max]`, both ends included.
    pub theta: Vec<f64>,
    /// `T(theta)`.
    pub tension: Vec<f64>,
    /// `T(theta_max)`.
    pub t_max: f64,
    /// `T(theta_max) / T(theta0)`.
    pub tension_ratio: f64,
    /// `closed-form`, `quadrature` or `ode`.
    pub method: &'static str,
}

/// Computes the report.
///
/// # Errors
/// Invalid scene values (exit code 2), no limiting equilibrium on the interval (3), or
/// non-convergence (4); see [`capstan_friction::membrane::tension_profile`].
pub fn report(scene: &Scene) -> Result<TensionReport, CliError> {
    let obstacle = scene.obstacle.build()?;
    let p = membrane::tension_profile_within(
        &obstacle,
        &membrane_problem(scene),
        &scene.membrane.budget(),
    )?;
    Ok(TensionReport {
        t_max: p.t_max(),
        tension_ratio: p.tension_ratio(),
        method: p.method.as_str(),
        theta: p.theta,
        tension: p.tension,
    })
}

/// Human-readable table of the report (at most about 13 rows).
pub fn table(r: &TensionReport, scene: &Scene) -> String {
    let m = &scene.membrane;
    let mut s = format!(
        "membrane on {}, mu = {}, T0 = {} on [{:.6}, {:.6}] ({})\n  T_max = {:.12}   T_max/T0 = {:.12}\n\n{:>14} {:>20}\n",
        scene.obstacle.shape,
        scene.friction.mu,
        m.t0,
        m.theta0,
        m.theta_max,
        r.method,
        r.t_max,
        r.tension_ratio,
        "theta",
        "T(theta)"
    );
    let n = r.theta.len();
    let step = n.div_ceil(12).max(1);
    let mut rows: Vec<usize> = (0..n).step_by(step).collect();
    if rows.last() != Some(&(n - 1)) {
        rows.push(n - 1);
    }
    for i in rows {
        s.push_str(&format!("{:>14.8} {:>20.12}\n", r.theta[i], r.tension[i]));
    }
    s
}
