//! `capstan contact`: the thick body on a rough prism under the scene's friction law
//! (`friction.law` through `AnyFrictionLaw`; regularised Coulomb by default, paper section 3).

use std::sync::atomic::{AtomicBool, Ordering};

use capstan_elasticity::contact::{ContactQuantities, ContactSolution, EndLoads, ThickBody};
use capstan_elasticity::solvers::Observer;
use capstan_elasticity::{Discretisation, Material};
use serde::Serialize;

use crate::commands::accuracy::{self, ErrorEstimate};
use crate::error::CliError;
use crate::progress::CliObserver;
use crate::scene::Scene;

/// The contact model a scene describes (either dimension).
pub type SceneModel = crate::problem::Model;

/// The paper's grid condition for its Jacobi iteration (section 3): `psi0 dx2 <= dx3` for every
/// `psi0 = sqrt(g_22)` on the body, with `dx2 = (theta_max - theta0)/(n2 - 1)` and
/// `dx3 = h/(n3 - 1)`. Returns `(max psi0 dx2, dx3)` over the grid's nodes on `x3 = 0` and
/// `x3 = h` (`sqrt(g_22)` is largest on a face of a convex body), or `None` for a body that
/// is not plane strain on a prism.
///
/// # Errors
/// A geometry error at a grid node.
pub fn paper_grid_condition(scene: &Scene) -> Result<Option<(f64, f64)>, CliError> {
    let obstacle = scene.obstacle.build()?;
    if scene.body.dimension != 2 || !obstacle.is_prism() {
        return Ok(None);
    }
    let (m, g, h) = (&scene.membrane, &scene.grid, scene.body.thickness);
    let dx2 = (m.theta_max - m.theta0) / (g.n2 - 1) as f64;
    let dx3 = h / (g.n3 - 1) as f64;
    let chart = capstan_geometry::ShellChart::new(&obstacle);
    let mut psi0 = 0.0f64;
    for i in 0..g.n2 {
        let x2 = m.theta0 + dx2 * i as f64;
        for x3 in [0.0, h] {
            psi0 = psi0.max(chart.point([0.0, x2, x3])?.metric[1][1].sqrt());
        }
    }
    Ok(Some((psi0 * dx2, dx3)))
}

/// Warns on stderr (unless `--quiet`) when the paper's grid condition is violated and the
/// scene iterates with Jacobi (`solver.nonlinear = "jacobi-newton"` or `solver.linear =
/// "jacobi"`), the method the condition is stated for; with other solvers a note at `-v`.
///
/// # Errors
/// As [`paper_grid_condition`].
pub fn warn_grid_condition(scene: &Scene) -> Result<(), CliError> {
    let Some((lhs, dx3)) = paper_grid_condition(scene)? else {
        return Ok(());
    };
    if lhs <= dx3 {
        return Ok(());
    }
    let jacobi = scene.solver.nonlinear == "jacobi-newton" || scene.solver.linear == "jacobi";
    let message = format!(
        "warning: the paper's grid condition psi0 dx2 <= dx3 is violated: max psi0 dx2 = {lhs:.4e} > dx3 = {dx3:.4e} (grid.n2 = {}, grid.n3 = {}){}",
        scene.grid.n2,
        scene.grid.n3,
        if jacobi {
            "; the paper states it for its Jacobi iteration"
        } else {
            "; the direct solvers converge without it (docs/verification.md)"
        }
    );
    crate::progress::note(u8::from(!jacobi), &message);
    Ok(())
}

/// The thick body a scene describes: `obstacle.*` (a prism), `body.*`, `grid.*`,
/// `discretisation.*`, and the contact interval `membrane.theta0`, `membrane.theta_max`
/// (default `[-pi/2, pi/2]`).
///
/// # Errors
/// Bad obstacle (a cone), geometry or material values.
pub fn thick_body(scene: &Scene) -> Result<ThickBody, CliError> {
    if scene.body.dimension != 2 {
        return Err(CliError::Scene {
            origin: "body.dimension".into(),
            message: format!(
                "`body.dimension` = {}: this command solves the plane-strain body only (allowed: 2); `capstan contact`, `sweep` and `threshold` solve the 3-D body",
                scene.body.dimension
            ),
        });
    }
    let obstacle = scene.obstacle.build()?;
    if !obstacle.is_prism() {
        return Err(CliError::Scene {
            origin: "obstacle.shape".into(),
            message:
                "the thick body needs a prism (cylinder, ellipse or prism); cones are membrane-only"
                    .into(),
        });
    }
    Ok(ThickBody {
        obstacle,
        theta: [scene.membrane.theta0, scene.membrane.theta_max],
        thickness: scene.body.thickness,
        material: Material::new(scene.body.young, scene.body.poisson)?,
        n2: scene.grid.n2,
        n3: scene.grid.n3,
        method: scene.discretisation.method,
        volumetric: scene.discretisation.volumetric,
        order: scene.discretisation.order,
        grading: scene.discretisation.grading()?,
        body_force: scene.loads.body_force_field(2)?,
    })
}

/// The contact model of a scene, plane strain or 3-D ([`Scene::build`], then
/// [`crate::Problem::model`]).
///
/// # Errors
/// See [`Scene::build`]; bad friction values; assembly errors.
pub fn model(scene: &Scene) -> Result<SceneModel, CliError> {
    Ok(scene.build()?.model()?)
}

/// The scene's loads.
pub fn loads(scene: &Scene) -> EndLoads {
    EndLoads::new(scene.loads.tau0, scene.loads.tau_max)
}

/// A signed extreme value with its place (JSON `{"value", "x2", "x3"}`).
pub type Extremum = capstan_elasticity::contact::Extremum;

/// One interval of the contact surface.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct IntervalReport {
    /// `+1` positive slip, `-1` negative slip, `0` stick.
    pub state: i8,
    /// Interpolated start (where `u` crosses `+-eps`).
    pub from: f64,
    /// Interpolated end.
    pub to: f64,
    /// `x2` of the first and last node.
    pub nodes: [f64; 2],
}

impl IntervalReport {
    /// The report of one interval of a solution's contact surface.
    pub fn of(i: &capstan_elasticity::contact::StateInterval) -> Self {
        Self {
            state: i.state,
            from: i.from,
            to: i.to,
            nodes: i.nodes,
        }
    }
}

/// The contact surface fields.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ContactArrays {
    /// `x2` of the contact nodes.
    pub x2: Vec<f64>,
    /// `v^2` (rad on an angular chart).
    pub v2: Vec<f64>,
    /// `v^3` (0: bilateral).
    pub v3: Vec<f64>,
    /// `sigma_n = T^3_3` (negative in compression).
    pub normal_stress: Vec<f64>,
    /// `T^3_2`.
    pub shear_stress: Vec<f64>,
    /// `+1`, `-1`, `0`; `2` lifted off (unilateral contact).
    pub state: Vec<i8>,
    /// Physical tangential displacement `sqrt(g_22) v^2`.
    pub slip: Vec<f64>,
    /// Physical friction traction on the body.
    pub friction_traction: Vec<f64>,
    /// `contact.kind = "unilateral"`: whether each node has lifted off (its `state` is then
    /// 2); absent for bilateral contact.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub separated: Option<Vec<bool>>,
}

impl ContactArrays {
    /// The fields of a solution's contact profile.
    pub fn of(c: &capstan_elasticity::contact::ContactProfile) -> Self {
        Self {
            x2: c.x2.clone(),
            v2: c.v2.clone(),
            v3: c.v3.clone(),
            normal_stress: c.normal_stress.clone(),
            shear_stress: c.shear_stress.clone(),
            state: c.state.clone(),
            slip: c.slip.clone(),
            friction_traction: c.friction_traction.clone(),
            separated: c.separated.clone(),
        }
    }
}

/// `capstan contact --json` (keys are a public contract).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ContactReport {
    /// `converged`.
    pub status: &'static str,
    /// `true`.
    pub converged: bool,
    /// Newton iterations in total (`full-newton`: on the scene's grid; `grid_sequence` has
    /// the coarser levels).
    pub newton_iterations: usize,
    /// The paper's Slip (mean of the node states).
    pub slip_fraction: f64,
    /// `[from, to]` of the longest stick run (interpolated), `null` if nothing sticks.
    pub stick_interval: Option<[f64; 2]>,
    /// `x2` of the first and last node of that run.
    pub stick_nodes: Option<[f64; 2]>,
    /// Runs of positive / negative slip.
    pub slip_intervals: Vec<IntervalReport>,
    /// `v^2` of largest magnitude over the body.
    pub max_azimuthal_displacement: Extremum,
    /// `v^3` of largest magnitude over the body.
    pub max_radial_displacement: Extremum,
    /// Fields on the contact surface.
    pub contact: ContactArrays,
    /// `tau0`.
    pub tau0: f64,
    /// `tau_max`.
    pub tau_max: f64,
    /// `tau_max / tau0`.
    pub tension_ratio: f64,
    /// `condensed`, `full-newton` or `full-jacobi-newton`.
    pub method: &'static str,
    /// The solver that ran and why (`solver.nonlinear = "auto"` chooses by size); absent for a
    /// report not made by a solve of the facade.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub solver_choice: Option<crate::problem::SolverChoice>,
    /// Load-continuation steps.
    pub continuation_steps: usize,
    /// Relative max-norm residual of the full system.
    pub residual: f64,
    /// Inner Jacobi iterations (Jacobi–Newton only).
    pub linear_iterations: usize,
    /// `[lower, upper]` tension ratios friction can hold, when the body can slide rigidly (circle);
    /// an entry is `null` when friction holds every ratio in that direction (no finite limit).
    pub limiting_ratios: Option<[Option<f64>; 2]>,
    /// Contact nodes under tension (`sigma_n > 0`; unilateral contact: of the nodes in
    /// contact).
    pub tensile_contact_nodes: usize,
    /// `contact.kind = "unilateral"`: the runs of lifted-off nodes, `[from, to]` in `x2`
    /// (ends midway to the neighbouring node in contact; a 3-D body: along its middle `x1`
    /// line); absent for bilateral contact.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lift_off_intervals: Option<Vec<[f64; 2]>>,
    /// `[n2, n3]`.
    pub grid: [usize; 2],
    /// Wall time of the setup (bulk factorisation and condensation), seconds; for
    /// `full-newton` only the scene's parsing (assembly and factorisations are in the solve).
    pub setup_seconds: f64,
    /// Wall time of the nonlinear solve, seconds.
    pub solve_seconds: f64,
    /// The bulk discretisation (`discretisation.method`): `fd`, `fem-q1` or `fem-q2`.
    pub discretisation: &'static str,
    /// `full-newton` only: `[n2, n3, newton_iterations]` of each grid-sequencing level,
    /// coarsest first (the coarsest solved boundary-only, each finer level by Newton from the
    /// coarser solution interpolated; the last is the scene's grid). `null` otherwise.
    pub grid_sequence: Option<Vec<[usize; 3]>>,
    /// A 3-D body (`body.dimension = 3`): its grid, extent and the `x1` fields of the contact
    /// surface; absent in plane strain.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub solid: Option<crate::commands::solid_report::SolidReport>,
    /// The converging quantities (keys `slip_measure`, `slip_physical_measure`,
    /// `contact_measure`, `normal_stress_probes`: [`ContactQuantities`]).
    #[serde(flatten)]
    pub quantities: Option<ContactQuantities>,
    /// The estimated discretisation error of every converging quantity
    /// ([`crate::commands::accuracy`]); absent with `output.error_estimate = false` or when the
    /// method has no coarser level.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub estimated_error: Option<ErrorEstimate>,
    /// With an accuracy target (`accuracy.tol`): the target, the chosen discretisation, grid
    /// and solver, and every refinement step ([`accuracy::AccuracyReport`]); absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub accuracy: Option<accuracy::AccuracyReport>,
}

impl ContactReport {
    /// The report of a solution.
    pub fn new(
        sol: &ContactSolution,
        limiting: Option<[f64; 2]>,
        grid: [usize; 2],
        times: [f64; 2],
    ) -> Self {
        let c = &sol.contact;
        Self {
            status: "converged",
            converged: true,
            newton_iterations: sol.stats.newton_iterations,
            slip_fraction: sol.slip_fraction,
            stick_interval: sol.stick_interval.map(|i| [i.from, i.to]),
            stick_nodes: sol.stick_interval.map(|i| i.nodes),
            slip_intervals: sol.slip_intervals().map(IntervalReport::of).collect(),
            max_azimuthal_displacement: sol.max_azimuthal_displacement,
            max_radial_displacement: sol.max_radial_displacement,
            contact: ContactArrays::of(c),
            tau0: sol.loads.tau0,
            tau_max: sol.loads.tau_max,
            tension_ratio: sol.loads.tension_ratio(),
            method: sol.stats.method,
            solver_choice: None,
            continuation_steps: sol.stats.continuation_steps,
            residual: sol.stats.residual,
            linear_iterations: sol.stats.linear_iterations,
            limiting_ratios: limiting.map(|r| r.map(|x| Some(x).filter(|x| x.is_finite()))),
            tensile_contact_nodes: sol.tensile_contact_nodes,
            lift_off_intervals: sol
                .lift_off_intervals
                .as_ref()
                .map(|zones| zones.iter().map(|i| [i.from, i.to]).collect()),
            grid,
            setup_seconds: times[0],
            solve_seconds: times[1],
            discretisation: "fd",
            grid_sequence: None,
            solid: None,
            quantities: None,
            estimated_error: None,
            accuracy: None,
        }
    }
}

/// The displacement at every node of the body.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct NodalDisplacement {
    /// `x2` of the nodes.
    pub x2: Vec<f64>,
    /// `x3` of the nodes.
    pub x3: Vec<f64>,
    /// `v^2`.
    pub v2: Vec<f64>,
    /// `v^3`.
    pub v3: Vec<f64>,
}

/// A solved scene: the solution, its nodal displacement and fields, and the obstacle.
#[derive(Debug, Clone)]
pub struct Solved {
    /// The solution.
    pub solution: ContactSolution,
    /// Nodal displacement.
    pub nodes: NodalDisplacement,
    /// Displacement, strain and stress at the nodes.
    pub fields: capstan_elasticity::NodalFields,
    /// The obstacle (for the body's points in E^3).
    pub obstacle: capstan_geometry::Obstacle,
}

/// The nodal fields of a solution on the plane-strain discretisation `disc`, with the scene's
/// obstacle.
///
/// # Errors
/// Geometry failures; bad obstacle values.
pub fn solved(
    scene: &Scene,
    disc: &dyn Discretisation,
    solution: ContactSolution,
) -> Result<Solved, CliError> {
    use capstan_elasticity::Component;
    let grid = disc.grid();
    let mut nodes = NodalDisplacement::default();
    for i in 0..grid.n2() {
        for j in 0..grid.n3() {
            nodes.x2.push(grid.x2(i));
            nodes.x3.push(grid.x3(j));
            nodes
                .v2
                .push(solution.displacement[disc.dof([i, j], Component::X2)]);
            nodes
                .v3
                .push(solution.displacement[disc.dof([i, j], Component::X3)]);
        }
    }
    let fields = disc.fields(&solution.displacement)?;
    Ok(Solved {
        solution,
        nodes,
        fields,
        obstacle: scene.obstacle.build()?,
    })
}

/// What `capstan contact` solved, for its outputs: the plane-strain body with its nodal
/// fields, or the 3-D body.
#[derive(Debug)]
pub enum ContactRun {
    /// Plane strain: the solution with its nodal displacement and fields.
    Plane(Solved),
    /// The 3-D body: the solution and the model it belongs to (box grid and fields through
    /// [`crate::problem::SolvedModel::solid`]).
    Solid {
        /// The solution.
        solution: ContactSolution,
        /// The model.
        model: crate::problem::SolvedModel,
    },
}

impl ContactRun {
    /// The solution, whichever body.
    pub fn solution(&self) -> &ContactSolution {
        match self {
            Self::Plane(solved) => &solved.solution,
            Self::Solid { solution, .. } => solution,
        }
    }
}

/// Solves a scene's contact problem (either dimension) with its solver, reporting progress
/// as the command line does ([`CliObserver`]: `-v` lines, a spinner on a terminal).
///
/// # Errors
/// Bad input (exit 2), no equilibrium (3), non-convergence (4).
pub fn solve(scene: &Scene) -> Result<(ContactReport, ContactRun), CliError> {
    solve_observed(scene, &mut CliObserver::new())
}

/// As [`solve`], with every iteration of the solve reported to `observer` (which may stop it:
/// [`capstan_elasticity::contact::ContactError::Interrupted`]). The Python package passes its callback and Ctrl-C check
/// here. The scene becomes a [`crate::Problem`] ([`Scene::build`]) and is solved by it; a
/// budget error names the scene keys that set the budget.
///
/// # Errors
/// As [`solve`]; [`capstan_elasticity::contact::ContactError::Interrupted`] when `observer` asks to stop.
pub fn solve_observed(
    scene: &Scene,
    observer: &mut dyn Observer<f64>,
) -> Result<(ContactReport, ContactRun), CliError> {
    let named = |e| match CliError::from(e) {
        CliError::Contact(e) => contact_budget(e, &scene.solver),
        e => e,
    };
    let probes = accuracy::probes(scene);
    if let Some(target) = scene.accuracy.target()? {
        let (solved, problem, estimate, accuracy) = accuracy::contact_to(scene, &target, observer)
            .map_err(|e| match e {
                CliError::Contact(e) => contact_budget(e, &scene.solver),
                e => e,
            })?;
        let mut report = report_of(scene, &solved);
        report.grid = [problem.body.n2, problem.body.n3];
        if let Some(solid) = report.solid.as_mut() {
            solid.grid = problem.grid().try_into().unwrap_or(solid.grid);
        }
        report.quantities = Some(solved.quantities(&probes)?);
        report.estimated_error = Some(estimate);
        report.accuracy = Some(accuracy);
        return Ok((report, run_of(scene, solved)?));
    }
    let problem = scene.build()?;
    let coarse = match scene.output.error_estimate {
        true => problem.coarser()?,
        false => None,
    };
    // The level one grid coarser for the error estimate: grid sequencing solves it on the way;
    // otherwise it is solved on a second thread beside the fine solve (the second core), and
    // stopped when the fine solve fails or is interrupted. A collective backend (`petsc`:
    // every rank must make the same MPI calls in one order, from one thread) solves it after
    // the fine solve, on this thread (below).
    let (solved, coarse_solved) = match coarse.as_ref() {
        Some(coarse)
            if !problem.sequences_grids()
                && !crate::features::collective_backend(&scene.solver.linear) =>
        {
            let stop = AtomicBool::new(false);
            std::thread::scope(|scope| {
                let side = scope.spawn(|| coarse.solve_observed(&mut StopFlag(&stop)));
                let fine = problem.solve_observed(observer);
                if fine.is_err() {
                    stop.store(true, Ordering::Relaxed);
                }
                let side = side
                    .join()
                    .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
                (fine, Some(side))
            })
        }
        _ => (problem.solve_observed(observer), None),
    };
    let solved = solved.map_err(named)?;
    let mut report = report_of(scene, &solved);
    let scalars = solved.scalars(&probes)?;
    report.quantities = Some(solved.quantities(&probes)?);
    if let Some(coarse) = coarse {
        let coarse_scalars = match (&solved.coarser, coarse_solved) {
            (Some(level), _) => level.scalars(&probes)?,
            (None, Some(side)) => side.map_err(named)?.scalars(&probes)?,
            (None, None) => coarse
                .solve_observed(&mut accuracy::StopOnly(observer))
                .map_err(named)?
                .scalars(&probes)?,
        };
        report.estimated_error = Some(ErrorEstimate::from_levels(
            &scalars,
            &coarse_scalars,
            coarse.grid(),
        ));
    }
    Ok((report, run_of(scene, solved)?))
}

/// An observer that reports nothing and stops when `flag` is set (the side solve of the error
/// estimate, stopped when the fine solve fails).
struct StopFlag<'a>(&'a AtomicBool);

impl Observer<f64> for StopFlag<'_> {
    fn iteration(&mut self, _progress: &capstan_elasticity::solvers::Progress<f64>) {}

    fn interrupted(&mut self) -> bool {
        self.0.load(Ordering::Relaxed)
    }
}

/// The outputs' view of a solved problem.
fn run_of(scene: &Scene, solved: crate::problem::Solved) -> Result<ContactRun, CliError> {
    Ok(match solved.model.plane() {
        Some(disc) => ContactRun::Plane(self::solved(scene, disc, solved.solution)?),
        None => ContactRun::Solid {
            solution: solved.solution,
            model: solved.model,
        },
    })
}

/// The report of a solved scene (the 3-D body adds `solid`).
fn report_of(scene: &Scene, solved: &crate::problem::Solved) -> ContactReport {
    let body = &scene.body;
    ContactReport {
        discretisation: solved.model.method(),
        solver_choice: Some(solved.choice.clone()),
        grid_sequence: solved.grid_sequence.clone(),
        solid: solved
            .model
            .solid()
            .map(|_| crate::commands::solid_report::SolidReport {
                dimension: 3,
                grid: [scene.grid.n1, scene.grid.n2, scene.grid.n3],
                x1: [body.x1 - 0.5 * body.width, body.x1 + 0.5 * body.width],
                sides: body.sides,
                contact_unknowns: solved.model.contact_unknowns(),
                contact: solved.solution.contact.solid.clone().unwrap_or_default(),
            }),
        ..ContactReport::new(
            &solved.solution,
            solved.limiting,
            [scene.grid.n2, scene.grid.n3],
            solved.times,
        )
    }
}

/// A contact error that a work budget of the scene may explain, with the keys named
/// ([`CliError::ContactBudget`]); other errors pass through.
pub(crate) fn contact_budget(
    e: capstan_elasticity::contact::ContactError,
    solver: &crate::scene::SolverSpec,
) -> CliError {
    use capstan_elasticity::contact::ContactError;
    use capstan_elasticity::solvers::SolverError;
    let iterative = matches!(solver.linear.as_str(), "jacobi" | "gauss-seidel")
        && solver.nonlinear != "newton"
        || solver.nonlinear == "jacobi-newton";
    let budget = match &e {
        ContactError::NotConverged { .. } | ContactError::LoadStepFailed { .. } => {
            format!(
                "`solver.max_iterations` = {} Newton iterations per load step, `solver.max_continuation_steps` = {} steps, `solver.min_load_step` = {}; raise the first two or lower the third (--set solver.max_iterations={})",
                solver.max_iterations,
                solver.max_continuation_steps,
                solver.min_load_step,
                solver.max_iterations.saturating_mul(4)
            ) + if iterative {
                "; the inner Jacobi / Gauss-Seidel solves are bounded by `solver.max_sweeps` (unset: 10,000; jacobi-newton 10^7): raise it"
            } else {
                ""
            }
        }
        ContactError::ContinuationBudgetSpent { steps, .. } => format!(
            "`solver.max_continuation_steps` = {} arclength steps of the continuation in the tension ratio (after Newton failed at the ratio asked for); raise it (--set solver.max_continuation_steps={})",
            solver.max_continuation_steps,
            steps.saturating_mul(4)
        ),
        ContactError::Solver(SolverError::BudgetSpent { iterations, .. })
            if solver.linear == "petsc" =>
        {
            format!(
                "{iterations} Krylov iterations spent: `-ksp_max_it` in `solver.petsc_options` = {:?} (default 2000) bounds each linear solve of `solver.linear` = \"petsc\"; raise it (--set solver.petsc_options='\"-ksp_max_it {}\"') or choose a stronger preconditioner",
                solver.petsc_options.as_deref().unwrap_or(""),
                iterations.saturating_mul(4)
            )
        }
        ContactError::Solver(SolverError::BudgetSpent { iterations, .. }) => format!(
            "{iterations} Krylov iterations spent: `solver.max_sweeps` = {} GMRES / CG iterations per linear solve of `solver.linear` = \"multigrid\" (unset: {}); raise it (--set solver.max_sweeps={})",
            solver
                .max_sweeps
                .map_or_else(|| "unset".into(), |n| n.to_string()),
            capstan_elasticity::solvers::KrylovParams::default().max_iterations,
            iterations.saturating_mul(4)
        ),
        ContactError::Solver(SolverError::NotConverged { iterations, .. }) => format!(
            "{iterations} iterations reached: `solver.max_sweeps` = {} Jacobi / Gauss-Seidel sweeps per linear solve, `solver.max_iterations` = {} Newton iterations; raise them (--set solver.max_sweeps={})",
            solver.max_sweeps.map_or_else(
                || "unset (10,000; jacobi-newton 10^7)".into(),
                |n| n.to_string()
            ),
            solver.max_iterations,
            iterations.saturating_mul(10)
        ),
        _ => return e.into(),
    };
    CliError::ContactBudget { source: e, budget }
}
