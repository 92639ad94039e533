//! `capstan membrane-path`: the membrane displacement model along a load path with memory
//! (`loads.path`), exact Coulomb friction on the slip increment, semismooth Newton per step.

use std::path::Path;

use capstan_friction::membrane_displacement::{EndCondition, MembraneDisplacementProblem};
use capstan_friction::membrane_path::{
    MembranePath, SemismoothIteration, SemismoothMembrane, SemismoothSettings,
};
use capstan_friction::{AnyNonsmoothLaw, AnyNonsmoothParams, FrictionError, FrictionState};
use serde::Serialize;

use crate::error::CliError;
use crate::output::{LinePlot, Series, Table};
use crate::provenance::report_dir;
use crate::scene::Scene;

/// One load state of the path.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PathStepReport {
    /// Step number (1 = the first value of `loads.path`).
    pub step: usize,
    /// The tension at `theta_max` (the path value).
    pub end_tension: f64,
    /// `T(theta_max) / T(theta0)`.
    pub tension_ratio: f64,
    /// Displacement of the end `theta_max` from the wrapped state (physical length).
    pub end_displacement: f64,
    /// Nodes in stick.
    pub stick_nodes: usize,
    /// Nodes in slip (forward or backward) in this step.
    pub slip_nodes: usize,
    /// The runs of slipping nodes, `[theta_first, theta_last]`.
    pub slip_intervals: Vec<[f64; 2]>,
    /// Energy dissipated by friction in this step.
    pub dissipation: f64,
    /// Semismooth Newton iterations.
    pub iterations: usize,
    /// Final residual (max norm).
    pub residual: f64,
}

/// The report of `capstan membrane-path`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MembranePathReport {
    /// The nonsmooth law (`friction.law`).
    pub law: String,
    /// Nodes (`membrane.nodes`).
    pub nodes: usize,
    /// Axial stiffness `E h / (1 - nu^2)` from `body.*`.
    pub stiffness: f64,
    /// Tension at `theta0`, also the wrapping tension (`membrane.t0`).
    pub t0: f64,
    /// The steps, in the order of `loads.path`.
    pub steps: Vec<PathStepReport>,
    /// Energy dissipated over the whole path.
    pub dissipation: f64,
    /// Node angles.
    #[serde(skip)]
    pub theta: Vec<f64>,
    /// Per step: displacement, slip increment, tension, friction force and state per node.
    #[serde(skip)]
    pub profiles: Vec<[Vec<f64>; 5]>,
}

/// Solves the scene's load path.
///
/// # Errors
/// `loads.path` missing, a smooth `friction.law`, a non-prism obstacle or membrane loads
/// (exit code 2); the membrane sliding as a whole (3); a spent budget
/// `membrane.max_newton_iterations` (4).
pub fn report(scene: &Scene) -> Result<MembranePathReport, CliError> {
    // -v prints every semismooth iteration with its active set (stage `membrane`)
    report_observed(scene, &mut crate::progress::CliObserver::new())
}

/// As [`report`], every semismooth iteration of every step going to `observer` (stage
/// `membrane`, with the stick/slip counts).
///
/// # Errors
/// As [`report`].
pub fn report_observed(
    scene: &Scene,
    observer: &mut dyn capstan_elasticity::solvers::Observer<f64>,
) -> Result<MembranePathReport, CliError> {
    let path = scene.loads.path.clone().ok_or(FrictionError::MissingParameter {
        field: "loads.path",
        why: "membrane-path needs the end tensions at theta_max, e.g. --set 'loads.path=[2.0, 1.0, 2.0]'",
    })?;
    let params =
        AnyNonsmoothParams::new(&scene.friction.law, &scene.friction.settings()).map_err(|e| {
            CliError::Scene {
                origin: "friction.law".into(),
                message: format!(
                    "{e} (membrane-path solves exact Coulomb: --set friction.law=exact-coulomb)"
                ),
            }
        })?;
    check_no_loads(scene)?;
    let obstacle = scene.obstacle.build()?;
    let profile = membrane_profile(&obstacle)?;
    let (m, b) = (&scene.membrane, &scene.body);
    let stiffness = b.young * b.thickness / (1.0 - b.poisson * b.poisson);
    let problem = MembraneDisplacementProblem {
        theta0: m.theta0,
        theta1: m.theta_max,
        nodes: m.nodes,
        stiffness,
        start: EndCondition::Tension(m.t0),
        end: EndCondition::Tension(m.t0),
    };
    let settings = SemismoothSettings {
        max_iterations: m.max_newton_iterations,
        ..Default::default()
    };
    let mut report_iteration = |_: usize, it: &SemismoothIteration| {
        use capstan_elasticity::solvers::{Progress, SolveStage};
        observer.iteration(
            &Progress::new(SolveStage::Membrane, it.iteration, it.residual, it.step)
                .with_active(it.stick, it.slip),
        );
    };
    let model = SemismoothMembrane::new(&profile, AnyNonsmoothLaw, params);
    let solved = model.solve_path(&problem, &path, settings, &mut report_iteration)?;
    Ok(summarise(scene, stiffness, &solved))
}

/// The membrane displacement model carries no body forces, belt speed or load expressions.
fn check_no_loads(scene: &Scene) -> Result<(), CliError> {
    let l = &scene.loads;
    let given = [
        ("loads.gravity", l.gravity * l.density != 0.0),
        ("loads.speed", l.speed != 0.0),
        ("loads.f_t", l.f_t.is_some()),
        ("loads.f_n", l.f_n.is_some()),
    ];
    match given.iter().find(|(_, set)| *set) {
        Some((key, _)) => Err(CliError::Scene {
            origin: (*key).into(),
            message: format!(
                "`{key}` is set: the membrane displacement model (membrane-path) carries no membrane loads; `capstan tension` computes the capstan profile under them"
            ),
        }),
        None => Ok(()),
    }
}

fn summarise(scene: &Scene, stiffness: f64, p: &MembranePath) -> MembranePathReport {
    let w = p.end_displacements();
    let count = |s: &[FrictionState], k| s.iter().filter(|&&x| x == k).count();
    let steps = p
        .steps
        .iter()
        .enumerate()
        .map(|(k, s)| PathStepReport {
            step: k + 1,
            end_tension: p.end_tensions[k],
            tension_ratio: s.tension_ratio(),
            end_displacement: w[k],
            stick_nodes: count(&s.states, FrictionState::Stick),
            slip_nodes: count(&s.states, FrictionState::Slip),
            slip_intervals: s.slip_intervals(),
            dissipation: s.dissipation,
            iterations: s.iterations,
            residual: s.residual,
        })
        .collect();
    let state_code = |s: &FrictionState| match s {
        FrictionState::Stick => 0.0,
        FrictionState::Slip => 1.0,
        FrictionState::Separated => 2.0,
    };
    MembranePathReport {
        law: scene.friction.law.clone(),
        nodes: scene.membrane.nodes,
        stiffness,
        t0: scene.membrane.t0,
        steps,
        dissipation: p.dissipation(),
        theta: p.steps.first().map(|s| s.theta.clone()).unwrap_or_default(),
        profiles: p
            .steps
            .iter()
            .map(|s| {
                [
                    s.displacement.clone(),
                    s.slip_increment.clone(),
                    s.tension.clone(),
                    s.friction.clone(),
                    s.states.iter().map(state_code).collect(),
                ]
            })
            .collect(),
    }
}

/// The per-step table (stdout).
pub fn table(r: &MembranePathReport) -> String {
    let mut s = format!(
        "membrane load path: {} nodes, k = {}, T0 = {}, {}\n\n{:>5} {:>12} {:>12} {:>16} {:>6} {:>6} {:>14} {:>5}\n",
        r.nodes,
        r.stiffness,
        r.t0,
        r.law,
        "step",
        "T_end",
        "T_end/T0",
        "end displ.",
        "stick",
        "slip",
        "dissipation",
        "iter"
    );
    for p in &r.steps {
        s.push_str(&format!(
            "{:>5} {:>12.6} {:>12.6} {:>16.9e} {:>6} {:>6} {:>14.6e} {:>5}\n",
            p.step,
            p.end_tension,
            p.tension_ratio,
            p.end_displacement,
            p.stick_nodes,
            p.slip_nodes,
            p.dissipation,
            p.iterations
        ));
    }
    s.push_str(&format!(
        "\ndissipated over the path: {:.6e}\n",
        r.dissipation
    ));
    s
}

/// Writes `membrane-path.json` (stamped), `scene.toml`, `path.csv` (one row per step),
/// `profiles.csv` (one row per step and node: `w`, slip increment, `T`, friction force, state
/// 0 stick / 1 slip / 2 separated) and the hysteresis loop `hysteresis.{svg,png}` (end
/// displacement against tension ratio, from the wrapped state).
///
/// # Errors
/// Output errors.
pub fn write_out(dir: &Path, r: &MembranePathReport, scene: &Scene) -> Result<(), CliError> {
    let out = report_dir(dir, "membrane-path", r, Some(scene))?;
    let col = |f: fn(&PathStepReport) -> f64| r.steps.iter().map(f).collect::<Vec<_>>();
    let table = Table::new()
        .f64("step", col(|p| p.step as f64))
        .f64("end_tension", col(|p| p.end_tension))
        .f64("tension_ratio", col(|p| p.tension_ratio))
        .f64("end_displacement", col(|p| p.end_displacement))
        .f64("stick_nodes", col(|p| p.stick_nodes as f64))
        .f64("slip_nodes", col(|p| p.slip_nodes as f64))
        .f64("dissipation", col(|p| p.dissipation))
        .f64("iterations", col(|p| p.iterations as f64));
    out.write_csv("path.csv", &table)?;
    let n = r.theta.len();
    let mut columns: [Vec<f64>; 7] = Default::default();
    for (k, profile) in r.profiles.iter().enumerate() {
        columns[0].extend(std::iter::repeat_n((k + 1) as f64, n));
        columns[1].extend_from_slice(&r.theta);
        for (c, values) in columns[2..].iter_mut().zip(profile) {
            c.extend_from_slice(values);
        }
    }
    let [step, theta, w, du, tension, friction, state] = columns;
    let profiles = Table::new()
        .f64("step", step)
        .f64("theta", theta)
        .f64("displacement", w)
        .f64("slip_increment", du)
        .f64("tension", tension)
        .f64("friction", friction)
        .f64("state", state);
    out.write_csv("profiles.csv", &profiles)?;
    let mut x = vec![1.0];
    let mut y = vec![0.0];
    x.extend(col(|p| p.tension_ratio));
    y.extend(col(|p| p.end_displacement));
    let plot = LinePlot::new("Belt creep: end displacement along the load path")
        .x_label("T(theta_max) / T0")
        .y_label("end displacement")
        .series(Series::line("path", x, y));
    out.write_plot("hysteresis", &plot)?;
    Ok(())
}

/// The profile curve of a prism obstacle, which the membrane displacement model needs.
///
/// # Errors
/// [`CliError::Scene`] naming `obstacle.shape` for an obstacle that is not a prism.
pub(crate) fn membrane_profile(
    obstacle: &capstan_geometry::Obstacle,
) -> Result<capstan_geometry::ObstacleProfile<'_>, CliError> {
    obstacle
        .is_prism()
        .then(|| obstacle.profile())
        .flatten()
        .ok_or_else(|| CliError::Scene {
            origin: "obstacle.shape".into(),
            message: "the membrane displacement model needs a prism (cylinder, ellipse, prism or a registered prism)".into(),
        })
}
