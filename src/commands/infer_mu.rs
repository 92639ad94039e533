//! `capstan infer-mu`: the coefficient of friction implied by a tension pair `{T0, T_max}`,
//! under one of three models (`--model capstan|membrane|kikuchi-oden`).

use std::path::PathBuf;

use capstan_elasticity::contact::{
    Body, BoundarySolver, ContactModel, ContactSettings, ThickBody, ThickBodyOperator,
    solve_below_threshold,
};
use capstan_friction::FrictionError;
use capstan_friction::membrane;
use capstan_friction::membrane_displacement::{
    EndCondition, MembraneDisplacement, MembraneDisplacementProblem, MembraneNewton,
};
use capstan_friction::root::Brent;
use capstan_friction::{RegularisedCoulomb, RegularisedCoulombParams};
use capstan_geometry::ProfileCurve;
use clap::{Args, ValueEnum};
use serde::Serialize;

use crate::commands::SceneArgs;
use crate::commands::tension::{extra_loads, has_extra_loads, membrane_problem};
use crate::error::CliError;
use crate::scene::Scene;

/// Arguments of `capstan infer-mu`.
#[derive(Debug, Args, Clone, Default)]
pub struct InferMuArgs {
    /// The scene.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Also write the report as `infer-mu.json` into this directory.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// The model whose coefficient the tension pair implies.
    #[arg(long, value_enum, default_value_t = FrictionModel::Capstan)]
    pub model: FrictionModel,
}

/// The three models of the same experiment (`docs/models.md`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, ValueEnum, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum FrictionModel {
    /// The generalised capstan equation (membrane at limiting equilibrium, section 2).
    #[default]
    Capstan,
    /// The 1-D membrane displacement model under regularised Coulomb friction.
    Membrane,
    /// The thick plane-strain body under Kikuchi–Oden friction (section 3).
    KikuchiOden,
}

impl FrictionModel {
    /// The name on the command line and in JSON.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Capstan => "capstan",
            Self::Membrane => "membrane",
            Self::KikuchiOden => "kikuchi-oden",
        }
    }
}

/// The implied coefficient of friction.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InferMuReport {
    /// The implied `mu` (`mu_F` of the model).
    pub mu: f64,
    /// `capstan`, `membrane` or `kikuchi-oden`.
    pub model: &'static str,
    /// The forward model that was inverted: `closed-form`, `quadrature` or `ode` (capstan),
    /// `membrane-displacement` (Brent), `thick-body` (bisection on full slip).
    pub method: &'static str,
    /// `membrane.t0`.
    pub t0: f64,
    /// `membrane.t_max`.
    pub t_max: f64,
    /// `T_max / T0`.
    pub tension_ratio: f64,
    /// Forward solves of the inversion (membrane, kikuchi-oden; `null` for capstan).
    pub solves: Option<usize>,
    /// `[n2, n3]` of the thick body (kikuchi-oden only).
    pub grid: Option<[usize; 2]>,
}

/// Nodes of the membrane displacement model (grid error about `1e-6` relative on the
/// paper's circle, `docs/models.md`).
pub const MEMBRANE_NODES: usize = 801;

/// Computes the capstan report (`friction.mu` is ignored); see [`report_for`].
///
/// # Errors
/// See [`report_for`].
pub fn report(scene: &Scene) -> Result<InferMuReport, CliError> {
    report_for(scene, FrictionModel::Capstan)
}

/// Computes the report of `model` (`friction.mu` is ignored).
///
/// - `capstan`: [`capstan_friction::membrane::infer_mu`]; with `loads.f_t`, `loads.f_n` or the
///   paper's belt-speed rule, [`capstan_friction::membrane::infer_mu_with_load`] (Brent on
///   the equilibrium ODE).
/// - `membrane`: the `mu` at which the membrane displacement model (stiffness
///   `E h/(1 - nu^2)` from `body.*`, [`MEMBRANE_NODES`] nodes, `friction.eps`), pulled at
///   `theta_max` until every node slides, carries the ratio `T_max / T0` ([`membrane_mu`]).
/// - `kikuchi-oden`: the `mu_F` at which the thick body (`body.*`, `grid.*`, regularised
///   Coulomb with `friction.eps`) with end tractions `tau_max / tau0 = T_max / T0` reaches
///   Slip = 1 ([`kikuchi_oden_mu`]).
///
/// # Errors
/// `membrane.t_max` missing or invalid (exit code 2); a pair no `mu` produces (3);
/// non-convergence (4); see [`capstan_friction::membrane::infer_mu`]. The membrane and
/// kikuchi-oden models need a prism and no membrane loads (2).
pub fn report_for(scene: &Scene, model: FrictionModel) -> Result<InferMuReport, CliError> {
    let t_max = scene.membrane.t_max.ok_or(FrictionError::MissingParameter {
        field: "membrane.t_max",
        why: "infer-mu needs the measured tension at theta_max (e.g. --set membrane.t_max=2.75)",
    })?;
    let obstacle = scene.obstacle.build()?;
    let t0 = scene.membrane.t0;
    let ratio = t_max / t0;
    let extra = has_extra_loads(scene);
    if extra && model != FrictionModel::Capstan {
        return Err(loads_not_in_model(scene));
    }
    let capstan = if extra {
        membrane::infer_mu_with_load(
            &obstacle,
            &membrane_problem(scene),
            t_max,
            &scene.membrane.budget(),
            &extra_loads(scene)?,
        )?
    } else {
        membrane::infer_mu_within(
            &obstacle,
            &membrane_problem(scene),
            t_max,
            &scene.membrane.budget(),
        )?
    };
    let mut r = InferMuReport {
        mu: capstan.mu,
        model: model.as_str(),
        method: capstan.method.as_str(),
        t0,
        t_max,
        tension_ratio: ratio,
        solves: None,
        grid: None,
    };
    if model == FrictionModel::Capstan {
        return Ok(r);
    }
    check_no_loads(scene)?;
    let (theta, eps) = (
        [scene.membrane.theta0, scene.membrane.theta_max],
        scene.friction.eps,
    );
    match model {
        FrictionModel::Capstan => {}
        FrictionModel::Membrane => {
            let profile = crate::commands::membrane_path::membrane_profile(&obstacle)?;
            let b = &scene.body;
            let m = membrane_mu(
                &profile,
                MembraneSetup {
                    theta,
                    stiffness: b.young * b.thickness / (1.0 - b.poisson * b.poisson),
                    eps,
                    nodes: MEMBRANE_NODES,
                    max_newton_iterations: scene.membrane.max_newton_iterations,
                    max_root_iterations: scene.membrane.max_root_iterations,
                },
                ratio,
            )?;
            (r.mu, r.solves) = (m.mu, Some(m.solves));
            r.method = "membrane-displacement";
        }
        FrictionModel::KikuchiOden => {
            // either dimension: the body the scene builds (`body.dimension`)
            let body = scene.build()?.body;
            let k = kikuchi_oden_mu(&body, ratio, eps, capstan.mu, 1e-6)?;
            (r.mu, r.solves) = (k.mu, Some(k.solves));
            r.method = "thick-body";
            r.grid = Some([body.n2, body.n3]);
        }
    }
    Ok(r)
}

/// `loads.f_t`, `loads.f_n` or the paper's belt-speed rule with `--model membrane` or
/// `kikuchi-oden`: only the capstan model carries them.
fn loads_not_in_model(scene: &Scene) -> CliError {
    let key = if scene.loads.f_t.is_some() {
        "loads.f_t"
    } else if scene.loads.f_n.is_some() {
        "loads.f_n"
    } else {
        "membrane.belt_speed_rule"
    };
    CliError::Scene {
        origin: key.into(),
        message: format!(
            "`{key}` is set; only the capstan model (--model capstan) has membrane loads"
        ),
    }
}

/// The membrane and thick-body models carry no body forces and no belt speed.
fn check_no_loads(scene: &Scene) -> Result<(), CliError> {
    let l = &scene.loads;
    if l.body_force.is_some() {
        return Err(CliError::Scene {
            origin: "loads.body_force".into(),
            message: "`loads.body_force` is set; the membrane and kikuchi-oden models invert end tensions alone".into(),
        });
    }
    for (key, v) in [
        ("loads.gravity", l.gravity * l.density),
        ("loads.speed", l.speed),
    ] {
        if v != 0.0 {
            return Err(CliError::Scene {
                origin: key.into(),
                message: format!(
                    "`{key}` is nonzero; only the capstan model (--model capstan) has membrane loads"
                ),
            });
        }
    }
    Ok(())
}

/// The membrane displacement model's data apart from the friction coefficient.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MembraneSetup {
    /// `[theta0, theta_max]`.
    pub theta: [f64; 2],
    /// Axial stiffness `k`.
    pub stiffness: f64,
    /// Regularisation width of the Coulomb law.
    pub eps: f64,
    /// Nodes.
    pub nodes: usize,
    /// Newton iterations per solve (`membrane.max_newton_iterations`).
    pub max_newton_iterations: usize,
    /// Iterations of the root finder (`membrane.max_root_iterations`).
    pub max_root_iterations: usize,
}

/// A coefficient found by inverting a forward model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpliedMu {
    /// The coefficient.
    pub mu: f64,
    /// Forward solves used.
    pub solves: usize,
}

/// The membrane's tension ratio `T(theta_max)/T(theta0)` at friction `mu` when every node
/// slides (`T0 = 1`, the far end pulled; the pull is quadrupled until every `w >= eps`).
///
/// # Errors
/// Bad setup values; non-convergence of the membrane's Newton iteration.
pub fn membrane_ratio<C: ProfileCurve<f64>>(
    profile: &C,
    setup: MembraneSetup,
    mu: f64,
) -> Result<f64, FrictionError> {
    let law = RegularisedCoulombParams::new(mu, setup.eps)?;
    let model = MembraneDisplacement::new(profile, RegularisedCoulomb, law);
    let mut pull = 1.0;
    for _ in 0..40 {
        let problem = MembraneDisplacementProblem {
            theta0: setup.theta[0],
            theta1: setup.theta[1],
            nodes: setup.nodes,
            stiffness: setup.stiffness,
            start: EndCondition::Tension(1.0),
            end: EndCondition::Displacement(pull),
        };
        // -v prints the membrane's Newton iterations (stage `membrane`)
        let mut observer = crate::progress::CliObserver::new();
        let mut report = |iteration: usize, residual: f64, step: f64| {
            use capstan_elasticity::solvers::{Observer, Progress, SolveStage};
            observer.iteration(&Progress::new(
                SolveStage::Membrane,
                iteration,
                residual,
                step,
            ));
        };
        let newton = MembraneNewton {
            max_iterations: setup.max_newton_iterations,
            ..Default::default()
        };
        let s = model.solve_observed(&problem, None, newton, &mut report)?;
        if s.slip_fraction(setup.eps) == 1.0 {
            return Ok(s.tension_ratio());
        }
        pull *= 4.0;
    }
    Err(FrictionError::NonFinite {
        what: "membrane pull needed for full slip",
        angle: setup.theta[0],
    })
}

/// The `mu` at which the membrane displacement model fully slips at the ratio `ratio`
/// (Brent on [`membrane_ratio`], bracket `[0, 2]` doubled up to `mu = 64`).
///
/// # Errors
/// [`FrictionError::TensionRatioBelowOne`] for `ratio < 1`;
/// [`FrictionError::NoFrictionCoefficient`] when no `mu <= 64` reaches `ratio`; see
/// [`membrane_ratio`].
pub fn membrane_mu<C: ProfileCurve<f64>>(
    profile: &C,
    setup: MembraneSetup,
    ratio: f64,
) -> Result<ImpliedMu, FrictionError> {
    if ratio.is_nan() || ratio < 1.0 {
        return Err(FrictionError::TensionRatioBelowOne { ratio });
    }
    let solves = std::cell::Cell::new(0);
    let mut f = |mu: f64| {
        solves.set(solves.get() + 1);
        Ok(membrane_ratio(profile, setup, mu)? - ratio)
    };
    let f0 = f(0.0)?;
    let mut hi = 2.0;
    let mut f_hi = f(hi)?;
    while f_hi < 0.0 {
        if hi >= 64.0 {
            return Err(FrictionError::NoFrictionCoefficient {
                t_max: ratio,
                reachable_min: f0 + ratio,
                reachable_max: f_hi + ratio,
                mu_limit: hi,
            });
        }
        hi *= 2.0;
        f_hi = f(hi)?;
    }
    let mu = Brent {
        x_tol: 1e-10,
        max_iterations: setup.max_root_iterations,
    }
    .solve(&mut f, 0.0, f0, hi, f_hi)?;
    Ok(ImpliedMu {
        mu,
        solves: solves.get(),
    })
}

/// Whether the thick body with friction `mu` fully slides at end tractions `(1, ratio)`:
/// a fully slipping solution, no static equilibrium, or (as in
/// [`capstan_elasticity::contact::threshold_ratio`]) a failed solve within `1e-3` of the
/// sliding mode's limiting ratio.
///
/// # Errors
/// Model or solver failures other than those.
pub fn thick_body_slides(
    body: &ThickBody,
    mu: f64,
    ratio: f64,
    eps: f64,
) -> Result<bool, CliError> {
    let model = coulomb_model(body, mu, eps)?;
    let solver = BoundarySolver::new(&model, ContactSettings::default())?;
    solver_slides(&solver, ratio)
}

/// [`thick_body_slides`] for a built solver.
fn solver_slides<
    D: capstan_elasticity::contact::ContactOperator,
    L: capstan_friction::FrictionLaw<f64>,
>(
    solver: &BoundarySolver<'_, D, L>,
    ratio: f64,
) -> Result<bool, CliError> {
    Ok(solve_below_threshold(solver, ratio, None)?.is_none())
}

/// The `mu_F` at which the thick body's Slip reaches 1 at end tractions `(1, ratio)`:
/// bracketing from `guess` (doubling or halving) and bisection on [`thick_body_slides`]
/// until the bracket is shorter than `tolerance` times its upper end; returns its midpoint.
///
/// # Errors
/// [`FrictionError::NoFrictionCoefficient`] when the body still slides at `mu = 1e3`; see
/// [`thick_body_slides`]. A body that holds at `mu = guess / 2^40` gives `mu = 0`.
pub fn kikuchi_oden_mu<S: capstan_geometry::Surface<f64> + Clone + Send + Sync + 'static>(
    body: &Body<S>,
    ratio: f64,
    eps: f64,
    guess: f64,
    tolerance: f64,
) -> Result<ImpliedMu, CliError> {
    if ratio.is_nan() || ratio < 1.0 {
        return Err(FrictionError::TensionRatioBelowOne { ratio }.into());
    }
    let guess = if guess > 0.0 { guess } else { 0.1 };
    // The bulk does not depend on `mu`: factorise and condense it once, at the guess.
    let law = |mu: f64| RegularisedCoulombParams::new(mu, eps);
    let base_model = body.model(RegularisedCoulomb, law(guess)?, eps)?;
    let base = BoundarySolver::new(&base_model, ContactSettings::default())?;
    let solves = std::cell::Cell::new(0);
    let slides = |mu: f64| -> Result<bool, CliError> {
        solves.set(solves.get() + 1);
        let model = base_model.with_params(law(mu)?);
        solver_slides(&base.with_model(&model)?, ratio)
    };
    let (mut lo, mut hi) = if slides(guess)? {
        let mut hi = 2.0 * guess;
        while slides(hi)? {
            if hi > 1e3 {
                // Every ratio reached is below `ratio` (the threshold, not known exactly).
                return Err(FrictionError::NoFrictionCoefficient {
                    t_max: ratio,
                    reachable_min: 1.0,
                    reachable_max: ratio,
                    mu_limit: hi,
                }
                .into());
            }
            hi *= 2.0;
        }
        (hi / 2.0, hi)
    } else {
        let mut lo = 0.5 * guess;
        let mut halvings = 1;
        while !slides(lo)? {
            if halvings >= 40 {
                // Holds at `guess / 2^40`: the coefficient is zero to this precision.
                return Ok(ImpliedMu {
                    mu: 0.0,
                    solves: solves.get(),
                });
            }
            lo *= 0.5;
            halvings += 1;
        }
        (lo, 2.0 * lo)
    };
    while hi - lo > tolerance * hi {
        let mid = 0.5 * (lo + hi);
        if slides(mid)? {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(ImpliedMu {
        mu: 0.5 * (lo + hi),
        solves: solves.get(),
    })
}

/// Human-readable summary.
pub fn table(r: &InferMuReport, scene: &Scene) -> String {
    let what = match r.model {
        "kikuchi-oden" => format!(
            "thick body ({} x {} grid, h = {})",
            scene.grid.n2, scene.grid.n3, scene.body.thickness
        ),
        "membrane" => "membrane displacement model".to_string(),
        _ => "membrane".to_string(),
    };
    format!(
        "{what} on {} over [{:.6}, {:.6}]: T0 = {}, T_max = {} (ratio {:.9})\n  mu = {:.12}   ({}, model {})\n",
        scene.obstacle.shape,
        scene.membrane.theta0,
        scene.membrane.theta_max,
        r.t0,
        r.t_max,
        r.tension_ratio,
        r.mu,
        r.method,
        r.model
    )
}

/// Regularised Coulomb with `mu`, regularised and classified at `eps`, on `body`.
///
/// # Errors
/// Invalid `mu` or `eps`; the body's discretisation errors.
pub(crate) fn coulomb_model(
    body: &ThickBody,
    mu: f64,
    eps: f64,
) -> Result<ContactModel<ThickBodyOperator, RegularisedCoulomb>, CliError> {
    Ok(body.model(
        RegularisedCoulomb,
        RegularisedCoulombParams::new(mu, eps)?,
        eps,
    )?)
}
