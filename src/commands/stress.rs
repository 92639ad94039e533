//! `capstan stress`: numerical stability under stress. Each parameter is swept toward its hard
//! limit on the thick-body contact problem and on the membrane capstan models; every point
//! records whether it converged (or its typed failure), Newton iterations, the final
//! residual, a condition estimate of the bulk operator and the change of the reported
//! quantities under one grid refinement.
//!
//! # Math
//! Condition estimate (a lower bound, 1-norm): `||A~||_1 * max_k ||x_k||_1 / ||x_{k-1}||_1`
//! over four steps of inverse iteration `x_k = A~^-1 x_{k-1}` from `x_0 = (1, -1, 1, ...)`,
//! where `A~` is the bulk with the contact solver's stabilising spring on the tangential
//! contact rows (as in [`BoundarySolver`]): without it a circle's bulk is singular (rigid
//! sliding). Refinement change: `|q(2 n2 - 1, 2 n3 - 1) - q(n2, n3)| / |q(2 n2 - 1, 2 n3 - 1)|`
//! for `q` = the largest `|v^2|` (the reported displacement).

use std::collections::BTreeMap;
use std::f64::consts::{FRAC_PI_2, PI};
use std::time::Instant;

use capstan_elasticity::contact::{
    BoundarySolver, ContactModel, ContactSettings, FullSystemSettings, solve_sequenced,
};
use capstan_elasticity::finite_element::DiscretisationMethod;
use capstan_elasticity::friction::{RegularisedCoulomb, RegularisedCoulombParams};
use capstan_elasticity::solvers::{LinearSolver, SilentObserver, SparseLu};
use capstan_friction::membrane::closed_form;
use serde::Serialize;

use crate::error::CliError;
use crate::output::OutputDir;
use crate::scene::{Scene, available_memory, memory_estimate};

/// One stressed point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StressPoint {
    /// The axis swept (`poisson`, `thickness`, `eps`, `mu`, `ratio`, `b/a`, `young`, `grid`,
    /// `capstan-*`).
    pub axis: &'static str,
    /// `contact` (thick body) or `capstan` (membrane).
    pub model: &'static str,
    /// The parameters that differ from the paper's default scene (and the grid).
    pub parameters: BTreeMap<String, serde_json::Value>,
    /// Whether the solve succeeded.
    pub converged: bool,
    /// The typed reason of a failure (`no-equilibrium: ...`, `not-converged: ...`,
    /// `invalid-input: ...`, `refused: ...`), or null.
    pub failure: Option<String>,
    /// Newton iterations (contact), null where the model has none (closed forms, quadrature).
    pub iterations: Option<usize>,
    /// Relative max-norm residual of the full contact system at the solution.
    pub final_residual: Option<f64>,
    /// 1-norm condition estimate of the stabilised bulk (lower bound; contact only).
    pub condition_estimate: Option<f64>,
    /// Relative change of the largest `|v^2|` under one grid refinement (contact), or relative
    /// error against a closed form (capstan), where available.
    pub refinement_change: Option<f64>,
    /// The reported quantities (`slip_fraction`, `max_v2`, `t_max`, ...).
    pub quantities: BTreeMap<String, f64>,
    /// Wall-clock seconds for the point (informative only).
    pub seconds: f64,
}

/// The whole report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StressReport {
    /// Whether this was the `--quick` subset.
    pub quick: bool,
    /// One entry per stressed point.
    pub points: Vec<StressPoint>,
}

fn num(x: f64) -> serde_json::Value {
    serde_json::json!(x)
}

/// The contact scene of a point: the paper's default plus `sets`.
pub struct ContactCase {
    axis: &'static str,
    scene: Scene,
    parameters: BTreeMap<String, serde_json::Value>,
    refine: bool,
}

/// A contact point on an `n2 x n3` grid: the paper's default scene with `sets` (scene keys and
/// values), refined once when `refine`.
///
/// # Errors
/// [`CliError::Scene`] if the scene is invalid.
pub fn contact_case(
    axis: &'static str,
    n: [usize; 2],
    sets: &[(&str, serde_json::Value)],
    refine: bool,
) -> Result<ContactCase, CliError> {
    let mut all: Vec<String> = vec![format!("grid.n2={}", n[0]), format!("grid.n3={}", n[1])];
    let mut parameters = BTreeMap::new();
    parameters.insert("grid".into(), serde_json::json!(n));
    for (k, v) in sets {
        all.push(format!("{k}={v}"));
        parameters.insert((*k).to_string(), v.clone());
    }
    // Scene::load validates exactly as for a user's scene, without the memory check's
    // dependence on where the scene came from.
    let scene = Scene::load(None, &all)?;
    Ok(ContactCase {
        axis,
        scene,
        parameters,
        refine,
    })
}

/// What one contact solve produced.
struct ContactOutcome {
    iterations: usize,
    residual: f64,
    quantities: BTreeMap<String, f64>,
    condition: Option<f64>,
}

/// A failure, typed: `kind: message`.
fn typed(e: &CliError) -> String {
    let kind = match e.exit_code() {
        2 => "invalid-input",
        3 => "no-equilibrium",
        4 => "not-converged",
        _ => "error",
    };
    format!("{kind}: {e}")
}

fn solve_contact(scene: &Scene, condition: bool) -> Result<ContactOutcome, CliError> {
    let body = crate::commands::contact::thick_body(scene)?;
    let params = RegularisedCoulombParams::new(scene.friction.mu, scene.friction.eps)?;
    let loads = crate::commands::contact::loads(scene);
    if scene.solver.nonlinear == "full-newton" {
        // grid sequencing: each finer level by Newton from the coarser solution
        let seq = solve_sequenced(
            &body,
            RegularisedCoulomb,
            params,
            scene.friction.eps,
            loads,
            FullSystemSettings::default(),
            &mut SilentObserver,
        )?;
        let condition = condition.then(|| condition_estimate(&seq.model)).flatten();
        let mut quantities = BTreeMap::new();
        quantities.insert("grid_sequence_levels".into(), seq.levels.len() as f64);
        return outcome(&seq.solution, quantities, condition);
    }
    let model = body.model(RegularisedCoulomb, params, scene.friction.eps)?;
    let condition = if condition {
        condition_estimate(&model)
    } else {
        None
    };
    let mut quantities = BTreeMap::new();
    let solver = BoundarySolver::new(&model, ContactSettings::default())?;
    if let Some(mode) = solver.sliding() {
        // an unbounded direction (friction holds every ratio) has no finite limit to report
        for (key, r) in [
            ("limiting_ratio_upper", mode.upper_ratio),
            ("limiting_ratio_lower", mode.lower_ratio),
        ] {
            if r.is_finite() {
                quantities.insert(key.into(), r);
            }
        }
    }
    let sol = solver.solve(loads)?;
    outcome(&sol, quantities, condition)
}

/// The reported quantities of a solution (typed failure if any is not finite).
fn outcome(
    sol: &capstan_elasticity::contact::ContactSolution,
    mut quantities: BTreeMap<String, f64>,
    condition: Option<f64>,
) -> Result<ContactOutcome, CliError> {
    quantities.insert("slip_fraction".into(), sol.slip_fraction);
    quantities.insert("max_v2".into(), sol.max_azimuthal_displacement.value);
    quantities.insert("max_v3".into(), sol.max_radial_displacement.value);
    quantities.insert(
        "min_normal_stress".into(),
        sol.contact
            .normal_stress
            .iter()
            .fold(f64::INFINITY, |m, &x| m.min(x)),
    );
    if quantities.values().any(|x| !x.is_finite()) {
        return Err(CliError::Contact(
            capstan_elasticity::contact::ContactError::NotConverged {
                iterations: sol.stats.newton_iterations,
                residual: sol.stats.residual,
                load_factor: 1.0,
            },
        ));
    }
    Ok(ContactOutcome {
        iterations: sol.stats.newton_iterations,
        residual: sol.stats.residual,
        quantities,
        condition,
    })
}

/// See the module docs: inverse iteration on the stabilised bulk, 1-norm.
fn condition_estimate<
    D: capstan_elasticity::Discretisation,
    L: capstan_elasticity::friction::FrictionLaw<f64>,
>(
    model: &ContactModel<D, L>,
) -> Option<f64> {
    let system = model.system();
    let mut values = system.values.clone();
    for &k in model.active() {
        let node = &model.contact_nodes()[k];
        let row = node.tangential_row?;
        let slot = system.pattern.slot(row, node.tangential_dof)?;
        values[slot] += values[slot].abs(); // the spring: w c = |A_rr|, as in BoundarySolver
    }
    let n = system.pattern.nrows();
    let mut col_sums = vec![0.0; n];
    for ((_, c), v) in system.pattern.entries().zip(&values) {
        col_sums[c] += v.abs();
    }
    let norm_a = col_sums.iter().fold(0.0f64, |m, &x| m.max(x));
    let mut lu = SparseLu::new(capstan_elasticity::solvers::DirectParams {
        ordering: model.discretisation().lu_ordering(),
        ..Default::default()
    })
    .ok()?;
    lu.analyse(&system.pattern).ok()?;
    lu.factor(&values).ok()?;
    let mut x: Vec<f64> = (0..n)
        .map(|i| if i % 2 == 0 { 1.0 } else { -1.0 })
        .collect();
    let mut best = 0.0f64;
    for _ in 0..4 {
        let before: f64 = x.iter().map(|v| v.abs()).sum();
        lu.solve_in_place(&mut x).ok()?;
        let after: f64 = x.iter().map(|v| v.abs()).sum();
        if !after.is_finite() {
            return None;
        }
        best = best.max(after / before);
        x.iter_mut().for_each(|v| *v /= after);
    }
    Some(norm_a * best)
}

impl StressPoint {
    /// The point of `axis` and `model` at `parameters` before its solve: nothing converged,
    /// measured or reported yet.
    fn unsolved(
        axis: &'static str,
        model: &'static str,
        parameters: BTreeMap<String, serde_json::Value>,
    ) -> Self {
        Self {
            axis,
            model,
            parameters,
            converged: false,
            failure: None,
            iterations: None,
            final_residual: None,
            condition_estimate: None,
            refinement_change: None,
            quantities: BTreeMap::new(),
            seconds: 0.0,
        }
    }
}

/// Runs one contact point; failures are recorded in the point.
pub fn run_contact_case(case: ContactCase) -> StressPoint {
    let start = Instant::now();
    let scene = &case.scene;
    let mut point = StressPoint::unsolved(case.axis, "contact", case.parameters);
    let (n2, n3) = (scene.grid.n2, scene.grid.n3);
    // The paper's Jacobi grid condition psi0 dx2 <= dx3 (psi0 = sqrt(g22) at x3 = 0): recorded,
    // not required by LU.
    if let Ok(obstacle) = scene.obstacle.build()
        && let Ok(tangents) = {
            use capstan_geometry::Surface;
            let mid = 0.5 * (scene.membrane.theta0 + scene.membrane.theta_max);
            obstacle.tangents([0.0, mid])
        }
    {
        let g = tangents[1];
        let psi0 = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
        let dx2 = (scene.membrane.theta_max - scene.membrane.theta0) / (n2 - 1) as f64;
        let dx3 = scene.body.thickness / (n3 - 1) as f64;
        point
            .quantities
            .insert("jacobi_grid_ratio".into(), psi0 * dx2 / dx3);
    }
    match solve_contact(scene, true) {
        Ok(out) => {
            point.converged = true;
            point.iterations = Some(out.iterations);
            point.final_residual = Some(out.residual);
            point.condition_estimate = out.condition;
            point.quantities.extend(out.quantities);
            if case.refine {
                let mut fine = scene.clone();
                fine.grid.n2 = 2 * n2 - 1;
                fine.grid.n3 = 2 * n3 - 1;
                match solve_contact(&fine, false) {
                    Ok(f) => {
                        // magnitudes: under symmetric loads the largest |v^2| sits at either
                        // end, with either sign
                        let (q, qf) = (
                            point.quantities["max_v2"].abs(),
                            f.quantities["max_v2"].abs(),
                        );
                        point.refinement_change = Some((qf - q).abs() / qf.max(1e-300));
                        point.quantities.insert(
                            "slip_fraction_refined".into(),
                            f.quantities["slip_fraction"],
                        );
                    }
                    Err(e) => {
                        point
                            .quantities
                            .insert("refined_failed_exit_code".into(), e.exit_code() as f64);
                    }
                }
            }
        }
        Err(e) => point.failure = Some(typed(&e)),
    }
    point.seconds = start.elapsed().as_secs_f64();
    point
}

fn contact_cases(quick: bool) -> Result<Vec<ContactCase>, CliError> {
    let base = [60, 11];
    let q2 = [61, 11];
    let pick = |all: &[f64], ends: bool| -> Vec<f64> {
        if ends {
            vec![all[0], all[all.len() - 1]]
        } else {
            all.to_vec()
        }
    };
    let mut cases = Vec::new();
    // the remedy rows: Q1 and Q2 with selective reduced integration of the volumetric part
    for nu in pick(&[0.45, 0.49, 0.499, 0.4999], quick) {
        for (method, n, reduced) in [
            ("fd", base, false),
            ("fem-q1", base, false),
            ("fem-q2", q2, false),
            ("fem-q1", base, true),
            ("fem-q2", q2, true),
        ] {
            let mut sets = vec![
                ("body.poisson", num(nu)),
                ("discretisation.method", serde_json::json!(method)),
            ];
            if reduced {
                sets.push(("discretisation.volumetric", serde_json::json!("reduced")));
            }
            cases.push(contact_case("poisson", n, &sets, true)?);
        }
    }
    for h in pick(&[1.0, 0.1, 0.01, 0.001], quick) {
        for (label, n) in [("fixed", base), ("scaled", [4 * base[0], base[1]])] {
            let mut c = contact_case("thickness", n, &[("body.thickness", num(h))], false)?;
            c.parameters
                .insert("grid_mode".into(), serde_json::json!(label));
            cases.push(c);
        }
    }
    for eps in pick(&[1e-3, 1e-5, 1e-7, 1e-10], quick) {
        cases.push(contact_case(
            "eps",
            base,
            &[("friction.eps", num(eps))],
            true,
        )?);
    }
    for mu in pick(&[0.0, 0.5, 1.0, 2.0], quick) {
        cases.push(contact_case("mu", base, &[("friction.mu", num(mu))], true)?);
    }
    let ratios: &[f64] = if quick {
        &[1.0, 3.3, 5.0]
    } else {
        &[1.0, 2.0, 3.0, 3.3, 3.35, 5.0]
    };
    for &r in ratios {
        cases.push(contact_case(
            "ratio",
            base,
            &[("loads.tau_max", num(r))],
            true,
        )?);
    }
    for ba in pick(&[0.1, 0.5, 1.0, 2.0, 10.0], quick) {
        cases.push(contact_case(
            "b/a",
            base,
            &[("obstacle.b", num(2.0 * ba)), ("loads.tau_max", num(1.2))],
            true,
        )?);
    }
    // E scaled with eps = 1e-5 (1e3 / E): the answer, times E, is invariant.
    for young in pick(&[1e-3, 1.0, 1e3, 1e6, 1e12], quick) {
        cases.push(contact_case(
            "young",
            base,
            &[
                ("body.young", num(young)),
                ("friction.eps", num(1e-5 * 1e3 / young)),
            ],
            false,
        )?);
    }
    let grids: &[[usize; 2]] = if quick {
        &[[20, 5], [250, 41], [500, 81]]
    } else {
        &[
            [20, 5],
            [60, 11],
            [250, 41],
            [500, 81],
            [1000, 161],
            [2000, 321],
        ]
    };
    for &n in grids {
        let full = [("solver.nonlinear", serde_json::json!("full-newton"))];
        let sets: &[(&str, serde_json::Value)] = if n[0] >= FULL_NEWTON_FROM_N2 {
            &full
        } else {
            &[]
        };
        cases.push(contact_case("grid", n, sets, false)?);
    }
    Ok(cases)
}

/// From this `n2` on the grid axis solves by the full-system Newton with grid sequencing
/// ([`solve_sequenced`]): a few factorisations per level are cheaper than condensing
/// `m ~ n2` right-hand sides (1000 x 161: 12.8 s against 32.6 s).
pub const FULL_NEWTON_FROM_N2: usize = 1000;

/// A grid no machine of today holds (16000 x 2560: ~380 GiB estimated): the quick run's
/// refusal point.
pub const REFUSED_GRID: [usize; 2] = [16000, 2560];

/// A point at a grid that may not fit: refused from the memory estimate when it does not fit,
/// else solved (by the full-system Newton from [`FULL_NEWTON_FROM_N2`] on).
pub fn grid_refusal(n: [usize; 2]) -> StressPoint {
    let start = Instant::now();
    let mut sets = vec![format!("grid.n2={}", n[0]), format!("grid.n3={}", n[1])];
    if n[0] >= FULL_NEWTON_FROM_N2 {
        sets.push("solver.nonlinear=full-newton".into());
    }
    let mut point = StressPoint::unsolved(
        "grid",
        "contact",
        BTreeMap::from([("grid".to_string(), serde_json::json!(n))]),
    );
    point.quantities.insert(
        "memory_estimate_bytes".to_string(),
        memory_estimate(
            n[0],
            n[1],
            DiscretisationMethod::Fd,
            n[0] < FULL_NEWTON_FROM_N2,
        ),
    );
    if let Some(have) = available_memory() {
        point
            .quantities
            .insert("memory_available_bytes".into(), have);
    }
    match Scene::load(None, &sets) {
        Err(e) => point.failure = Some(format!("refused: {e}")),
        Ok(scene) => {
            let mut parameters = point.parameters.clone();
            if !matches!(scene.solver.nonlinear.as_str(), "auto" | "newton") {
                parameters.insert(
                    "solver.nonlinear".into(),
                    serde_json::json!(scene.solver.nonlinear),
                );
            }
            let case = ContactCase {
                axis: "grid",
                scene,
                parameters,
                refine: false,
            };
            let memory = std::mem::take(&mut point.quantities);
            point = run_contact_case(case);
            point.quantities.extend(memory);
        }
    }
    point.seconds = start.elapsed().as_secs_f64();
    point
}

/// A membrane point: the scene's tension profile, with a closed-form reference where known.
pub fn capstan_point(
    axis: &'static str,
    sets: &[(&str, serde_json::Value)],
    reference: Option<f64>,
) -> StressPoint {
    let start = Instant::now();
    let mut parameters = BTreeMap::new();
    let all: Vec<String> = sets
        .iter()
        .map(|(k, v)| {
            parameters.insert((*k).to_string(), v.clone());
            match v {
                serde_json::Value::String(s) => format!("{k}={s}"),
                _ => format!("{k}={v}"),
            }
        })
        .collect();
    let mut point = StressPoint::unsolved(axis, "capstan", parameters);
    let result = Scene::load(None, &all)
        .and_then(|scene| crate::commands::tension::membrane_profile(&scene));
    match result {
        Ok(p) => {
            let t_max = p.t_max();
            if t_max.is_finite() {
                point.converged = true;
                point.quantities.insert("t_max".into(), t_max);
                point
                    .quantities
                    .insert("tension_ratio".into(), p.tension_ratio());
                point
                    .parameters
                    .insert("method".into(), serde_json::json!(p.method.as_str()));
                if let Some(r) = reference.filter(|r| r.is_finite()) {
                    point.quantities.insert("reference_t_max".into(), r);
                    point.refinement_change = Some((t_max - r).abs() / r.abs());
                }
            } else {
                point.failure = Some("not-converged: non-finite T_max".into());
            }
        }
        Err(e) => point.failure = Some(typed(&e)),
    }
    point.seconds = start.elapsed().as_secs_f64();
    point
}

fn capstan_points(quick: bool) -> Vec<StressPoint> {
    let mut out = Vec::new();
    let s = |x: &str| serde_json::json!(x);
    // Contact angles near pi/2 on the ellipse a = 2, b = 1 (u' = 0 at theta = +-pi/2).
    let deltas: &[f64] = if quick {
        &[1e-2, 1e-8, -1e-8]
    } else {
        &[1e-2, 1e-4, 1e-6, 1e-8, 0.0, -1e-8, -1e-4]
    };
    for &d in deltas {
        let th = FRAC_PI_2 - d;
        let r = closed_form::ellipse_tension(0.5, 1.0, 2.0, 1.0, -th, th);
        out.push(capstan_point(
            "capstan-angle",
            &[
                ("obstacle.b", num(1.0)),
                ("membrane.theta0", num(-th)),
                ("membrane.theta_max", num(th)),
            ],
            Some(r),
        ));
    }
    // Long multi-wrap intervals on a cylinder (closed form) and the same circle as a general
    // prism (quadrature/ODE path), and mu up to 5 (overflow past exp(709) is typed).
    let wraps: &[f64] = if quick {
        &[1.0, 20.0]
    } else {
        &[1.0, 5.0, 20.0, 50.0]
    };
    let cylinder = vec![("obstacle.shape", s("cylinder"))];
    let circle_prism = vec![
        ("obstacle.shape", s("prism")),
        ("obstacle.u", s("2*sin(t)")),
        ("obstacle.v", s("2*cos(t)")),
    ];
    for &k in wraps {
        for mu in [0.5, 5.0] {
            let angle = 2.0 * PI * k;
            for obstacle in [&cylinder, &circle_prism] {
                let mut sets = obstacle.clone();
                sets.extend([
                    ("friction.mu", num(mu)),
                    ("membrane.theta0", num(0.0)),
                    ("membrane.theta_max", num(angle)),
                ]);
                out.push(capstan_point(
                    "capstan-wraps",
                    &sets,
                    Some(closed_form::capstan(mu, 1.0, angle)),
                ));
            }
        }
    }
    // Cones: near a needle (alpha -> 0, the apex region) and near a plane (alpha -> pi/2).
    let alphas: &[f64] = if quick {
        &[1e-6, FRAC_PI_2 - 1e-4]
    } else {
        &[
            1e-6,
            1e-3,
            0.5,
            1.0,
            1.5,
            FRAC_PI_2 - 1e-3,
            FRAC_PI_2 - 1e-4,
        ]
    };
    for &alpha in alphas {
        let r = closed_form::right_circular_cone_tension(0.5, 1.0, alpha, 0.0, PI);
        out.push(capstan_point(
            "capstan-cone",
            &[
                ("obstacle.shape", s("circular-cone")),
                ("obstacle.half_angle", num(alpha)),
                ("membrane.theta0", num(0.0)),
                ("membrane.theta_max", num(PI)),
            ],
            Some(r),
        ));
    }
    for mu in if quick {
        vec![0.0, 5.0]
    } else {
        vec![0.0, 1.0, 2.0, 5.0]
    } {
        out.push(capstan_point(
            "capstan-mu",
            &[("obstacle.b", num(1.0)), ("friction.mu", num(mu))],
            Some(closed_form::ellipse_tension(
                mu, 1.0, 2.0, 1.0, -FRAC_PI_2, FRAC_PI_2,
            )),
        ));
    }
    out
}

/// Runs the stress suite.
///
/// # Errors
/// Only for a stress point that cannot even be described (a bug); failures of the points
/// themselves are recorded in the report.
pub fn report(quick: bool) -> Result<StressReport, CliError> {
    let mut points: Vec<StressPoint> = contact_cases(quick)?
        .into_iter()
        .map(run_contact_case)
        .collect();
    // Refused from the memory estimate before anything is allocated (instant) in the quick
    // run; the full run attempts 4000 x 640 (~20 GiB estimated), solved where it fits.
    points.push(grid_refusal(if quick { REFUSED_GRID } else { [4000, 640] }));
    points.extend(capstan_points(quick));
    Ok(StressReport { quick, points })
}

fn fmt_opt(x: Option<f64>) -> String {
    x.map_or_else(|| "-".into(), |v| format!("{v:.3e}"))
}

/// The report as a Markdown table.
pub fn table(r: &StressReport) -> String {
    let mut s = String::from(
        "| axis | model | parameters | converged | failure | iterations | residual | cond. est. | refinement change / error | quantities |\n|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for p in &r.points {
        let params: Vec<String> = p
            .parameters
            .iter()
            .map(|(k, v)| format!("{k}={v}"))
            .collect();
        let qs: Vec<String> = p
            .quantities
            .iter()
            .map(|(k, v)| format!("{k}={v:.6e}"))
            .collect();
        let failure = p
            .failure
            .as_deref()
            .map(|f| {
                let f = f.replace('|', "/");
                if f.chars().count() > 140 {
                    format!("{}...", f.chars().take(140).collect::<String>())
                } else {
                    f
                }
            })
            .unwrap_or_default();
        s.push_str(&format!(
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
            p.axis,
            p.model,
            params.join(" "),
            if p.converged { "yes" } else { "no" },
            failure,
            p.iterations.map_or_else(|| "-".into(), |i| i.to_string()),
            fmt_opt(p.final_residual),
            fmt_opt(p.condition_estimate),
            fmt_opt(p.refinement_change),
            qs.join(" "),
        ));
    }
    s
}

/// Writes `stress.json` and `stress.md` into `dir`.
///
/// # Errors
/// Output errors (including a NaN refused).
pub fn write_out(dir: &std::path::Path, r: &StressReport) -> Result<(), CliError> {
    let out = OutputDir::create(dir)?;
    out.write_json("stress.json", r)?;
    let md = table(r);
    out.write("stress.md", |w| {
        std::io::Write::write_all(w, md.as_bytes()).map_err(crate::output::OutputError::from)
    })?;
    Ok(())
}
