//! `capstan contact-path`: the thick body (2-D or 3-D) along a load path with memory
//! (`loads.path`: the end traction `tau_max` of each state, `loads.tau0` held), each state
//! solved quasi-statically from the previous one with friction on the slip increment.

use std::path::Path;

use capstan_elasticity::contact::{ContactSolution, EndLoads, PathStep};
use capstan_elasticity::solvers::Observer;
use serde::Serialize;

use crate::commands::contact::{ContactArrays, Extremum, IntervalReport};
use crate::error::CliError;
use crate::output::{LinePlot, Pvd, Series, Table};
use crate::problem::{SolvedModel, SolverChoice};
use crate::provenance::report_dir;
use crate::scene::Scene;

/// One load state of the path (`capstan contact-path --json`: `steps[k]`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ContactPathStep {
    /// Step number (1 = the first value of `loads.path`).
    pub step: usize,
    /// `tau0` (`loads.tau0`).
    pub tau0: f64,
    /// `tau_max` (the path value).
    pub tau_max: f64,
    /// `tau_max / tau0`.
    pub tension_ratio: f64,
    /// Physical tangential displacement `sqrt(g_22) v^2` of the contact node at `theta_max`
    /// (a 3-D body: on its middle `x1` line), from rest.
    pub end_displacement: f64,
    /// `v^2` of largest magnitude over the body.
    pub max_azimuthal_displacement: Extremum,
    /// The paper's Slip of the step's slip increment (mean of the node states).
    pub slip_fraction: f64,
    /// Contact nodes that stick in this step (no further slip).
    pub stick_nodes: usize,
    /// Contact nodes that slip in this step (either way).
    pub slip_nodes: usize,
    /// Runs of positive / negative slip in this step.
    pub slip_intervals: Vec<IntervalReport>,
    /// Energy dissipated by friction in this step (per unit length of the prism in plane
    /// strain).
    pub dissipation: f64,
    /// Newton iterations of the step.
    pub newton_iterations: usize,
    /// Relative max-norm residual of the full system.
    pub residual: f64,
    /// Wall time of the step's solve, seconds.
    pub solve_seconds: f64,
    /// Fields on the contact surface: `slip` and `state` are those of the step's slip
    /// increment, `v2`, `v3` the displacement from rest.
    pub contact: ContactArrays,
}

/// `capstan contact-path --json` (keys are a public contract).
#[derive(Debug, Serialize)]
pub struct ContactPathReport {
    /// `friction.law`.
    pub law: String,
    /// The bulk discretisation (`fd`, `fem-q2`, `solid-q1`, ...).
    pub discretisation: &'static str,
    /// `[n2, n3]` (a 3-D body: `[n1, n2, n3]`).
    pub grid: Vec<usize>,
    /// The solver that ran every step and why.
    pub solver_choice: SolverChoice,
    /// `loads.tau0`.
    pub tau0: f64,
    /// Wall time of the set-up (assembly; the condensed solver's factorisation and
    /// condensation, once for the whole path), seconds.
    pub setup_seconds: f64,
    /// The steps, in the order of `loads.path`.
    pub steps: Vec<ContactPathStep>,
    /// Energy dissipated over the whole path.
    pub dissipation: f64,
    /// The model and every step's solution, for the body files.
    #[serde(skip)]
    pub bodies: Option<(SolvedModel, Vec<ContactSolution>)>,
}

/// Solves the scene's load path.
///
/// # Errors
/// `loads.path` missing (exit code 2); the scene's errors as `capstan contact`; a step without
/// equilibrium (3) or not converging (4), named by its number.
pub fn report(scene: &Scene) -> Result<ContactPathReport, CliError> {
    report_observed(scene, &mut crate::progress::CliObserver::new())
}

/// As [`report`], every Newton iterate of every step going to `observer` (which may stop
/// the path).
///
/// # Errors
/// As [`report`].
pub fn report_observed(
    scene: &Scene,
    observer: &mut dyn Observer<f64>,
) -> Result<ContactPathReport, CliError> {
    let values = scene
        .loads
        .path
        .clone()
        .ok_or_else(|| CliError::Scene {
            origin: "loads.path".into(),
            message: "contact-path needs the end tractions tau_max of the load states, e.g. --set 'loads.path=[2.0, 1.5, 2.0]'".into(),
        })?;
    let tau0 = scene.loads.tau0;
    let path: Vec<EndLoads> = values.iter().map(|&t| EndLoads::new(tau0, t)).collect();
    let problem = scene.build()?;
    let solved =
        problem
            .solve_path_observed(&path, observer)
            .map_err(|e| match CliError::from(e) {
                CliError::Contact(e) => crate::commands::contact::contact_budget(e, &scene.solver),
                e => e,
            })?;
    let steps: Vec<ContactPathStep> = solved
        .steps
        .iter()
        .enumerate()
        .map(|(k, s)| step_report(k + 1, s))
        .collect();
    let model = SolvedModel::Body(solved.model);
    let grid = if model.solid().is_some() {
        vec![scene.grid.n1, scene.grid.n2, scene.grid.n3]
    } else {
        vec![scene.grid.n2, scene.grid.n3]
    };
    Ok(ContactPathReport {
        law: scene.friction.law.clone(),
        discretisation: model.method(),
        grid,
        solver_choice: solved.choice,
        tau0,
        setup_seconds: solved.setup_seconds,
        dissipation: steps.iter().map(|s| s.dissipation).sum(),
        steps,
        bodies: Some((
            model,
            solved.steps.into_iter().map(|s| s.solution).collect(),
        )),
    })
}

fn step_report(step: usize, s: &PathStep) -> ContactPathStep {
    let sol = &s.solution;
    let c = &sol.contact;
    let count = |f: fn(i8) -> bool| c.state.iter().filter(|&&x| f(x)).count();
    ContactPathStep {
        step,
        tau0: sol.loads.tau0,
        tau_max: sol.loads.tau_max,
        tension_ratio: sol.loads.tension_ratio(),
        end_displacement: s.end_displacement,
        max_azimuthal_displacement: sol.max_azimuthal_displacement,
        slip_fraction: sol.slip_fraction,
        stick_nodes: count(|x| x == 0),
        slip_nodes: count(|x| x == 1 || x == -1),
        slip_intervals: sol.slip_intervals().map(IntervalReport::of).collect(),
        dissipation: s.dissipation,
        newton_iterations: sol.stats.newton_iterations,
        residual: sol.stats.residual,
        solve_seconds: s.seconds,
        contact: ContactArrays::of(c),
    }
}

/// The per-step table (stdout).
pub fn table(r: &ContactPathReport) -> String {
    let c = &r.solver_choice;
    let mut s = format!(
        "contact load path: {} on grid {:?} ({}), {} with {}, tau0 = {}, set-up {:.3} s\n\n{:>5} {:>10} {:>10} {:>16} {:>6} {:>6} {:>14} {:>5} {:>9}\n",
        r.law,
        r.grid,
        r.discretisation,
        c.nonlinear,
        c.linear,
        r.tau0,
        r.setup_seconds,
        "step",
        "tau_max",
        "ratio",
        "end displ.",
        "stick",
        "slip",
        "dissipation",
        "iter",
        "solve s"
    );
    for p in &r.steps {
        s.push_str(&format!(
            "{:>5} {:>10.6} {:>10.6} {:>16.9e} {:>6} {:>6} {:>14.6e} {:>5} {:>9.3}\n",
            p.step,
            p.tau_max,
            p.tension_ratio,
            p.end_displacement,
            p.stick_nodes,
            p.slip_nodes,
            p.dissipation,
            p.newton_iterations,
            p.solve_seconds
        ));
    }
    s.push_str(&format!(
        "\ndissipated over the path: {:.6e}\n",
        r.dissipation
    ));
    s
}

/// Writes `contact-path.json` (stamped), `scene.toml`, `path.csv` (one row per step),
/// `profiles.csv` (one row per step and contact node: `x2`, `v2`, `v3`, `normal_stress`,
/// `slip` (increment), `friction_traction`, `state`), one VTU per step `step_NNNN.vtu` with
/// their time series `path.pvd` (time = the step number), and the hysteresis loop
/// `hysteresis.{svg,png}` (end displacement from rest against tension ratio, one point per
/// step).
///
/// # Errors
/// Geometry or output errors.
pub fn write_out(dir: &Path, r: &ContactPathReport, scene: &Scene) -> Result<(), CliError> {
    let out = report_dir(dir, "contact-path", r, Some(scene))?;
    let col = |f: fn(&ContactPathStep) -> f64| r.steps.iter().map(f).collect::<Vec<_>>();
    let table = Table::new()
        .f64("step", col(|p| p.step as f64))
        .f64("tau0", col(|p| p.tau0))
        .f64("tau_max", col(|p| p.tau_max))
        .f64("tension_ratio", col(|p| p.tension_ratio))
        .f64("end_displacement", col(|p| p.end_displacement))
        .f64("slip_fraction", col(|p| p.slip_fraction))
        .f64("stick_nodes", col(|p| p.stick_nodes as f64))
        .f64("slip_nodes", col(|p| p.slip_nodes as f64))
        .f64("dissipation", col(|p| p.dissipation))
        .f64("newton_iterations", col(|p| p.newton_iterations as f64))
        .f64("solve_seconds", col(|p| p.solve_seconds));
    out.write_csv("path.csv", &table)?;
    let mut columns: [Vec<f64>; 8] = Default::default();
    for p in &r.steps {
        let c = &p.contact;
        columns[0].extend(std::iter::repeat_n(p.step as f64, c.x2.len()));
        for (column, values) in columns[1..7].iter_mut().zip([
            &c.x2,
            &c.v2,
            &c.v3,
            &c.normal_stress,
            &c.slip,
            &c.friction_traction,
        ]) {
            column.extend_from_slice(values);
        }
        columns[7].extend(c.state.iter().map(|&s| f64::from(s)));
    }
    let [step, x2, v2, v3, normal, slip, friction, state] = columns;
    let profiles = Table::new()
        .f64("step", step)
        .f64("x2", x2)
        .f64("v2", v2)
        .f64("v3", v3)
        .f64("normal_stress", normal)
        .f64("slip", slip)
        .f64("friction_traction", friction)
        .f64("state", state);
    out.write_csv("profiles.csv", &profiles)?;
    if let Some((model, solutions)) = &r.bodies {
        let mut pvd = Pvd::new();
        for (k, solution) in solutions.iter().enumerate() {
            let stem = format!("step_{:04}", k + 1);
            write_step_body(&out, scene, model, solution, &stem, (k + 1) as f64)?;
            pvd.push((k + 1) as f64, format!("{stem}.vtu"));
        }
        out.write("path.pvd", |w| pvd.write(w))?;
    }
    let x = col(|p| p.tension_ratio);
    let y = col(|p| p.end_displacement);
    let plot = LinePlot::new("Thick body: end displacement along the load path")
        .x_label("tau_max / tau0")
        .y_label("end displacement sqrt(g22) v2 at theta_max")
        .series(Series::line("path", x, y).with_markers());
    out.write_plot("hysteresis", &plot)?;
    Ok(())
}

/// One step's body file: the plane-strain body's VTU (time `time`) or the 3-D body's.
fn write_step_body(
    out: &crate::output::OutputDir,
    scene: &Scene,
    model: &SolvedModel,
    solution: &ContactSolution,
    stem: &str,
    time: f64,
) -> Result<(), CliError> {
    if let Some(disc) = model.plane() {
        let solved = crate::commands::contact::solved(scene, disc, solution.clone())?;
        crate::output::body::write_body(
            out,
            stem,
            &solved.obstacle,
            &solved.fields,
            &solution.contact,
            crate::output::body::BodyFiles {
                time: Some(time),
                plots: false,
                compression: scene.output.vtu_compression,
                obstacle: scene.output.vtu_obstacle,
            },
        )?;
    } else if let Some(solid) = model.solid() {
        let (hexahedra, fields, coordinates) =
            crate::commands::solid_contact::body_fields(scene, solid, solution)?;
        crate::output::solid_body::write_solid_body(
            out,
            stem,
            &hexahedra,
            &fields,
            &coordinates,
            &solution.contact,
            scene.output.vtu_compression,
        )?;
    }
    Ok(())
}
