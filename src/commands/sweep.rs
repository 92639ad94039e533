//! `capstan sweep`: one scene key varied over a range; Slip and the other contact numbers per
//! point, in parallel over the points.

use std::time::Instant;

use capstan_elasticity::contact::{
    BoundarySolver, ContactErrorKind, ContactModel, ContactOperator, ContactSolution, EndLoads,
};
use capstan_elasticity::friction::AnyFrictionLaw;
use rayon::prelude::*;
use serde::Serialize;

use crate::commands::contact::{loads, model};
use crate::error::CliError;
use crate::output::{OutputDir, Table};
use crate::provenance::{Stamped, write_scene};
use crate::scene::Scene;

/// How a sweep point ended (JSON: `converged`, `no-equilibrium`, `not-converged`,
/// `invalid-input`, `interrupted`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PointStatus {
    /// A solution was found.
    Converged,
    /// No static equilibrium exists (e.g. a tension ratio beyond limiting equilibrium).
    NoEquilibrium,
    /// The solver's budget was spent.
    NotConverged,
    /// The point's scene was refused.
    InvalidInput,
    /// The solve was stopped by its observer.
    Interrupted,
}

impl PointStatus {
    /// The status of a point whose solve failed with `error`.
    #[must_use]
    pub fn of_error(error: &CliError) -> Self {
        match error {
            CliError::Contact(c) => match c.kind() {
                ContactErrorKind::InvalidInput => Self::InvalidInput,
                ContactErrorKind::NoEquilibrium => Self::NoEquilibrium,
                ContactErrorKind::NotConverged => Self::NotConverged,
                ContactErrorKind::Interrupted => Self::Interrupted,
            },
            CliError::AccuracyNotReached { .. } => Self::NotConverged,
            _ => Self::InvalidInput,
        }
    }
}

capstan_elasticity::solvers::named_variants!(PointStatus {
    Converged => "converged",
    NoEquilibrium => "no-equilibrium",
    NotConverged => "not-converged",
    InvalidInput => "invalid-input",
    Interrupted => "interrupted",
});

/// One point of a sweep; also what a sweep part (`capstan sweep --shard`) stores and the MPI
/// workers send, read back exactly.
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepPoint {
    /// The swept key's value.
    pub value: f64,
    /// How the point ended.
    pub status: PointStatus,
    /// Whether a solution was found.
    pub converged: bool,
    /// Slip (mean state), `null` without a solution.
    pub slip_fraction: Option<f64>,
    /// Newton iterations.
    pub newton_iterations: Option<usize>,
    /// Interpolated stick interval.
    pub stick_interval: Option<[f64; 2]>,
    /// Signed max `v^2` with its place.
    pub max_azimuthal_displacement: Option<capstan_elasticity::contact::Extremum>,
    /// Signed max `v^3` with its place.
    pub max_radial_displacement: Option<capstan_elasticity::contact::Extremum>,
    /// `tau_max / tau0`.
    pub tension_ratio: f64,
    /// The error message of a failed point.
    pub error: Option<String>,
    /// With an accuracy target (`accuracy.tol`): the point's converging quantities, their
    /// estimates and the grid chosen; absent otherwise.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub accuracy: Option<PointAccuracy>,
}

/// A sweep point solved to an accuracy target.
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PointAccuracy {
    /// The x2-length of the slipping set (`slip_measure` of `capstan contact`).
    pub slip_measure: f64,
    /// The length of the contact face (`contact_measure`).
    pub contact_measure: f64,
    /// `estimated_error.quantities` of the point's contact report.
    pub estimated_error: std::collections::BTreeMap<String, Option<f64>>,
    /// The grid the target chose.
    pub grid: Vec<usize>,
}

/// `capstan sweep --json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SweepReport {
    /// The swept key.
    pub param: String,
    /// The points in order.
    pub points: Vec<SweepPoint>,
    /// Whether one bulk factorisation served every point (a sweep of `loads.tau0` or
    /// `loads.tau_max`).
    pub shared_factorisation: bool,
    /// Wall time, seconds.
    pub seconds: f64,
}

/// The sweep's values: `steps` points from `from` to `to`, both included.
///
/// # Errors
/// [`CliError::Scene`] for `steps == 0` or non-finite ends.
pub fn values(from: f64, to: f64, steps: usize) -> Result<Vec<f64>, CliError> {
    if steps == 0 || !from.is_finite() || !to.is_finite() {
        return Err(CliError::Scene {
            origin: "--steps/--from/--to".into(),
            message: "need finite --from, --to and --steps >= 1".into(),
        });
    }
    Ok((0..steps)
        .map(|i| {
            if steps == 1 {
                from
            } else {
                from + (to - from) * i as f64 / (steps - 1) as f64
            }
        })
        .collect())
}

fn point(
    value: f64,
    loads: EndLoads,
    result: Result<capstan_elasticity::contact::ContactSolution, CliError>,
) -> SweepPoint {
    match result {
        Ok(sol) => SweepPoint {
            value,
            status: PointStatus::Converged,
            converged: true,
            slip_fraction: Some(sol.slip_fraction),
            newton_iterations: Some(sol.stats.newton_iterations),
            stick_interval: sol.stick_interval.map(|i| [i.from, i.to]),
            max_azimuthal_displacement: Some(sol.max_azimuthal_displacement),
            max_radial_displacement: Some(sol.max_radial_displacement),
            tension_ratio: loads.tension_ratio(),
            error: None,
            accuracy: None,
        },
        Err(e) => SweepPoint {
            value,
            status: PointStatus::of_error(&e),
            converged: false,
            slip_fraction: None,
            newton_iterations: None,
            stick_interval: None,
            max_azimuthal_displacement: None,
            max_radial_displacement: None,
            tension_ratio: loads.tension_ratio(),
            error: Some(e.to_string()),
            accuracy: None,
        },
    }
}

/// Runs the sweep of `key` over `values` (in parallel; the linear algebra inside each point
/// stays sequential).
///
/// # Errors
/// Bad input that concerns every point (the base scene, an unknown key).
pub fn report(
    path: Option<&std::path::Path>,
    sets: &[String],
    key: &str,
    values: &[f64],
) -> Result<SweepReport, CliError> {
    report_indexed(path, sets, SweepPoints::new(key, values))
}

/// The VTU of sweep point `index` (`points/point_NNNN.vtu`, `TimeValue` = the swept value):
/// the plane-strain body's quadrilaterals or the 3-D body's hexahedra.
fn point_vtu(
    out: &OutputDir,
    index: usize,
    value: f64,
    scene: &Scene,
    model: &crate::commands::contact::SceneModel,
    sol: &capstan_elasticity::contact::ContactSolution,
) -> Result<(), CliError> {
    let Some(disc) = model.discretisation().plane() else {
        return match model.discretisation().solid() {
            Some(solid) => solid_point_vtu(out, index, value, scene, solid, sol),
            None => Ok(()),
        };
    };
    let solved = crate::commands::contact::solved(scene, disc, sol.clone())?;
    crate::output::body::write_body(
        out,
        &point_vtu_name(index),
        &solved.obstacle,
        &solved.fields,
        &sol.contact,
        crate::output::body::BodyFiles {
            time: Some(value),
            plots: false,
            compression: scene.output.vtu_compression,
            obstacle: scene.output.vtu_obstacle,
        },
    )?;
    Ok(())
}

fn point_vtu_name(index: usize) -> String {
    format!("points/point_{index:04}")
}

/// The points of a sweep: `key` set to each of `values`; with `fields`, the body fields of every
/// converged point written as `points/point_NNNN.vtu` into it (see [`write_out`] for the `.pvd`
/// collection), the `i`-th value being point `index(i)` of the whole sweep (a shard's points keep
/// their grid numbers).
#[derive(Clone, Copy)]
pub struct SweepPoints<'a> {
    /// The swept scene key.
    pub key: &'a str,
    /// Its values.
    pub values: &'a [f64],
    /// Where the VTU files of the converged points go, if anywhere.
    pub fields: Option<&'a OutputDir>,
    /// The number of the `i`-th value in the whole sweep (its VTU name).
    pub index: &'a (dyn Fn(usize) -> usize + Sync),
}

/// The numbering of a whole sweep: point `i` is the `i`-th value.
fn identity(i: usize) -> usize {
    i
}

impl<'a> SweepPoints<'a> {
    /// The whole sweep of `key` over `values`, no files.
    pub fn new(key: &'a str, values: &'a [f64]) -> Self {
        Self {
            key,
            values,
            fields: None,
            index: &identity,
        }
    }

    /// With the body fields written into `fields`.
    #[must_use]
    pub fn fields(self, fields: Option<&'a OutputDir>) -> Self {
        Self { fields, ..self }
    }
}

/// As [`report`], for the points `at` (body fields, numbering: [`SweepPoints`]).
///
/// # Errors
/// As [`report`].
pub fn report_indexed(
    path: Option<&std::path::Path>,
    sets: &[String],
    at: SweepPoints<'_>,
) -> Result<SweepReport, CliError> {
    let t = Instant::now();
    let scene = &Scene::load(path, sets)?;
    let with = |value: f64| -> Result<Scene, CliError> {
        let mut s = sets.to_vec();
        s.push(format!("{}={value}", at.key));
        Scene::load(path, &s)
    };
    run(scene, &with, at, t)
}

/// As [`report_indexed`] on a scene already loaded (`scene` with the key set to each value as
/// `--set key=value` sets it): the sweep of the Python package.
///
/// # Errors
/// As [`report`].
pub fn report_scene(scene: &Scene, at: SweepPoints<'_>) -> Result<SweepReport, CliError> {
    let t = Instant::now();
    let with = |value: f64| scene.with_raw(at.key, &value.to_string(), "--set");
    run(scene, &with, at, t)
}

/// The points of the sweep of `scene` over `values` of `key` (`with(v)` the scene of point
/// `v`) for a body whose model `build` makes and whose point VTU `vtu` writes: the
/// plane-strain body or the 3-D body.
#[allow(clippy::too_many_arguments)] // the sweep's inputs and the body's two hooks
fn points<D>(
    scene: &Scene,
    with: &(dyn Fn(f64) -> Result<Scene, CliError> + Sync),
    at: SweepPoints<'_>,
    tick: &(dyn Fn() + Sync),
    build: &BuildModel<D>,
    vtu: &PointVtu<D>,
) -> Result<Vec<SweepPoint>, CliError>
where
    D: ContactOperator + Sync + Send,
{
    let SweepPoints {
        key,
        values,
        fields,
        index,
    } = at;
    let shared = key == "loads.tau_max" || key == "loads.tau0";
    Ok(if shared {
        let model = build(scene)?;
        let solver = BoundarySolver::new(&model, scene.solver.contact_settings())?;
        values
            .par_iter()
            .enumerate()
            .map(|(i, &v)| {
                let mut l = loads(scene);
                if key == "loads.tau_max" {
                    l.tau_max = v;
                } else {
                    l.tau0 = v;
                }
                let mut r = solver.solve(l).map_err(CliError::from);
                if let (Some(out), Ok(sol)) = (fields, &r)
                    && let Err(e) = vtu(out, index(i), v, scene, &model, sol)
                {
                    r = Err(e);
                }
                tick();
                point(v, l, r)
            })
            .collect()
    } else {
        values
            .par_iter()
            .enumerate()
            .map(|(i, &v)| {
                let run = || -> Result<(EndLoads, Result<_, CliError>), CliError> {
                    let sc = with(v)?;
                    let m = build(&sc)?;
                    let solver = BoundarySolver::new(&m, sc.solver.contact_settings())?;
                    let l = loads(&sc);
                    let mut r = solver.solve(l).map_err(CliError::from);
                    if let (Some(out), Ok(sol)) = (fields, &r)
                        && let Err(e) = vtu(out, index(i), v, &sc, &m, sol)
                    {
                        r = Err(e);
                    }
                    Ok((l, r))
                };
                let p = match run() {
                    Ok((l, r)) => point(v, l, r),
                    Err(e) => point(v, loads(scene), Err(e)),
                };
                tick();
                p
            })
            .collect()
    })
}

/// Builds the contact model of a point's scene.
type BuildModel<D> = dyn Fn(&Scene) -> Result<ContactModel<D, AnyFrictionLaw>, CliError> + Sync;

/// Writes the VTU of one converged sweep point (`points/point_NNNN.vtu`).
type PointVtu<D> = dyn Fn(
        &OutputDir,
        usize,
        f64,
        &Scene,
        &ContactModel<D, AnyFrictionLaw>,
        &ContactSolution,
    ) -> Result<(), CliError>
    + Sync;

/// The VTU of sweep point `index` of a 3-D body (hexahedra, `TimeValue` = the swept value).
fn solid_point_vtu(
    out: &OutputDir,
    index: usize,
    value: f64,
    scene: &Scene,
    body: &dyn capstan_elasticity::solid::SolidOutput,
    sol: &ContactSolution,
) -> Result<(), CliError> {
    let (grid, fields, coordinates) =
        crate::commands::solid_contact::body_fields(scene, body, sol)?;
    let vtu = crate::output::solid_body::solid_vtu(&grid, &fields, &coordinates, &sol.contact)
        .encoding(scene.output.vtu_compression.encoding())
        .time(value);
    out.write_vtu(&format!("{}.vtu", point_vtu_name(index)), &vtu)?;
    Ok(())
}

/// The sweep of `scene` over `values` of `key`; `with(v)` is the scene of point `v`.
fn run(
    scene: &Scene,
    with: &(dyn Fn(f64) -> Result<Scene, CliError> + Sync),
    at: SweepPoints<'_>,
    t: Instant,
) -> Result<SweepReport, CliError> {
    let (key, values) = (at.key, at.values);
    let _sequential = capstan_elasticity::contact::sequential_linear_algebra_scope();
    let bar = crate::progress::bar(values.len(), key, false);
    let tick = || bar.inc(1);
    // Validate the key once (and that there is a point).
    with(*values.first().ok_or(CliError::Scene {
        origin: "--steps".into(),
        message: "no points".into(),
    })?)?;
    let shared = key == "loads.tau_max" || key == "loads.tau0";
    let points = if scene.accuracy.tol.is_some() {
        accurate_points(scene, with, values, &tick)
    } else {
        points(scene, with, at, &tick, &model, &point_vtu)?
    };
    bar.finish_and_clear();
    Ok(SweepReport {
        param: key.to_owned(),
        points,
        shared_factorisation: shared,
        seconds: t.elapsed().as_secs_f64(),
    })
}

/// The points of a sweep run to an accuracy target: each point's scene solved by
/// `capstan contact` with its target ([`crate::commands::accuracy::contact_to`]), in parallel.
fn accurate_points(
    scene: &Scene,
    with: &(dyn Fn(f64) -> Result<Scene, CliError> + Sync),
    values: &[f64],
    tick: &(dyn Fn() + Sync),
) -> Vec<SweepPoint> {
    values
        .par_iter()
        .map(|&v| {
            let solved = with(v).and_then(|sc| {
                crate::commands::contact::solve_observed(
                    &sc,
                    &mut capstan_elasticity::solvers::SilentObserver,
                )
                .map(|(report, _)| (loads(&sc), report))
            });
            tick();
            match solved {
                Ok((l, r)) => SweepPoint {
                    value: v,
                    status: PointStatus::Converged,
                    converged: true,
                    slip_fraction: Some(r.slip_fraction),
                    newton_iterations: Some(r.newton_iterations),
                    stick_interval: r.stick_interval,
                    max_azimuthal_displacement: Some(r.max_azimuthal_displacement),
                    max_radial_displacement: Some(r.max_radial_displacement),
                    tension_ratio: l.tension_ratio(),
                    error: None,
                    accuracy: r.quantities.as_ref().map(|q| PointAccuracy {
                        slip_measure: q.slip_measure,
                        contact_measure: q.contact_measure,
                        estimated_error: r
                            .estimated_error
                            .as_ref()
                            .map(|e| e.quantities.clone())
                            .unwrap_or_default(),
                        grid: r
                            .accuracy
                            .as_ref()
                            .map_or_else(|| r.grid.to_vec(), |a| a.chosen.grid.clone()),
                    }),
                },
                Err(e) => point(v, loads(scene), Err(e)),
            }
        })
        .collect()
}

/// Plain text: a title line, then one line per point under a header in the same columns.
pub fn table(r: &SweepReport) -> String {
    let line = |[value, status, slip, newton]: [&str; 4]| {
        format!("{value:>12} {status:>16} {slip:>10} {newton:>8}\n")
    };
    let mut s = format!(
        "sweep of {} ({} points, {:.2} s)\n",
        r.param,
        r.points.len(),
        r.seconds
    );
    s += &line([&r.param, "status", "Slip", "Newton"]);
    for p in &r.points {
        let slip = p.slip_fraction.map_or("-".into(), |x| format!("{x:.4}"));
        let newton = p.newton_iterations.map_or("-".into(), |x| x.to_string());
        s += &line([&format!("{:.6}", p.value), p.status.name(), &slip, &newton]);
        if let Some(a) = &p.accuracy {
            // what the accuracy target chose for the point, and the slip measure it reached
            let e = a
                .estimated_error
                .get("slip_measure")
                .copied()
                .flatten()
                .map_or_else(String::new, |e| format!(" +- {e:.1e}"));
            s += &format!(
                "{:>12} slip measure {:.6}{e} of {:.6}, chosen grid {:?}\n",
                "", a.slip_measure, a.contact_measure, a.grid
            );
        }
    }
    s
}

/// Writes `sweep.json` (with `capstan_version` and the resolved base `scene`), `scene.toml`,
/// `sweep.csv`, the plot `sweep.{svg,png}` (Slip against the swept value) and, when `points/point_NNNN.vtu` files were written by [`report_indexed`],
/// their collection `sweep.pvd` (time = the swept value; ParaView reads it, meshio does not).
///
/// # Errors
/// Output errors.
pub fn write_out(dir: &std::path::Path, r: &SweepReport, scene: &Scene) -> Result<(), CliError> {
    let out = OutputDir::create(dir)?;
    out.write_json("sweep.json", &Stamped::new(r, Some(scene)))?;
    write_scene(&out, scene)?;
    let mut pvd = crate::output::Pvd::new();
    for (i, p) in r.points.iter().enumerate() {
        let name = format!("{}.vtu", point_vtu_name(i));
        if p.converged && out.file(&name)?.is_file() {
            pvd.push(p.value, name);
        }
    }
    if !pvd.entries().is_empty() {
        out.write("sweep.pvd", |w| pvd.write(w))?;
    }
    let ok: Vec<&SweepPoint> = r.points.iter().filter(|p| p.converged).collect();
    if !ok.is_empty() {
        let plot = crate::output::LinePlot::new(format!("Slip against {}", r.param))
            .x_label(r.param.clone())
            .y_label("Slip (mean of -1/0/+1 states)")
            .series(
                crate::output::Series::line(
                    "Slip",
                    ok.iter().map(|p| p.value).collect::<Vec<_>>(),
                    ok.iter()
                        .map(|p| p.slip_fraction.unwrap_or(0.0))
                        .collect::<Vec<_>>(),
                )
                .with_markers(),
            );
        out.write_plot("sweep", &plot)?;
    }
    let converged: Vec<&SweepPoint> = r.points.iter().filter(|p| p.converged).collect();
    let column =
        |value: fn(&SweepPoint) -> f64| converged.iter().map(|p| value(p)).collect::<Vec<_>>();
    let table = Table::new()
        .f64("value", column(|p| p.value))
        .f64("slip_fraction", column(|p| p.slip_fraction.unwrap_or(0.0)))
        .f64("tension_ratio", column(|p| p.tension_ratio))
        .f64(
            "max_v2",
            column(|p| p.max_azimuthal_displacement.map_or(0.0, |e| e.value)),
        )
        .f64(
            "max_v3",
            column(|p| p.max_radial_displacement.map_or(0.0, |e| e.value)),
        );
    out.write_csv("sweep.csv", &table)?;
    Ok(())
}
