//! `capstan contact` and `capstan threshold` for a 3-D body (`body.dimension = 3`): the body
//! on the box `[x1 - width/2, x1 + width/2] x [theta0, theta_max] x [0, h]` of any obstacle
//! (prisms and cones), Q1/Q2/Qp hexahedra, under the scene's friction law acting on the
//! two-component slip in the tangent plane.

use std::time::Instant;

use capstan_elasticity::Material;
use capstan_elasticity::contact::{
    ContactModel, ContactQuantities, ContactSolution, FullSystemSolver,
};
use capstan_elasticity::friction::AnyFrictionLaw;
use capstan_elasticity::registration::DiscretisationSettings;
use capstan_elasticity::solid::{SolidBody, SolidFields, SolidNavier};
use capstan_geometry::{Obstacle, ShellChart};

use crate::commands::accuracy::{self, ErrorEstimate};
use crate::commands::contact::{ContactReport, SceneSolver, condensed, loads, scene_law};
use crate::commands::solid_report::SolidReport;
use crate::error::CliError;
use crate::figures::solid_body::{solid_grid, write_solid_body};
use crate::output::QuadGrid;
use crate::progress::CliObserver;
use crate::scene::Scene;

/// The contact model of a 3-D scene.
pub type SolidSceneModel = ContactModel<SolidNavier<ShellChart<Obstacle>>, AnyFrictionLaw>;

/// The 3-D body a scene describes.
///
/// # Errors
/// A body reaching the apex of a cone (`body.x1 - body.width/2 <= 0`); finite differences;
/// bad material values.
pub fn solid_body(scene: &Scene) -> Result<SolidBody<Obstacle>, CliError> {
    let obstacle = scene.obstacle.build()?;
    let b = &scene.body;
    let x1 = [b.x1 - 0.5 * b.width, b.x1 + 0.5 * b.width];
    if obstacle.is_cone() && x1[0] <= 0.0 {
        return Err(CliError::Scene {
            origin: "body.x1".into(),
            message: format!(
                "`body.x1` = {} puts the body's side x1 = {} at or past the cone's apex (x1 = 0); allowed: body.x1 > body.width / 2 = {}",
                b.x1,
                x1[0],
                0.5 * b.width
            ),
        });
    }
    let settings = DiscretisationSettings {
        order: scene.discretisation.order,
        volumetric: scene.discretisation.volumetric,
        ..Default::default()
    };
    let order = scene
        .discretisation
        .method
        .scheme(&settings)?
        .solid_element()?;
    Ok(SolidBody {
        surface: obstacle,
        x1,
        theta: [scene.membrane.theta0, scene.membrane.theta_max],
        thickness: b.thickness,
        material: Material::new(b.young, b.poisson)?,
        nodes: [scene.grid.n1, scene.grid.n2, scene.grid.n3],
        order,
        volumetric: scene.discretisation.volumetric,
        sides: b.sides,
    })
}

/// The contact model of a 3-D scene.
///
/// # Errors
/// See [`solid_body`]; bad friction values; assembly errors (a degenerate chart).
pub fn model(scene: &Scene) -> Result<SolidSceneModel, CliError> {
    let (law, params, eps) = scene_law(scene)?;
    Ok(solid_body(scene)?.model(law, params, eps)?)
}

/// The report of a 3-D solution (the plane-strain keys, `x2` fastest, and `solid`).
fn report(
    scene: &Scene,
    model: &SolidSceneModel,
    sol: &ContactSolution,
    limiting: Option<[f64; 2]>,
    times: [f64; 2],
) -> ContactReport {
    let body = &scene.body;
    ContactReport {
        discretisation: capstan_elasticity::contact::ContactOperator::method(
            model.discretisation(),
        ),
        solid: Some(SolidReport {
            dimension: 3,
            grid: [scene.grid.n1, scene.grid.n2, scene.grid.n3],
            x1: [body.x1 - 0.5 * body.width, body.x1 + 0.5 * body.width],
            sides: body.sides,
            contact_unknowns: model.active().len(),
            contact: sol.contact.solid.clone().unwrap_or_default(),
        }),
        ..ContactReport::new(sol, limiting, [scene.grid.n2, scene.grid.n3], times)
    }
}

/// Solves a 3-D scene's contact problem with its solver (`newton`: boundary-only, `2m x 2m`
/// for `m` contact nodes; `full-newton` / `jacobi-newton`: the full system, no grid
/// sequencing in 3-D).
///
/// # Errors
/// Bad input (exit 2), no equilibrium (3), non-convergence (4).
pub fn solve(scene: &Scene) -> Result<(ContactReport, ContactSolution, SolidSceneModel), CliError> {
    solve_observed(scene, &mut CliObserver::new())
}

/// [`solve`] reporting every iteration to `observer`.
///
/// # Errors
/// See [`solve`]; [`capstan_elasticity::contact::ContactError::Interrupted`] when the
/// observer stops the solve.
pub fn solve_observed(
    scene: &Scene,
    observer: &mut dyn capstan_elasticity::solvers::Observer<f64>,
) -> Result<(ContactReport, ContactSolution, SolidSceneModel), CliError> {
    let named = |e| match e {
        CliError::Contact(e) => crate::commands::contact::contact_budget(e, &scene.solver),
        e => e,
    };
    let (mut report, sol, model) = solve_unnamed(scene, observer).map_err(named)?;
    let probes = accuracy::probes(scene);
    let quantities = ContactQuantities::new(&model, &sol, &probes)?;
    if scene.output.error_estimate
        && let Some(coarse) = accuracy::coarser_scene(scene)?
    {
        let (_, coarse_sol, coarse_model) =
            solve_unnamed(&coarse, &mut accuracy::StopOnly(observer)).map_err(named)?;
        let coarse_quantities = ContactQuantities::new(&coarse_model, &coarse_sol, &probes)?;
        report.estimated_error = Some(ErrorEstimate::from_levels(
            &quantities.scalars(&sol),
            &coarse_quantities.scalars(&coarse_sol),
            accuracy::grid_of(&coarse),
        ));
    }
    report.quantities = Some(quantities);
    Ok((report, sol, model))
}

fn solve_unnamed(
    scene: &Scene,
    observer: &mut dyn capstan_elasticity::solvers::Observer<f64>,
) -> Result<(ContactReport, ContactSolution, SolidSceneModel), CliError> {
    let method = SceneSolver::from_scene(scene)?;
    let loads = loads(scene);
    let t0 = Instant::now();
    let model = model(scene)?;
    let (sol, limiting, times) = match method {
        SceneSolver::Condensed => {
            let run = condensed(&model, scene, loads, observer, t0)?;
            (run.sol, run.limiting, run.times)
        }
        SceneSolver::FullNewton(_)
        | SceneSolver::FullNewtonMultigrid
        | SceneSolver::JacobiNewton => {
            let solver = FullSystemSolver::new(&model, method.full_settings_for(scene))?;
            let setup = t0.elapsed().as_secs_f64();
            let t1 = Instant::now();
            let sol = solver.solve_observed(loads, observer)?;
            (sol, None, [setup, t1.elapsed().as_secs_f64()])
        }
    };
    let report = report(scene, &model, &sol, limiting, times);
    Ok((report, sol, model))
}

/// Writes `contact.json` (stamped), `scene.toml` and `contact.csv` (the contact surface,
/// `x1` and `x2` per node with both tangential components).
///
/// # Errors
/// Output errors.
pub fn write_out(
    dir: &std::path::Path,
    report: &ContactReport,
    scene: &Scene,
) -> Result<crate::output::OutputDir, CliError> {
    let out = crate::figures::reports::report_dir(dir, "contact", report, Some(scene))?;
    let table = crate::commands::contact::contact_table(report);
    out.write_csv("contact.csv", &table)?;
    Ok(out)
}

/// The 3-D body's hexahedra, nodal fields and node coordinates `(x1, x2, x3)` for the
/// solution.
///
/// # Errors
/// Geometry failures.
pub fn body_fields(
    scene: &Scene,
    model: &SolidSceneModel,
    solution: &ContactSolution,
) -> Result<(QuadGrid, SolidFields, Vec<[f64; 3]>), CliError> {
    let op = model.discretisation();
    let grid = op.grid();
    let [n1, n2, n3] = grid.counts();
    let axis = |a: usize, n: usize| -> Vec<f64> {
        (0..n)
            .map(|i| {
                let mut node = [0; 3];
                node[a] = i;
                grid.coordinates(node)[a]
            })
            .collect()
    };
    let (x1, x2, x3) = (axis(0, n1), axis(1, n2), axis(2, n3));
    let hexahedra = solid_grid(&scene.obstacle.build()?, &x1, &x2, &x3)?;
    let fields = op.fields(&solution.displacement)?;
    let coordinates: Vec<[f64; 3]> = (0..grid.node_count())
        .map(|k| grid.coordinates(grid.node(k)))
        .collect();
    Ok((hexahedra, fields, coordinates))
}

/// Writes `body.vtu`: the 3-D body's fields on its hexahedra
/// ([`crate::figures::body::VTU_ARRAYS`] and
/// [`crate::figures::solid_body::SOLID_EXTRA_VTU_ARRAYS`]).
///
/// # Errors
/// Geometry or output errors.
pub fn write_body(
    out: &crate::output::OutputDir,
    scene: &Scene,
    model: &SolidSceneModel,
    solution: &ContactSolution,
) -> Result<(), CliError> {
    let (hexahedra, fields, coordinates) = body_fields(scene, model, solution)?;
    write_solid_body(
        out,
        "body",
        &hexahedra,
        &fields,
        &coordinates,
        &solution.contact,
        &scene.output,
    )?;
    Ok(())
}
