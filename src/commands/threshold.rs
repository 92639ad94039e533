//! `capstan threshold`: the tension ratio at which the whole contact slides (Slip = 1), and the
//! capstan coefficient of friction it implies.

use std::collections::BTreeMap;
use std::time::Instant;

use capstan_elasticity::contact::{ContactError, ThresholdSettings};
use capstan_friction::membrane::{self, MembraneProblem};
use serde::Serialize;

use crate::commands::accuracy::{AccuracyReport, ErrorEstimate};
use crate::error::CliError;
use crate::problem::Scaled;
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
    /// When the threshold is the fold of the equilibrium path (a 3-D body under unilateral
    /// contact, from ratio 1 by continuation in the ratio): the fold ratio `r*` and its
    /// bracket; absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub run_off: Option<RunOffReport>,
    /// The estimated discretisation error of `threshold_ratio` and `implied_mu`: the difference
    /// to the threshold one grid level coarser ([`crate::commands::accuracy`]); absent with
    /// `output.error_estimate = false` or when the method has no coarser level.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub estimated_error: Option<ErrorEstimate>,
    /// With an accuracy target (`accuracy.tol`): the target, the chosen discretisation, grid
    /// and solver, and every refinement step; absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub accuracy: Option<AccuracyReport>,
}

/// The fold of a 3-D unilateral body's equilibrium path (`run_off` of
/// [`ThresholdReport`]): no equilibrium beyond `fold_ratio` on the path.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunOffReport {
    /// `r*`: the largest ratio the equilibrium path reached before it turned back.
    pub fold_ratio: f64,
    /// `[lower, upper]`: the largest ratio converged at and the smallest the path folded back
    /// before (`below` and `threshold_ratio`); `lower <= r* < upper`.
    pub bracket: [f64; 2],
    /// The other end of the equilibrium range: the path from ratio 1 down towards
    /// `1 / max_ratio` (`1e-4`), the far end pulled less than the near one.
    pub lower_end: LowerEndReport,
}

/// The lower end of a 3-D unilateral body's equilibrium range (`run_off.lower_end` of
/// [`ThresholdReport`]): no equilibrium below `fold_ratio` on the path down from ratio 1.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LowerEndReport {
    /// `r_*`: the smallest ratio the path down reached before it turned back; `null` when it
    /// reached `1 / max_ratio` without a fold.
    pub fold_ratio: Option<f64>,
    /// `[lower, upper]`: the largest ratio the path folded back before and the smallest it
    /// converged at; `lower < r_* <= upper`, at most the threshold tolerance `1e-6` wide
    /// (the smallest ratio step is half of it).
    pub bracket: [f64; 2],
    /// Ratio steps of the run-off down (and its start at ratio 1).
    pub solves: usize,
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
    // the run-off of a 3-D unilateral body spent its budget: name the key
    let run_off_budget = |e| match CliError::from(e) {
        CliError::Contact(e @ ContactError::ContinuationBudgetSpent { .. }) => {
            crate::commands::contact::contact_budget(e, &scene.solver)
        }
        e => e,
    };
    let t = Instant::now();
    let mut problem = scene.build()?;
    let mut accuracy = None;
    let (r, implied_mu, estimated_error) = if let Some(target) = scene.accuracy.target()? {
        // the bisection's own tolerance a tenth of the target's (at most the default 1e-6),
        // bracketed from the rigid-sliding limit where the body has one: 3 solves a step, not
        // the ~22 of a bisection from 1 (whose solves next to the limit spent the Newton budget
        // on the ladder's 113,906-unknown step)
        let settings = ThresholdSettings {
            tolerance: (target.tolerance * 1e-1).min(ThresholdSettings::default().tolerance),
            bracket_at_limit: true,
            ..Default::default()
        };
        let refined = problem.refine_to(&target, |p| {
            let r = p.threshold_with(settings)?;
            let membrane = MembraneProblem {
                theta0: scene.membrane.theta0,
                theta_max: scene.membrane.theta_max,
                t0: 1.0,
                ..Default::default()
            };
            let mu = membrane::infer_mu(&p.body.surface, &membrane, r.ratio)?.mu;
            let q = |v: f64| Scaled::smooth(v, v.abs().max(f64::MIN_POSITIVE));
            let quantities = BTreeMap::from([
                ("threshold_ratio".to_owned(), q(r.ratio)),
                ("implied_mu".to_owned(), q(mu)),
            ]);
            Ok(((r, mu), quantities))
        })?;
        accuracy = AccuracyReport::new(scene, &target, &refined);
        let estimate = AccuracyReport::estimate(&refined);
        let ((r, mu), chosen) = (refined.value, refined.problem);
        problem = chosen;
        (r, mu, Some(estimate))
    } else {
        let r = problem.threshold().map_err(run_off_budget)?;
        let mu = implied_mu(scene, r.ratio)?;
        (r, mu, plain_estimate(scene, &problem, r.ratio, mu)?)
    };
    // a fold: the run-off down from 1 for the other end (3-D unilateral bodies)
    let lower_end = match r.fold {
        Some(_) => problem
            .threshold_lower_end(ThresholdSettings::default())
            .map_err(run_off_budget)?,
        None => None,
    };
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
        grid: [problem.body.n2, problem.body.n3],
        seconds: t.elapsed().as_secs_f64(),
        grid_n1: (scene.body.dimension == 3).then_some(scene.grid.n1),
        run_off: r
            .fold
            .zip(lower_end)
            .map(|(fold_ratio, lower)| RunOffReport {
                fold_ratio,
                bracket: [r.below, r.above],
                lower_end: LowerEndReport {
                    fold_ratio: lower.fold,
                    bracket: lower.bracket,
                    solves: lower.solves,
                },
            }),
        estimated_error,
        accuracy,
    })
}

/// The estimate one grid level coarser (`output.error_estimate`).
fn plain_estimate(
    scene: &Scene,
    problem: &crate::Problem,
    ratio: f64,
    implied_mu: f64,
) -> Result<Option<ErrorEstimate>, CliError> {
    Ok(match problem.coarser()? {
        Some(coarse) if scene.output.error_estimate => {
            let coarse_ratio = coarse.threshold()?.ratio;
            let level = |ratio: f64, mu: f64| {
                BTreeMap::from([
                    ("threshold_ratio".to_owned(), ratio),
                    ("implied_mu".to_owned(), mu),
                ])
            };
            Some(ErrorEstimate::from_levels(
                &level(ratio, implied_mu),
                &level(coarse_ratio, self::implied_mu(scene, coarse_ratio)?),
                coarse.grid(),
            ))
        }
        _ => None,
    })
}

/// The capstan coefficient a threshold ratio implies on the scene's obstacle and contact
/// interval (membrane model, Corollary 1).
fn implied_mu(scene: &Scene, ratio: f64) -> Result<f64, CliError> {
    let obstacle = scene.obstacle.build()?;
    let problem = MembraneProblem {
        theta0: scene.membrane.theta0,
        theta_max: scene.membrane.theta_max,
        t0: 1.0,
        ..Default::default()
    };
    Ok(membrane::infer_mu(&obstacle, &problem, ratio)?.mu)
}

/// Plain text.
pub fn table(r: &ThresholdReport) -> String {
    let estimate = |name: &str| {
        r.estimated_error
            .as_ref()
            .and_then(|e| e.quantities.get(name).copied().flatten())
            .map_or_else(String::new, |e| format!(" +- {e:.1e}"))
    };
    let accuracy = r
        .accuracy
        .as_ref()
        .map_or_else(String::new, AccuracyReport::table);
    // a fold of the equilibrium path: no stick node needed at `below`
    // the limiting equilibrium solved directly (a plane body under unilateral contact): the
    // bracket is the ratio itself
    let direct = r.run_off.is_none()
        && r.below == r.threshold_ratio
        && r.limiting_ratio == Some(r.threshold_ratio);
    let (what, below) = match r.run_off {
        Some(_) => ("the equilibrium path folds back", "last converged ratio"),
        None if direct => (
            "Slip = 1: the full-slip balance along the rigid sliding mode",
            "solved directly at",
        ),
        None => ("Slip = 1", "last ratio with a stick node"),
    };
    let text = format!(
        "threshold tension ratio {:.6}{} ({what}{}), grid {} x {}\n  implied capstan mu {:.6}{} (thick-body mu {})\n  {below} {:.6} (Slip {:.4}); {} solves, {:.2} s\n",
        r.threshold_ratio,
        estimate("threshold_ratio"),
        if r.no_equilibrium_beyond {
            "; no static equilibrium beyond"
        } else {
            ""
        },
        r.grid[0],
        r.grid[1],
        r.implied_mu,
        estimate("implied_mu"),
        r.mu,
        r.below,
        r.slip_fraction_below,
        r.solves,
        r.seconds
    );
    let run_off = r.run_off.as_ref().map_or_else(String::new, |f| {
        let lower = &f.lower_end;
        let below = match lower.fold_ratio {
            Some(fold) => format!(
                "  no equilibrium below r_* = {fold:.6} in [{:.6}, {:.6}] (the path down from ratio 1 folds back there)\n",
                lower.bracket[0], lower.bracket[1]
            ),
            None => format!(
                "  the path down from ratio 1 reached {:.6} without a fold\n",
                lower.bracket[0]
            ),
        };
        format!(
            "  no equilibrium beyond r* = {:.6} in [{:.6}, {:.6}] (the equilibrium path folds back there)\n{below}",
            f.fold_ratio, f.bracket[0], f.bracket[1]
        )
    });
    text + &run_off + &accuracy
}
