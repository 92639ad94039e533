//! `capstan tension`: the membrane's tension profile on the contact interval (paper section 2).

use capstan_friction::membrane::{
    self, LoadSum, MembraneProblem, PaperSpeedTransform, TensionProfile,
};
use serde::Serialize;

use crate::error::CliError;
use crate::scene::{BeltSpeedRule, MembraneModel, Scene};

/// The membrane problem a scene describes (`friction.mu`, `membrane.*`, `loads.*`).
///
/// With `membrane.model = "infinite"` (Corollary 1) the width and thickness are 1: the problem
/// is Theorem 1 divided by `h l`, `membrane.t0` is the stress `tau0` and the loads are volume
/// densities (paper-notes item 8; [`capstan_friction::membrane::InfiniteMembrane`]).
pub fn membrane_problem(scene: &Scene) -> MembraneProblem {
    let m = &scene.membrane;
    let mut loads = scene.loads.membrane();
    if m.model == MembraneModel::Infinite {
        loads.width = 1.0;
        loads.thickness = 1.0;
    }
    MembraneProblem {
        mu: scene.friction.mu,
        t0: m.t0,
        theta0: m.theta0,
        theta_max: m.theta_max,
        samples: m.samples,
        loads,
    }
}

/// Whether the scene needs more than the built-in loads: `loads.f_t`, `loads.f_n`, or the
/// paper's belt-speed rule with a non-zero speed.
pub fn has_extra_loads(scene: &Scene) -> bool {
    scene.loads.f_t.is_some()
        || scene.loads.f_n.is_some()
        || (scene.membrane.belt_speed_rule == BeltSpeedRule::Paper
            && membrane_problem(scene).loads.speed_tension() != 0.0)
}

/// The tension (Theorem 1; Theorem 2 on cones) or stress (Corollary 1) profile of the scene's
/// membrane: the cheapest exact method without extra loads, else the equilibrium ODE with
/// `loads.f_t`, `loads.f_n` and the paper's speed term (`membrane.belt_speed_rule`).
///
/// # Errors
/// As [`report`].
pub fn membrane_profile(scene: &Scene) -> Result<TensionProfile, CliError> {
    let obstacle = scene.obstacle.build()?;
    let problem = membrane_problem(scene);
    let budget = scene.membrane.budget();
    if !has_extra_loads(scene) {
        return Ok(membrane::tension_profile_within(
            &obstacle, &problem, &budget,
        )?);
    }
    let paper = PaperSpeedTransform {
        speed_tension: match scene.membrane.belt_speed_rule {
            BeltSpeedRule::Paper => problem.loads.speed_tension(),
            BeltSpeedRule::Corrected => 0.0,
        },
    };
    let extra = LoadSum(scene.loads.expression_load()?, paper);
    Ok(membrane::tension_profile_with_load(
        &obstacle, &problem, &budget, &extra,
    )?)
}

/// The tension profile `T(theta)` of the scene's membrane.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TensionReport {
    /// `membrane.samples` evenly spaced angles on `[theta0, theta_max]`, both ends included.
    pub theta: Vec<f64>,
    /// `T(theta)` (`membrane.model = "infinite"`: the tensile stress `tau(theta)`).
    pub tension: Vec<f64>,
    /// `T(theta_max)`.
    pub t_max: f64,
    /// `T(theta_max) / T(theta0)`.
    pub tension_ratio: f64,
    /// `closed-form`, `quadrature` or `ode`.
    pub method: &'static str,
    /// `finite` (Theorem 1; Theorem 2 on cones: `tension` is a force) or `infinite`
    /// (Corollary 1: `tension` is the tensile stress `tau`).
    pub model: MembraneModel,
}

/// Computes the report.
///
/// # Errors
/// Invalid scene values (exit code 2), no limiting equilibrium on the interval (3), or
/// non-convergence (4); see [`capstan_friction::membrane::tension_profile`].
pub fn report(scene: &Scene) -> Result<TensionReport, CliError> {
    let p = membrane_profile(scene)?;
    Ok(TensionReport {
        model: scene.membrane.model,
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
