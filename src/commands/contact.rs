//! `capstan contact`: the thick body on a rough prism under the scene's friction law
//! (`friction.law` through `AnyFrictionLaw`; regularised Coulomb by default, paper section 3).

use std::time::Instant;

use capstan_elasticity::Material;
use capstan_elasticity::contact::{
    BoundarySolver, BulkMultigrid, ContactError, ContactModel, ContactQuantities, ContactSettings,
    ContactSolution, EndLoads, FullSystemSettings, FullSystemSolver, ThickBody, ThickBodyOperator,
    solve_sequenced,
};
use capstan_elasticity::friction::{AnyFrictionLaw, AnyFrictionParams, FrictionLawKind};
use capstan_elasticity::solvers::{LinearBackend, NonlinearMethod, Observer};
use serde::Serialize;

use crate::commands::accuracy::{self, ErrorEstimate};
use crate::error::CliError;
use crate::figures::reports::report_dir;
use crate::output::Table;
use crate::progress::CliObserver;
use crate::scene::Scene;

/// The contact model a scene describes.
pub type SceneModel = ContactModel<ThickBodyOperator, AnyFrictionLaw>;

/// The solver a scene selects (`solver.nonlinear`, `solver.linear`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SceneSolver {
    /// `newton` (default): boundary-only Newton on the condensed contact tractions, bulk
    /// factorised once.
    Condensed,
    /// `full-newton`: Newton on the full residual with `solver.linear`, refactorised each step.
    FullNewton(LinearBackend),
    /// `jacobi-newton`: the paper's Jacobi–Newton (damped Jacobi, relaxation 1/2).
    JacobiNewton,
    /// `full-newton` with `solver.linear = "multigrid"`: each Newton step by GMRES with the
    /// geometric multigrid of the 3-D body ([`BulkMultigrid`]).
    FullNewtonMultigrid,
}

impl SceneSolver {
    /// Reads the scene's solver keys.
    ///
    /// # Errors
    /// [`CliError::Scene`] for an unknown name.
    pub fn from_scene(scene: &Scene) -> Result<Self, CliError> {
        if scene.solver.linear == "multigrid" {
            return match scene.solver.nonlinear.as_str() {
                "full-newton" => Ok(Self::FullNewtonMultigrid),
                other => Err(CliError::Scene {
                    origin: "solver.linear".into(),
                    message: format!(
                        "`solver.linear` = \"multigrid\" is the bulk solver of `solver.nonlinear` = \"full-newton\", not of `{other}`"
                    ),
                }),
            };
        }
        let linear: LinearBackend = scene.solver.linear.parse().map_err(
            |e: capstan_elasticity::solvers::SolverError| CliError::Scene {
                origin: "solver.linear".into(),
                message: e.to_string(),
            },
        )?;
        match scene.solver.nonlinear.as_str() {
            "newton" => Ok(Self::Condensed),
            "full-newton" => Ok(Self::FullNewton(linear)),
            "jacobi-newton" => Ok(Self::JacobiNewton),
            other => Err(CliError::Scene {
                origin: "solver.nonlinear".into(),
                message: format!(
                    "unknown contact solver `{other}`; expected `newton` (boundary-only), `full-newton` or `jacobi-newton`"
                ),
            }),
        }
    }

    /// The settings of the full-system solvers.
    pub fn full_settings(self) -> FullSystemSettings {
        let mut s = FullSystemSettings::default();
        match self {
            Self::FullNewton(linear) => s.newton.linear = linear,
            Self::FullNewtonMultigrid => s.multigrid = Some(BulkMultigrid::default()),
            Self::JacobiNewton => {
                s.method = NonlinearMethod::JacobiNewton;
                s.newton.iterative.relaxation = 0.5; // undamped Jacobi diverges here
                s.newton.iterative.max_iterations = 10_000_000;
                s.newton.iterative.tolerance = 1e-12;
                s.continuation.tolerance = 1e-9;
            }
            Self::Condensed => {}
        }
        s
    }

    /// [`SceneSolver::full_settings`] with the scene's work budgets (`solver.max_iterations`,
    /// `max_continuation_steps`, `min_load_step`, `max_sweeps`).
    pub fn full_settings_for(self, scene: &Scene) -> FullSystemSettings {
        let mut s = self.full_settings();
        s.continuation = ContactSettings {
            tolerance: s.continuation.tolerance,
            ..scene.solver.contact_settings()
        };
        if let Some(sweeps) = scene.solver.max_sweeps {
            s.newton.iterative.max_iterations = sweeps;
            if let Some(m) = s.multigrid.as_mut() {
                m.krylov.max_iterations = sweeps;
            }
        }
        s
    }
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
    })
}

/// The contact model of a scene.
///
/// # Errors
/// See [`thick_body`]; bad friction values; assembly errors.
pub fn model(scene: &Scene) -> Result<SceneModel, CliError> {
    let (law, params, eps) = scene_law(scene)?;
    let body = thick_body(scene)?;
    Ok(body.model(law, params, eps)?)
}

/// The scene's friction law, its parameters and the stick/slip threshold `friction.eps`.
///
/// # Errors
/// An unknown `friction.law`; bad friction values.
pub fn scene_law(scene: &Scene) -> Result<(AnyFrictionLaw, AnyFrictionParams, f64), CliError> {
    let f = &scene.friction;
    let kind = FrictionLawKind::parse(&f.law).ok_or_else(|| CliError::Scene {
        origin: "friction.law".into(),
        message: format!(
            "unknown friction law `{}`; expected one of {}",
            f.law,
            FrictionLawKind::names()
        ),
    })?;
    let params = AnyFrictionParams::of_kind(kind, &f.settings())?;
    Ok((AnyFrictionLaw, params, f.eps))
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
    /// `+1`, `-1`, `0`.
    pub state: Vec<i8>,
    /// Physical tangential displacement `sqrt(g_22) v^2`.
    pub slip: Vec<f64>,
    /// Physical friction traction on the body.
    pub friction_traction: Vec<f64>,
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
    /// Load-continuation steps.
    pub continuation_steps: usize,
    /// Relative max-norm residual of the full system.
    pub residual: f64,
    /// Inner Jacobi iterations (Jacobi–Newton only).
    pub linear_iterations: usize,
    /// `[lower, upper]` tension ratios friction can hold, when the body can slide rigidly (circle);
    /// an entry is `null` when friction holds every ratio in that direction (no finite limit).
    pub limiting_ratios: Option<[Option<f64>; 2]>,
    /// Contact nodes under tension (`sigma_n > 0`).
    pub tensile_contact_nodes: usize,
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
            slip_intervals: sol
                .slip_intervals()
                .map(|i| IntervalReport {
                    state: i.state,
                    from: i.from,
                    to: i.to,
                    nodes: i.nodes,
                })
                .collect(),
            max_azimuthal_displacement: sol.max_azimuthal_displacement,
            max_radial_displacement: sol.max_radial_displacement,
            contact: ContactArrays {
                x2: c.x2.clone(),
                v2: c.v2.clone(),
                v3: c.v3.clone(),
                normal_stress: c.normal_stress.clone(),
                shear_stress: c.shear_stress.clone(),
                state: c.state.clone(),
                slip: c.slip.clone(),
                friction_traction: c.friction_traction.clone(),
            },
            tau0: sol.loads.tau0,
            tau_max: sol.loads.tau_max,
            tension_ratio: sol.loads.tension_ratio(),
            method: sol.stats.method,
            continuation_steps: sol.stats.continuation_steps,
            residual: sol.stats.residual,
            linear_iterations: sol.stats.linear_iterations,
            limiting_ratios: limiting.map(|r| r.map(|x| Some(x).filter(|x| x.is_finite()))),
            tensile_contact_nodes: sol.tensile_contact_nodes,
            grid,
            setup_seconds: times[0],
            solve_seconds: times[1],
            discretisation: "fd",
            grid_sequence: None,
            solid: None,
            quantities: None,
            estimated_error: None,
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
    /// The converging quantities of the solution (probes at `output.probe_x2`).
    pub quantities: ContactQuantities,
}

/// The nodal fields of a solution of `model`, with the scene's obstacle.
///
/// # Errors
/// Geometry failures; bad obstacle values.
pub fn solved(
    scene: &Scene,
    model: &SceneModel,
    solution: ContactSolution,
) -> Result<Solved, CliError> {
    use capstan_elasticity::{Component, Discretisation};
    let disc = model.discretisation();
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
    let quantities = ContactQuantities::new(model, &solution, &accuracy::probes(scene))?;
    Ok(Solved {
        solution,
        nodes,
        fields,
        obstacle: scene.obstacle.build()?,
        quantities,
    })
}

/// Solves a scene's contact problem with its solver, reporting progress as the command line
/// does ([`CliObserver`]: `-v` lines, a spinner on a terminal).
///
/// # Errors
/// Bad input (exit 2), no equilibrium (3), non-convergence (4).
pub fn solve(scene: &Scene) -> Result<(ContactReport, Solved), CliError> {
    solve_observed(scene, &mut CliObserver::new())
}

/// As [`solve`], with every iteration of the solve reported to `observer` (which may stop it:
/// [`ContactError::Interrupted`]). The Python package passes its callback and Ctrl-C check here.
///
/// # Errors
/// As [`solve`]; [`ContactError::Interrupted`] when `observer` asks to stop.
pub fn solve_observed(
    scene: &Scene,
    observer: &mut dyn Observer<f64>,
) -> Result<(ContactReport, Solved), CliError> {
    let named = |e| match e {
        CliError::Contact(e) => contact_budget(e, &scene.solver),
        e => e,
    };
    let (mut report, solved) = solve_unnamed(scene, observer).map_err(named)?;
    report.quantities = Some(solved.quantities.clone());
    if scene.output.error_estimate
        && let Some(coarse) = accuracy::coarser_scene(scene)?
    {
        let (_, coarse_solved) =
            solve_unnamed(&coarse, &mut accuracy::StopOnly(observer)).map_err(named)?;
        let scalars = |s: &Solved| s.quantities.scalars(&s.solution);
        report.estimated_error = Some(ErrorEstimate::from_levels(
            &scalars(&solved),
            &scalars(&coarse_solved),
            accuracy::grid_of(&coarse),
        ));
    }
    Ok((report, solved))
}

fn solve_unnamed(
    scene: &Scene,
    observer: &mut dyn Observer<f64>,
) -> Result<(ContactReport, Solved), CliError> {
    let method = SceneSolver::from_scene(scene)?;
    let loads = loads(scene);
    let t0 = Instant::now();
    let grid = [scene.grid.n2, scene.grid.n3];
    match method {
        SceneSolver::Condensed => {
            let model = model(scene)?;
            let CondensedRun {
                sol,
                limiting,
                times,
            } = condensed(&model, scene, loads, observer, t0)?;
            let report = ContactReport {
                discretisation: capstan_elasticity::Discretisation::method(model.discretisation()),
                ..ContactReport::new(&sol, limiting, grid, times)
            };
            Ok((report, solved(scene, &model, sol)?))
        }
        SceneSolver::FullNewton(_) | SceneSolver::FullNewtonMultigrid => {
            // Grid sequencing: the model is assembled level by level inside.
            let (law, params, eps) = scene_law(scene)?;
            let body = thick_body(scene)?;
            let setup = t0.elapsed().as_secs_f64();
            let t1 = Instant::now();
            let settings = method.full_settings_for(scene);
            match solve_sequenced(&body, law, params, eps, loads, settings, observer) {
                Ok(seq) => {
                    let report = ContactReport {
                        discretisation: capstan_elasticity::Discretisation::method(
                            seq.model.discretisation(),
                        ),
                        grid_sequence: Some(
                            seq.levels.iter().map(|&(a, b, c)| [a, b, c]).collect(),
                        ),
                        ..ContactReport::new(
                            &seq.solution,
                            None,
                            grid,
                            [setup, t1.elapsed().as_secs_f64()],
                        )
                    };
                    Ok((report, solved(scene, &seq.model, seq.solution)?))
                }
                Err(e @ ContactError::NotConverged { .. }) => {
                    Err(explain_not_converged(&model(scene)?, loads, e))
                }
                Err(e) => Err(e.into()),
            }
        }
        SceneSolver::JacobiNewton => {
            let model = model(scene)?;
            let solver = FullSystemSolver::new(&model, method.full_settings_for(scene))?;
            let setup = t0.elapsed().as_secs_f64();
            let t1 = Instant::now();
            match solver.solve_observed(loads, observer) {
                Ok(sol) => {
                    let report = ContactReport {
                        discretisation: capstan_elasticity::Discretisation::method(
                            model.discretisation(),
                        ),
                        ..ContactReport::new(&sol, None, grid, [setup, t1.elapsed().as_secs_f64()])
                    };
                    Ok((report, solved(scene, &model, sol)?))
                }
                Err(e @ ContactError::NotConverged { .. }) => {
                    Err(explain_not_converged(&model, loads, e))
                }
                Err(e) => Err(e.into()),
            }
        }
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
        ContactError::NotConverged { .. } => {
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
        ContactError::Solver(SolverError::BudgetSpent { iterations, .. }) => format!(
            "{iterations} Krylov iterations spent: `solver.max_sweeps` = {} GMRES / CG iterations per linear solve of `solver.linear` = \"multigrid\" (unset: {}); raise it (--set solver.max_sweeps={})",
            solver
                .max_sweeps
                .map_or_else(|| "unset".into(), |n| n.to_string()),
            BulkMultigrid::default().krylov.max_iterations,
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

/// A full-system non-convergence, told apart: no equilibrium (checked by the boundary-only
/// solver's limiting ratios of `model`) rather than a solver failure.
fn explain_not_converged(model: &SceneModel, loads: EndLoads, e: ContactError) -> CliError {
    let check = || -> Result<(), ContactError> {
        BoundarySolver::new(model, ContactSettings::default())?.check_equilibrium(loads)
    };
    match check() {
        Err(no_equilibrium @ ContactError::NoEquilibrium { .. }) => no_equilibrium.into(),
        _ => e.into(),
    }
}

/// A plain-text summary.
pub fn table(r: &ContactReport) -> String {
    let mut s = format!(
        "contact: tau0 = {}, tau_max = {} (ratio {:.6}), grid {} x {} ({}), {}\n",
        r.tau0, r.tau_max, r.tension_ratio, r.grid[0], r.grid[1], r.discretisation, r.method
    );
    s += &format!(
        "  status {}: {} Newton iterations ({} continuation steps), residual {:.2e}, setup {:.3} s, solve {:.3} s\n",
        r.status,
        r.newton_iterations,
        r.continuation_steps,
        r.residual,
        r.setup_seconds,
        r.solve_seconds
    );
    let e = |x: &Extremum| format!("{:+.6e} at (x2, x3) = ({:.6}, {:.6})", x.value, x.x2, x.x3);
    if let Some(solid) = &r.solid {
        let [n1, n2, n3] = solid.grid;
        s += &format!(
            "  3-D body: grid {n1} x {n2} x {n3}, x1 in [{}, {}], sides {:?}, {} contact unknowns\n",
            solid.x1[0], solid.x1[1], solid.sides, solid.contact_unknowns
        );
    }
    s += &format!("  max |v2| {}\n", e(&r.max_azimuthal_displacement));
    s += &format!("  max |v3| {}\n", e(&r.max_radial_displacement));
    s += &format!("  Slip {:.6}\n", r.slip_fraction);
    s += &quantities_table(r);
    match r.stick_interval {
        Some([a, b]) => s += &format!("  stick ({a:.6}, {b:.6})\n"),
        None => s += "  stick: none\n",
    }
    for i in &r.slip_intervals {
        s += &format!("  slip {:+} [{:.6}, {:.6}]\n", i.state, i.from, i.to);
    }
    if let Some([lo, hi]) = r.limiting_ratios {
        let f =
            |x: Option<f64>, unbounded: &str| x.map_or(unbounded.to_owned(), |x| format!("{x:.6}"));
        s += &format!(
            "  limiting tension ratios (rigid sliding): [{}, {}]\n",
            f(lo, "-inf (none)"),
            f(hi, "inf (none)")
        );
    }
    s
}

/// The converging quantities with their estimated errors (`+- e`), as [`table`] prints them.
fn quantities_table(r: &ContactReport) -> String {
    let Some(q) = &r.quantities else {
        return String::new();
    };
    let estimate = |name: &str| {
        r.estimated_error
            .as_ref()
            .and_then(|e| e.quantities.get(name).copied().flatten())
            .map_or_else(String::new, |e| format!(" +- {e:.1e}"))
    };
    let mut s = format!(
        "  slip measure {:.6}{} of {:.6} (physical {:.6}{})\n",
        q.slip_measure,
        estimate("slip_measure"),
        q.contact_measure,
        q.slip_physical_measure,
        estimate("slip_physical_measure")
    );
    for (i, p) in q.normal_stress_probes.iter().enumerate() {
        s += &format!(
            "  sigma_n({:.6}) = {:+.6e}{}\n",
            p.x2,
            p.value,
            estimate(&format!("normal_stress_probe_{i}"))
        );
    }
    if let Some(e) = &r.estimated_error {
        let named = ["stick_from", "stick_to", "max_abs_v2", "max_abs_v3"]
            .iter()
            .filter_map(|n| {
                Some(format!(
                    "{n} {:.1e}",
                    e.quantities.get(*n).copied().flatten()?
                ))
            })
            .collect::<Vec<_>>();
        s += &format!(
            "  estimated errors (vs grid {:?}): {}\n",
            e.coarser_grid,
            named.join(", ")
        );
    }
    s
}

/// Writes `contact.json`, `contact.csv` (contact surface), `displacement.csv` (nodes),
/// `body.vtu` (every field on the curved body, see [`crate::figures::body::VTU_ARRAYS`]) and the
/// plots `body_v2`, `body_v3` (displacement colour maps) and `body_state` (stick/slip strip),
/// each as SVG and PNG.
///
/// # Errors
/// Output errors.
pub fn write_out(
    dir: &std::path::Path,
    report: &ContactReport,
    sol: &Solved,
    scene: &Scene,
) -> Result<(), CliError> {
    let out = report_dir(dir, "contact", report, Some(scene))?;
    let table = contact_table(report);
    out.write_csv("contact.csv", &table)?;
    let nodes = Table::new()
        .f64("x2", sol.nodes.x2.clone())
        .f64("x3", sol.nodes.x3.clone())
        .f64("v2", sol.nodes.v2.clone())
        .f64("v3", sol.nodes.v3.clone());
    out.write_csv("displacement.csv", &nodes)?;
    crate::figures::body::write_body(
        &out,
        "body",
        &sol.obstacle,
        &sol.fields,
        &sol.solution.contact,
        crate::figures::body::BodyFiles {
            time: None,
            plots: true,
            output: &scene.output,
        },
    )?;
    Ok(())
}

/// The contact surface as a table (`contact.csv`): `x2, v2, v3, normal_stress, shear_stress,
/// slip, friction_traction, state`; a 3-D body adds `x1`, `v1`, `shear_stress_1`, `slip_1`,
/// `friction_traction_1` beside their `x2` counterparts.
pub fn contact_table(report: &ContactReport) -> Table {
    let c = &report.contact;
    let solid = report.solid.as_ref().map(|s| &s.contact);
    let mut table = Table::new();
    if let Some(s) = solid {
        table = table.f64("x1", s.x1.clone());
    }
    table = table.f64("x2", c.x2.clone());
    if let Some(s) = solid {
        table = table.f64("v1", s.v1.clone());
    }
    table = table
        .f64("v2", c.v2.clone())
        .f64("v3", c.v3.clone())
        .f64("normal_stress", c.normal_stress.clone());
    for (name, plane, across) in [
        (
            "shear_stress",
            &c.shear_stress,
            solid.map(|s| &s.shear_stress_1),
        ),
        ("slip", &c.slip, solid.map(|s| &s.slip_1)),
        (
            "friction_traction",
            &c.friction_traction,
            solid.map(|s| &s.friction_traction_1),
        ),
    ] {
        if let Some(values) = across {
            table = table.f64(format!("{name}_1"), values.clone());
        }
        table = table.f64(name, plane.clone());
    }
    table.i32(
        "state",
        c.state.iter().map(|&s| i32::from(s)).collect::<Vec<_>>(),
    )
}

/// A boundary-only solve as the commands report it.
pub(crate) struct CondensedRun {
    /// The contact solution.
    pub sol: ContactSolution,
    /// Limiting ratios `[lower, upper]` when the body can slide rigidly.
    pub limiting: Option<[f64; 2]>,
    /// Wall times `[set-up since t0, solve]`, seconds.
    pub times: [f64; 2],
}

/// The boundary-only solve of `model` with the scene's budgets (`solver.*`). Shared by the
/// plane-strain and the 3-D body.
///
/// # Errors
/// Solver errors; [`ContactError::Interrupted`] when `observer` stops the solve.
pub(crate) fn condensed<D: capstan_elasticity::contact::ContactOperator>(
    model: &ContactModel<D, AnyFrictionLaw>,
    scene: &Scene,
    loads: EndLoads,
    observer: &mut dyn Observer<f64>,
    t0: Instant,
) -> Result<CondensedRun, CliError> {
    let solver = BoundarySolver::new(model, scene.solver.contact_settings())?;
    let setup = t0.elapsed().as_secs_f64();
    let t1 = Instant::now();
    let sol = solver.solve_observed(loads, observer)?;
    let limiting = solver
        .sliding_at(sol.loads.tau0)?
        .map(|m| [m.lower_ratio, m.upper_ratio]);
    Ok(CondensedRun {
        sol,
        limiting,
        times: [setup, t1.elapsed().as_secs_f64()],
    })
}
