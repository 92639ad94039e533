//! `--out DIR` files of the membrane and report commands: JSON for every report, CSV and a
//! plot for profiles (`capstan tension`, `capstan geometry`).

use std::path::Path;

use serde::Serialize;

use crate::commands::geometry::GeometryReport;
use crate::commands::tension::TensionReport;
use crate::error::CliError;
use crate::output::{LinePlot, OutputDir, Series, Table};
use crate::provenance::{Stamped, write_scene};
use crate::scene::Scene;

/// Writes `NAME.json` with its provenance ([`Stamped`]) and, for a report of a scene,
/// `scene.toml`.
///
/// # Errors
/// Output errors (a non-finite number refuses the file).
pub fn write_json_report<T: Serialize>(
    dir: &Path,
    name: &str,
    report: &T,
    scene: Option<&Scene>,
) -> Result<(), CliError> {
    report_dir(dir, name, report, scene).map(drop)
}

/// As [`write_json_report`]; the directory, for the report's other files.
///
/// # Errors
/// Output errors (a non-finite number refuses the file).
pub fn report_dir<T: Serialize>(
    dir: &Path,
    name: &str,
    report: &T,
    scene: Option<&Scene>,
) -> Result<OutputDir, CliError> {
    let out = OutputDir::create(dir)?;
    out.write_json(&format!("{name}.json"), &Stamped::new(report, scene))?;
    if let Some(scene) = scene {
        write_scene(&out, scene)?;
    }
    Ok(out)
}

/// Writes `tension.json` (stamped), `scene.toml`, `tension.csv` (`theta`, `tension`) and the profile plot
/// `tension.{svg,png}`.
///
/// # Errors
/// Output errors.
pub fn write_tension(dir: &Path, r: &TensionReport, scene: &Scene) -> Result<(), CliError> {
    let out = report_dir(dir, "tension", r, Some(scene))?;
    let table = Table::new()
        .f64("theta", r.theta.clone())
        .f64("tension", r.tension.clone());
    out.write_csv("tension.csv", &table)?;
    let plot = LinePlot::new(format!(
        "Tension profile (T_max / T0 = {:.6}, {})",
        r.tension_ratio, r.method
    ))
    .x_label("theta (rad)")
    .y_label("T (N)")
    .series(Series::line("T(theta)", r.theta.clone(), r.tension.clone()));
    out.write_plot("tension", &plot)?;
    Ok(())
}

/// Writes `geometry.json` (stamped), `scene.toml`, `geometry.csv` (one column per sampled quantity) and a plot of the
/// mean curvature `geometry.{svg,png}`.
///
/// # Errors
/// Output errors.
pub fn write_geometry(dir: &Path, r: &GeometryReport, scene: &Scene) -> Result<(), CliError> {
    let out = report_dir(dir, "geometry", r, Some(scene))?;
    let table = Table::new()
        .f64("x2", r.x2.clone())
        .f64("mean_curvature", r.mean_curvature.clone())
        .f64("gaussian_curvature", r.gaussian_curvature.clone())
        .f64("a22", r.a22.clone())
        .f64("b22", r.b22.clone())
        .f64("christoffel_222", r.christoffel_222.clone())
        .f64("sqrt_g_outer", r.sqrt_g_outer.clone());
    out.write_csv("geometry.csv", &table)?;
    let plot = LinePlot::new("Mean curvature on the contact interval")
        .x_label("x2 (rad)")
        .y_label("H (1/m)")
        .series(Series::line("H", r.x2.clone(), r.mean_curvature.clone()));
    out.write_plot("geometry", &plot)?;
    Ok(())
}
