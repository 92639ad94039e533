//! `capstan threshold`: the tension ratio at which the whole contact slides (Slip = 1), and the
//! capstan coefficient of friction it implies.

use std::time::Instant;

use capstan_friction::membrane::{self, MembraneProblem};
use serde::Serialize;

use crate::error::CliError;
use crate::scene::Scene;

/// `capstan threshold --json` (keys are a public contract).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ThresholdReport {
    /// `converged`.
    pub status: &'static str,
    /// The threshold ratio `tau_max / tau0` (Slip reaches 1, or no equilibrium beyond).
    pub threshold_ratio: f64,
    /// Largest ratio found with a stick node.
    pub below: f64,
    /// Slip at `below`.
    pub slip_fraction_below: f64,
    /// Whether past the threshold no static solution exists (rigid sliding on a circle).
    pub no_equilibrium_beyond: bool,
    /// The limiting ratio from the rigid-sliding solvability condition, if the body can slide.
    pub limiting_ratio: Option<f64>,
    /// The capstan coefficient implied by the threshold ratio (membrane model, Corollary 1:
    /// `ln(ratio) / Psi`, `Psi` the turning angle of the contact interval).
    pub implied_mu: f64,
    /// `friction.mu` of the thick body.
    pub mu: f64,
    /// Contact solves of the bisection.
    pub solves: usize,
    /// `[n2, n3]`.
    pub grid: [usize; 2],
    /// Wall time, seconds.
    pub seconds: f64,
    /// `grid.n1` of a 3-D body (`body.dimension = 3`); absent in plane strain.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub grid_n1: Option<usize>,
}

/// Computes the report.
///
/// # Errors
/// Bad input (2), including `loads.body_force` (the threshold is a tension ratio of loads
/// linear in the end tractions; a fixed body force makes them affine); non-convergence (4).
pub fn report(scene: &Scene) -> Result<ThresholdReport, CliError> {
    if scene.loads.body_force.is_some() {
        return Err(CliError::Scene {
            origin: "loads.body_force".into(),
            message: "`loads.body_force` is set: the full-slip threshold is a tension ratio of loads linear in the end tractions, and a body force held fixed is not; use `capstan sweep --param loads.tau_max` to follow Slip under the force".into(),
        });
    }
    let t = Instant::now();
    let r = scene.build()?.threshold()?;
    let obstacle = scene.obstacle.build()?;
    let problem = MembraneProblem {
        theta0: scene.membrane.theta0,
        theta_max: scene.membrane.theta_max,
        t0: 1.0,
        ..Default::default()
    };
    let implied_mu = membrane::infer_mu(&obstacle, &problem, r.ratio)?.mu;
    Ok(ThresholdReport {
        status: "converged",
        threshold_ratio: r.ratio,
        below: r.below,
        slip_fraction_below: r.slip_fraction_below,
        no_equilibrium_beyond: r.above_is_no_equilibrium,
        limiting_ratio: r.limiting_ratio,
        implied_mu,
        mu: scene.friction.mu,
        solves: r.solves,
        grid: [scene.grid.n2, scene.grid.n3],
        seconds: t.elapsed().as_secs_f64(),
        grid_n1: (scene.body.dimension == 3).then_some(scene.grid.n1),
    })
}

/// Plain text.
pub fn table(r: &ThresholdReport) -> String {
    format!(
        "threshold tension ratio {:.6} (Slip = 1{}), grid {} x {}\n  implied capstan mu {:.6} (thick-body mu {})\n  last ratio with a stick node {:.6} (Slip {:.4}); {} solves, {:.2} s\n",
        r.threshold_ratio,
        if r.no_equilibrium_beyond {
            "; no static equilibrium beyond"
        } else {
            ""
        },
        r.grid[0],
        r.grid[1],
        r.implied_mu,
        r.mu,
        r.below,
        r.slip_fraction_below,
        r.solves,
        r.seconds
    )
}
