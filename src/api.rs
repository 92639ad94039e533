//! The studies a researcher runs on a scene, as library calls: each takes a [`Scene`] and
//! returns a typed, serialisable report (the JSON of the command of the same name). The
//! command line (`capstan tension`, `infer-mu`, `threshold`, `geometry`, `sweep`, `contact`,
//! `membrane-path`, `contact-path`)
//! and the Python package are thin layers over these functions; [`crate::Problem`] is the
//! contact problem itself, built in code or by [`Scene::build`].
//!
//! The `cli` and `commands` modules are the binary's internals (argument parsing, text
//! tables, files): they are not part of the library's API and may change without notice.
//!
//! # Example
//! ```
//! use capstan::{Scene, api};
//! // the default scene: a membrane over a semi-elliptical prism a = b = 2, mu = 1/2, half a turn
//! let scene = Scene::default();
//! let tension = api::tension(&scene).unwrap();
//! assert!((tension.tension_ratio - (0.5 * std::f64::consts::PI).exp()).abs() < 1e-9);
//! // the thick body on a coarse grid (any scene key, checked as `--set` checks it)
//! let coarse = scene.with_raw("grid.n2", "41", "set").unwrap().with_raw("grid.n3", "9", "set").unwrap();
//! let (report, _) = api::contact(&coarse).unwrap();
//! assert!(report.converged && report.slip_fraction > 0.0);
//! ```

use std::path::Path;

use capstan_elasticity::contact::ContactSolution;
use capstan_elasticity::solid::SolidFields;
use capstan_elasticity::solvers::Observer;

use crate::commands;
use crate::error::CliError;
use crate::output::QuadGrid;
use crate::scene::Scene;

pub use crate::commands::compare::{CompareReport, CompareRow};
pub use crate::commands::contact::{ContactReport, ContactRun, Solved as PlaneSolved};
pub use crate::commands::contact_path::{ContactPathReport, ContactPathStep};
pub use crate::commands::geometry::{GeometryDetail, GeometryReport};
pub use crate::commands::infer_mu::{FrictionModel, InferMuReport};
pub use crate::commands::membrane_path::{MembranePathReport, PathStepReport};
pub use crate::commands::sweep::{PointStatus, SweepPoint, SweepPoints, SweepReport};
pub use crate::commands::tension::TensionReport;
pub use crate::commands::threshold::ThresholdReport;

/// The membrane's tension profile over the obstacle (paper section 2: the generalised capstan
/// equation `dT/dtheta = mu T kappa-terms + loads`, Theorem 1 on prisms, Theorem 2 on cones):
/// `T(theta_max)`, the ratio `T(theta_max)/T(theta0)` and the profile.
///
/// # Errors
/// Bad scene values; no solution of the membrane equations (e.g. a non-convex interval).
pub fn tension(scene: &Scene) -> Result<TensionReport, CliError> {
    commands::tension::report(scene)
}

/// The friction coefficient implied by the tension pair `(membrane.t0, membrane.t_max)` under
/// `model`: the capstan closed form / quadrature `mu = ln(T_max/T0) / turning`, the membrane
/// displacement model (root of the full-slip ratio in `mu`), or the thick body
/// (Kikuchi–Oden: the `mu` at which the body starts to slide at that ratio).
///
/// # Errors
/// Bad scene values; [`capstan_friction::FrictionError::NoFrictionCoefficient`] when no `mu`
/// reproduces the pair; a spent work budget.
pub fn infer_mu(scene: &Scene, model: FrictionModel) -> Result<InferMuReport, CliError> {
    commands::infer_mu::report_for(scene, model)
}

/// The membrane displacement model along the load path `loads.path` (the tensions at
/// `theta_max` in turn, from the membrane wrapped at `membrane.t0`) with the nonsmooth law
/// `friction.law` (`exact-coulomb`) on each step's slip increment, by semismooth Newton:
/// per-step end displacement, stick/slip zones and dissipated energy (belt creep, hysteresis).
///
/// # Errors
/// No `loads.path`, a smooth `friction.law`, a non-prism obstacle or membrane loads (bad
/// input); the membrane sliding as a whole (no equilibrium); a spent
/// `membrane.max_newton_iterations`.
pub fn membrane_path(scene: &Scene) -> Result<MembranePathReport, CliError> {
    commands::membrane_path::report(scene)
}

/// [`membrane_path`] reporting every semismooth iteration to `observer` (stage `membrane`,
/// with the stick/slip counts).
///
/// # Errors
/// As [`membrane_path`].
pub fn membrane_path_observed(
    scene: &Scene,
    observer: &mut dyn Observer<f64>,
) -> Result<MembranePathReport, CliError> {
    commands::membrane_path::report_observed(scene, observer)
}

/// Writes a load path's `membrane-path.json`, `scene.toml`, `path.csv`, `profiles.csv` and the
/// hysteresis plot into `dir`.
///
/// # Errors
/// Output errors.
pub fn write_membrane_path(
    dir: &Path,
    report: &MembranePathReport,
    scene: &Scene,
) -> Result<(), CliError> {
    commands::membrane_path::write_out(dir, report, scene)
}

/// The thick body (2-D or 3-D) along the load path `loads.path` (the end tractions `tau_max`
/// in turn, `loads.tau0` held), the first state from rest and each later one from the state
/// before it, with friction on each step's slip increment: per-step end displacement,
/// stick/slip zones of the increment, dissipated energy and contact fields (hysteresis).
///
/// # Errors
/// No `loads.path` and the scene's errors (bad input); a step without equilibrium or not
/// converging, named by its number.
pub fn contact_path(scene: &Scene) -> Result<ContactPathReport, CliError> {
    commands::contact_path::report(scene)
}

/// [`contact_path`] reporting every Newton iterate of every step to `observer`.
///
/// # Errors
/// As [`contact_path`].
pub fn contact_path_observed(
    scene: &Scene,
    observer: &mut dyn Observer<f64>,
) -> Result<ContactPathReport, CliError> {
    commands::contact_path::report_observed(scene, observer)
}

/// Writes a load path's `contact-path.json`, `scene.toml`, `path.csv`, `profiles.csv`, one
/// VTU per step with `path.pvd`, and the hysteresis plot into `dir`.
///
/// # Errors
/// Output errors.
pub fn write_contact_path(
    dir: &Path,
    report: &ContactPathReport,
    scene: &Scene,
) -> Result<(), CliError> {
    commands::contact_path::write_out(dir, report, scene)
}

/// The threshold tension ratio `tau_max / tau0` beyond which the thick body has no static
/// equilibrium (it slides), with the slip fractions just below it.
///
/// # Errors
/// Bad scene values; the contact solver's errors.
pub fn threshold(scene: &Scene) -> Result<ThresholdReport, CliError> {
    commands::threshold::report(scene)
}

/// The obstacle's geometry (first and second fundamental forms, curvatures, Christoffel
/// symbols; on a cone the development map `phi(theta)` and its Jacobian) at the parameters
/// `x2`.
///
/// # Errors
/// Bad scene values; a degenerate chart at a point.
pub fn geometry_at(scene: &Scene, x2: &[f64]) -> Result<GeometryDetail, CliError> {
    commands::geometry::report_at(scene, x2)
}

/// One study per point of `at` (a scene key and its values): the tension, and the thick
/// body's contact where the scene solves it, each point with its status.
///
/// # Errors
/// Bad scene values or sweep points; a point's error does not stop the sweep (its status
/// says it).
pub fn sweep(scene: &Scene, at: SweepPoints<'_>) -> Result<SweepReport, CliError> {
    commands::sweep::report_scene(scene, at)
}

/// Writes a sweep's `sweep.json`, `sweep.csv` and plots into `dir` (stamped with the scene).
///
/// # Errors
/// Output errors.
pub fn write_sweep(dir: &Path, report: &SweepReport, scene: &Scene) -> Result<(), CliError> {
    commands::sweep::write_out(dir, report, scene)
}

/// The thick body in frictional contact with the obstacle (paper section 3), of the scene's
/// dimension: the report (stick/slip, Slip, extrema, solver statistics) and the run (the
/// solution and its model, for fields and files).
///
/// # Errors
/// Bad input, no equilibrium (the ratio beyond the threshold), non-convergence, a spent
/// work budget.
pub fn contact(scene: &Scene) -> Result<(ContactReport, ContactRun), CliError> {
    commands::contact::solve(scene)
}

/// [`contact`] reporting every iteration to `observer` (progress, interruption).
///
/// # Errors
/// As [`contact`]; an interruption by the observer.
pub fn contact_observed(
    scene: &Scene,
    observer: &mut dyn Observer<f64>,
) -> Result<(ContactReport, ContactRun), CliError> {
    commands::contact::solve_observed(scene, observer)
}

/// Writes a contact run's files into `dir`: `contact.json`, `scene.toml`, `contact.csv`, and
/// the body (`body.vtu`; plane strain also `displacement.csv` and plots).
///
/// # Errors
/// Geometry or output errors.
pub fn write_contact(
    dir: &Path,
    report: &ContactReport,
    run: &ContactRun,
    scene: &Scene,
) -> Result<(), CliError> {
    commands::contact_output::write_run(dir, report, run, scene)
}

/// The 3-D body's hexahedra (node positions in space), its displacement, strain and stress at
/// the nodes for `solution`, and the nodes' parameters `(x1, x2, x3)`.
///
/// # Errors
/// Geometry failures; a solution of another body.
pub fn solid_fields(
    scene: &Scene,
    body: &dyn capstan_elasticity::solid::SolidOutput,
    solution: &ContactSolution,
) -> Result<(QuadGrid, SolidFields, Vec<[f64; 3]>), CliError> {
    commands::solid_contact::body_fields(scene, body, solution)
}

/// The friction models compared (paper section 3 and its conclusions): for elliptical prisms
/// of several `b/a`, thicknesses and Poisson's ratios, the thick body's threshold ratio `r_K`
/// and the coefficient each model implies for the pair `(1, r_K)` (capstan `ln(r_K)/Psi`,
/// membrane, Kikuchi–Oden `nu_F`); `quick`: fewer configurations on coarser grids.
///
/// # Errors
/// A configuration's solver errors.
pub fn compare(quick: bool) -> Result<CompareReport, CliError> {
    commands::compare::report(quick)
}

/// Writes a comparison's `compare.json`, CSV tables and plots into `dir`.
///
/// # Errors
/// Output errors.
pub fn write_compare(dir: &Path, report: &CompareReport) -> Result<(), CliError> {
    commands::compare::write_out(dir, report)
}

/// A comparison as a text table.
pub fn compare_table(report: &CompareReport) -> String {
    commands::compare::table(report)
}
