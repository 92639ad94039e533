//! `--out DIR` files of the membrane and report commands: JSON for every report, CSV and a
//! plot for profiles (`capstan tension`, `capstan geometry`).

use std::path::Path;

use crate::commands::geometry::GeometryReport;
use crate::commands::tension::TensionReport;
use crate::error::CliError;
use crate::output::{LinePlot, Series, Table};
use crate::provenance::report_dir;
use crate::scene::Scene;

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
