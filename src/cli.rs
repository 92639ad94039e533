//! The `capstan` command line.

use std::path::{Path, PathBuf};

use clap::{Args, Parser, Subcommand};
use serde::Serialize;

use crate::commands;
pub use crate::commands::{SceneArgs, StudyArgs};
use crate::error::CliError;
use crate::figures::reports::{write_geometry, write_tension};
use crate::output::OutputDir;
use crate::provenance::Stamped;
use crate::provenance::write_json_report;
use crate::scene::Scene;

/// Friction between elastic bodies and rough rigid curved obstacles.
///
/// Without a subcommand, runs the paper's default scene.
#[derive(Debug, Parser)]
#[command(name = "capstan", version, about, long_about = None, after_help = EXAMPLES)]
pub struct Cli {
    /// What to run.
    #[command(subcommand)]
    pub command: Option<Command>,
    /// No progress bars or notes on stderr (results and errors still print).
    #[arg(long, short, global = true)]
    pub quiet: bool,
    /// More notes on stderr (repeatable: `-vv`).
    #[arg(long, short = 'v', action = clap::ArgAction::Count, global = true)]
    pub verbose: u8,
    /// Stop after this many seconds of wall-clock time: exit code 5 (`timed out`), and none
    /// of the run's files is left in `--out` (they are renamed into place only at the end).
    #[arg(long, global = true, value_name = "SECONDS")]
    pub timeout: Option<f64>,
}

const EXAMPLES: &str = "Examples:\n  capstan geometry --set obstacle.shape=ellipse --set obstacle.b=1 --json\n  capstan tension examples/scenes/capstan_ellipse.toml --out out/tension\n  capstan contact --set loads.tau_max=1 --out out/contact\n  capstan figure all --quick --out out/figures";

/// The subcommands (their examples and the wording of shared arguments: [`SUBCOMMAND_HELP`]).
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Differential geometry of the obstacle on the contact interval.
    Geometry(OutSceneArgs),
    /// Convergence studies of the elasticity discretisations: errors and observed orders.
    Verify(StudyArgs),
    /// Benchmarks: `work-precision` (run time against error, FD vs FEM vs scikit-fem and NGSolve).
    Bench(commands::bench::BenchArgs),
    /// Tension profile of a membrane at limiting equilibrium (generalised capstan equation).
    Tension(OutSceneArgs),
    /// Coefficient of friction implied by a tension pair {membrane.t0, membrane.t_max}, under
    /// the capstan, membrane displacement or Kikuchi–Oden thick-body model.
    InferMu(commands::infer_mu::InferMuArgs),
    /// The membrane displacement model along a load path `loads.path` (end tensions at
    /// theta_max) with exact Coulomb friction on each step's slip increment: belt creep and
    /// its hysteresis loop.
    MembranePath(OutSceneArgs),
    /// The thick body (2-D or 3-D) along a load path `loads.path` (end tractions tau_max at
    /// theta_max, loads.tau0 held), each state from the previous one with friction on the
    /// slip increment: stick/slip history and the hysteresis loop.
    ContactPath(OutSceneArgs),
    /// Thick body on a rough prism under regularised Coulomb friction (paper section 3).
    Contact(ContactArgs),
    /// One scene key swept over a range: Slip and the contact numbers per point (parallel).
    Sweep(SweepArgs),
    /// Tension ratio at which the whole contact slides, and the capstan mu it implies.
    Threshold(OutSceneArgs),
    /// Implied coefficients of friction of the capstan, membrane and Kikuchi–Oden models
    /// against b/a, h and nu, with the thick body's threshold as h -> 0 (CSV, SVG/PNG plots).
    Compare(StudyArgs),
    /// Numerical stability under stress: each parameter toward its hard limit (contact and
    /// capstan models), with iterations, residuals, condition estimates, refinement changes.
    Stress(StudyArgs),
    /// The paper's figures and tables (sections 2 and 3) as PNG + SVG + CSV, with an index.
    Figure(crate::figures::command::FigureArgs),
    /// Sweep parts written by `capstan sweep --shard I/N`, checked and merged into one sweep.
    Merge(crate::scale::merge_command::MergeArgs),
    /// The contact problem's linear system (Newton Jacobian at a state) in Matrix Market.
    ExportSystem(commands::export_system::ExportSystemArgs),
}

/// What `--help` of one subcommand adds to its derived text: example command lines (shown
/// after the options; every one is parsed in the tests) and the help of shared arguments that
/// this subcommand words its own way (argument id, text).
#[derive(Debug, Clone, Copy)]
pub struct SubcommandHelp {
    /// The subcommand's name on the command line.
    pub name: &'static str,
    /// Example command lines.
    pub examples: &'static [&'static str],
    /// `(argument id, help)` replacing the shared argument's help.
    pub arguments: &'static [(&'static str, &'static str)],
}

/// The examples and reworded arguments of every subcommand, applied by [`Cli::command_with_help`].
pub const SUBCOMMAND_HELP: &[SubcommandHelp] = &[
    SubcommandHelp {
        name: "geometry",
        examples: &[
            "capstan geometry --set obstacle.shape=prism --set 'obstacle.u=2*sin(t)+0.2*sin(2*t)' --json",
        ],
        arguments: &[],
    },
    SubcommandHelp {
        name: "verify",
        examples: &["capstan verify --quick", "capstan verify --json"],
        arguments: &[
            ("quick", "Only the three coarsest grids of each study"),
            ("out", "Also write `verify.json` into this directory"),
        ],
    },
    SubcommandHelp {
        name: "bench",
        examples: &["capstan bench work-precision --quick"],
        arguments: &[],
    },
    SubcommandHelp {
        name: "tension",
        examples: &[
            "capstan tension --set obstacle.shape=ellipse --set obstacle.b=1 --set membrane.theta0=-0.785398 --set membrane.theta_max=0.785398 --json",
            "capstan tension --set obstacle.shape=cylinder --set loads.gravity=9.81 --set loads.density=0.1 --set membrane.theta0=0",
        ],
        arguments: &[],
    },
    SubcommandHelp {
        name: "infer-mu",
        examples: &[
            "capstan infer-mu --set obstacle.shape=cylinder --set membrane.theta0=0 --set membrane.theta_max=3.14159265358979 --set membrane.t_max=2.75",
            "capstan infer-mu --model kikuchi-oden --set membrane.t_max=2.75 --set grid.n2=41 --set grid.n3=9 --json",
        ],
        arguments: &[],
    },
    SubcommandHelp {
        name: "membrane-path",
        examples: &[
            "capstan membrane-path examples/scenes/belt_creep.toml --out out/belt-creep",
            "capstan membrane-path --set friction.law=exact-coulomb --set obstacle.shape=cylinder --set 'loads.path=[2.0, 1.0, 2.0]' --json",
        ],
        arguments: &[],
    },
    SubcommandHelp {
        name: "contact-path",
        examples: &[
            "capstan contact-path examples/scenes/contact_path.toml --out out/contact-path",
            "capstan contact-path --set friction.law=exact-coulomb --set grid.n2=41 --set grid.n3=9 --set 'loads.path=[2.0, 1.5, 2.0]' --json",
        ],
        arguments: &[],
    },
    SubcommandHelp {
        name: "contact",
        examples: &[
            "capstan contact --set loads.tau_max=1 --json",
            "capstan contact --set grid.n2=80 --set grid.n3=17 --set solver.nonlinear=full-newton --out out/contact",
        ],
        arguments: &[],
    },
    SubcommandHelp {
        name: "sweep",
        examples: &["capstan sweep --param loads.tau_max --from 1 --to 3.5 --steps 26 --json"],
        arguments: &[],
    },
    SubcommandHelp {
        name: "threshold",
        examples: &["capstan threshold --set grid.n2=80 --set grid.n3=17 --json"],
        arguments: &[],
    },
    SubcommandHelp {
        name: "compare",
        examples: &[
            "capstan compare --quick",
            "capstan compare --json --out out/models",
        ],
        arguments: &[
            (
                "out",
                "Write `compare.json`, `implied_mu.csv`, `thickness.csv` and the plots `implied_mu_vs_{b_over_a,thickness,poisson}.{svg,png}` into this directory",
            ),
            (
                "quick",
                "Grid 41 x 9, three values per axis, one grid in the thickness study (under a second in release; the full study takes about 40 s on 2 cores)",
            ),
        ],
    },
    SubcommandHelp {
        name: "stress",
        examples: &[
            "capstan stress --quick",
            "capstan stress --json --out out/stress",
        ],
        arguments: &[
            (
                "json",
                "Print one JSON object (`points`: one object per stressed point) instead of a table",
            ),
            (
                "out",
                "Write `stress.json` and `stress.md` into this directory",
            ),
            (
                "quick",
                "A representative subset: every axis at its extreme values (about a minute in release)",
            ),
        ],
    },
    SubcommandHelp {
        name: "figure",
        examples: &[
            "capstan figure all --out figures",
            "capstan figure slip-ratio --quick --out /tmp/fig",
        ],
        arguments: &[],
    },
    SubcommandHelp {
        name: "merge",
        examples: &[
            "capstan sweep --param body.poisson --from 0.1 --to 0.4 --steps 8 --shard 1/2 --out parts",
            "capstan sweep --param body.poisson --from 0.1 --to 0.4 --steps 8 --shard 2/2 --out parts",
            "capstan merge parts --out sweep",
        ],
        arguments: &[],
    },
    SubcommandHelp {
        name: "export-system",
        examples: &[
            "capstan export-system --set grid.n2=40 --set grid.n3=9 --out system --state solution",
        ],
        arguments: &[],
    },
];

impl Cli {
    /// The clap command with every subcommand's [`SUBCOMMAND_HELP`] applied: the command
    /// line that `capstan` parses.
    #[must_use]
    pub fn command_with_help() -> clap::Command {
        SUBCOMMAND_HELP
            .iter()
            .fold(<Self as clap::CommandFactory>::command(), |cli, help| {
                cli.mut_subcommand(help.name, |sub| {
                    let heading = if help.examples.len() == 1 {
                        "Example:"
                    } else {
                        "Examples:"
                    };
                    let examples: String =
                        help.examples.iter().map(|e| format!("\n  {e}")).collect();
                    help.arguments.iter().fold(
                        sub.after_help(format!("{heading}{examples}")),
                        |sub, &(id, text)| sub.mut_arg(id, |a| a.help(text)),
                    )
                })
            })
    }

    /// Parses the process's arguments with [`Cli::command_with_help`]; on `--help`,
    /// `--version` or an error, prints and exits as clap does.
    #[must_use]
    pub fn parse_with_help() -> Self {
        let matches = Self::command_with_help().get_matches();
        <Self as clap::FromArgMatches>::from_arg_matches(&matches).unwrap_or_else(|e| e.exit())
    }
}

/// Arguments of `capstan contact`.
#[derive(Debug, Args, Clone, Default)]
pub struct ContactArgs {
    /// The scene.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Write `contact.json`, `contact.csv` and `displacement.csv` into this directory.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
}

/// Arguments of `capstan sweep`.
#[derive(Debug, Args, Clone, Default)]
pub struct SweepArgs {
    /// The scene.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// The scene key to vary, e.g. `loads.tau_max`, `obstacle.b`, `body.thickness`.
    #[arg(long, value_name = "KEY")]
    pub param: String,
    /// First value.
    #[arg(long)]
    pub from: f64,
    /// Last value.
    #[arg(long)]
    pub to: f64,
    /// Number of points (both ends included).
    #[arg(long)]
    pub steps: usize,
    /// Write `sweep.json` and `sweep.csv` into this directory (with `--shard`, the part
    /// `shard-I-of-N.json` instead).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Run only part `I` of `N` (1-based): the points `k` (0-based) with `k % N == I - 1`;
    /// merge the parts with `capstan merge`.
    #[arg(long, value_name = "I/N")]
    pub shard: Option<crate::scale::ShardSpec>,
}

/// A scene and an output directory (`capstan geometry`, `tension`, `threshold`).
#[derive(Debug, Args, Clone, Default)]
pub struct OutSceneArgs {
    /// The scene.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Also write the report as files into this directory (JSON; CSV and SVG/PNG plots for
    /// profiles).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
}

/// Runs the command line; returns what to print on stdout.
///
/// # Errors
/// Any [`CliError`]; the caller maps it to an exit code.
pub fn run(cli: Cli) -> Result<String, CliError> {
    crate::progress::set_flags(cli.quiet, cli.verbose);
    let Some(seconds) = cli.timeout else {
        return run_command(cli);
    };
    if !(seconds.is_finite() && seconds > 0.0) {
        return Err(CliError::Set {
            set: format!("--timeout {seconds}"),
            message: "SECONDS must be a positive number".into(),
        });
    }
    crate::output::defer_commits();
    std::thread::spawn(move || {
        std::thread::sleep(std::time::Duration::from_secs_f64(seconds));
        // Nothing happens when the run has committed its files already (it is finishing).
        crate::output::discard_outputs_and(|| {
            eprintln!("error: {}", CliError::TimedOut { seconds });
            std::process::exit(CliError::TimedOut { seconds }.exit_code())
        });
    });
    match run_command(cli) {
        Ok(out) => {
            crate::output::commit_deferred()?;
            Ok(out)
        }
        Err(e) => {
            crate::output::discard_outputs_and(|| ());
            Err(e)
        }
    }
}

fn run_command(cli: Cli) -> Result<String, CliError> {
    match cli.command {
        None => default_job(),
        Some(Command::Geometry(args)) => scene_command(
            &args.scene,
            args.out.as_deref(),
            commands::geometry::report,
            write_geometry,
            |r, scene| Ok(commands::geometry::table(r, &scene.obstacle.build()?)),
        ),
        Some(Command::Verify(args)) => {
            let report = commands::verify::report(args.quick)?;
            let out = study(
                &args,
                |_| Ok(report.clone()),
                |dir, r| write_json_report(dir, "verify", r, None),
                commands::verify::table,
            )?;
            let missed = report.missed();
            if missed.is_empty() {
                Ok(out)
            } else {
                Err(CliError::VerificationFailed {
                    output: out,
                    missed,
                })
            }
        }
        Some(Command::Bench(args)) => bench(&args),
        Some(Command::Tension(args)) => scene_command(
            &args.scene,
            args.out.as_deref(),
            commands::tension::report,
            write_tension,
            |r, scene| Ok(commands::tension::table(r, scene)),
        ),
        Some(Command::InferMu(args)) => scene_command(
            &args.scene,
            args.out.as_deref(),
            |scene| commands::infer_mu::report_for(scene, args.model),
            |dir, r, scene| write_json_report(dir, "infer-mu", r, Some(scene)),
            |r, scene| Ok(commands::infer_mu::table(r, scene)),
        ),
        Some(Command::MembranePath(args)) => scene_command(
            &args.scene,
            args.out.as_deref(),
            commands::membrane_path::report,
            commands::membrane_path::write_out,
            |r, _| Ok(commands::membrane_path::table(r)),
        ),
        Some(Command::ContactPath(args)) => scene_command(
            &args.scene,
            args.out.as_deref(),
            commands::contact_path::report,
            commands::contact_path::write_out,
            |r, _| Ok(commands::contact_path::table(r)),
        ),
        Some(Command::Contact(args)) => contact(&args),
        Some(Command::Sweep(args)) => sweep(&args),
        Some(Command::Threshold(args)) => scene_command(
            &args.scene,
            args.out.as_deref(),
            commands::threshold::report,
            |dir, r, scene| write_json_report(dir, "threshold", r, Some(scene)),
            |r, _| Ok(commands::threshold::table(r)),
        ),
        Some(Command::Compare(args)) => study(
            &args,
            commands::compare::report,
            commands::compare::write_out,
            commands::compare::table,
        ),
        Some(Command::Stress(args)) => study(
            &args,
            commands::stress::report,
            commands::stress::write_out,
            commands::stress::table,
        ),
        Some(Command::Figure(args)) => figure(&args, cli.quiet),
        Some(Command::Merge(args)) => crate::scale::merge_command::run(&args),
        Some(Command::ExportSystem(args)) => export_system(&args),
    }
}

/// The report of one scene: `report(scene)`, written into `out` by `write`; printed as one
/// JSON object stamped with the scene (`--json`) or as `table(report, scene)`.
fn scene_command<R: Serialize>(
    args: &SceneArgs,
    out: Option<&Path>,
    report: impl FnOnce(&Scene) -> Result<R, CliError>,
    write: impl FnOnce(&Path, &R, &Scene) -> Result<(), CliError>,
    table: impl FnOnce(&R, &Scene) -> Result<String, CliError>,
) -> Result<String, CliError> {
    let scene = args.load()?;
    let report = report(&scene)?;
    if let Some(dir) = out {
        write(dir, &report, &scene)?;
    }
    render(args.json, &Stamped::new(&report, Some(&scene)), || {
        table(&report, &scene)
    })
}

/// A fixed study: `report(quick)`, written into `--out` by `write`; printed as one JSON object
/// (`--json`) or as `table(report)`.
fn study<R: Serialize>(
    args: &StudyArgs,
    report: impl FnOnce(bool) -> Result<R, CliError>,
    write: impl FnOnce(&Path, &R) -> Result<(), CliError>,
    table: impl FnOnce(&R) -> String,
) -> Result<String, CliError> {
    let report = report(args.quick)?;
    if let Some(dir) = &args.out {
        write(dir, &report)?;
    }
    render(args.json, &report, || Ok(table(&report)))
}

/// What a command prints: `report` as one JSON object when `json`, else `table()`.
fn render<R: Serialize>(
    json: bool,
    report: &R,
    table: impl FnOnce() -> Result<String, CliError>,
) -> Result<String, CliError> {
    if json {
        Ok(crate::output::to_json_string(report)?)
    } else {
        table()
    }
}

fn contact(args: &ContactArgs) -> Result<String, CliError> {
    let scene = args.scene.load()?;
    commands::contact::warn_grid_condition(&scene)?;
    // `solver.linear = "petsc"`: PETSc (and MPI) for this command; ranks other than 0 end
    // after the solve, rank 0 writes and ends PETSc when `_petsc` drops.
    #[cfg(feature = "petsc")]
    let mut _petsc = crate::scale::petsc::PetscRun::start(&scene)?;
    let (report, run) = commands::contact::solve(&scene)?;
    #[cfg(feature = "petsc")]
    {
        _petsc = _petsc.map(crate::scale::petsc::PetscRun::end_unless_root);
    }
    if let Some(dir) = &args.out {
        commands::contact_output::write_run(dir, &report, &run, &scene)?;
    }
    render(
        args.scene.json,
        &Stamped::new(&report, Some(&scene)),
        || Ok(commands::contact_output::table(&report)),
    )
}

fn sweep(args: &SweepArgs) -> Result<String, CliError> {
    let values = commands::sweep::values(args.from, args.to, args.steps)?;
    if let Some(spec) = args.shard {
        return sweep_shard(args, &values, spec);
    }
    #[cfg(feature = "mpi")]
    if let Some(out) = sweep_mpi(args, &values)? {
        return Ok(out);
    }
    let fields = args.out.as_deref().map(OutputDir::create).transpose()?;
    let report = commands::sweep::report_indexed(
        args.scene.scene.as_deref(),
        &args.scene.sets,
        commands::sweep::SweepPoints::new(&args.param, &values).fields(fields.as_ref()),
    )?;
    sweep_output(args, &report)
}

/// A whole sweep: written into `--out`, printed as JSON stamped with the scene or as a table.
fn sweep_output(
    args: &SweepArgs,
    report: &commands::sweep::SweepReport,
) -> Result<String, CliError> {
    let scene = args.scene.load()?;
    if let Some(dir) = &args.out {
        commands::sweep::write_out(dir, report, &scene)?;
    }
    render(args.scene.json, &Stamped::new(report, Some(&scene)), || {
        Ok(commands::sweep::table(report))
    })
}

/// `capstan sweep --shard I/N`: one part, written as `shard-I-of-N.json`.
fn sweep_shard(
    args: &SweepArgs,
    values: &[f64],
    spec: crate::scale::ShardSpec,
) -> Result<String, CliError> {
    let out = args.out.as_deref().map(OutputDir::create).transpose()?;
    let part = crate::scale::run_shard(
        args.scene.scene.as_deref(),
        &args.scene.sets,
        &args.param,
        values,
        spec,
        out.as_ref(),
    )?;
    if let Some(out) = &out {
        out.write_json(&crate::scale::shard_file_name(spec), &part)?;
    }
    render(args.scene.json, &part, || {
        Ok(format!(
            "sweep of {}: shard {}/{} holds points {:?} of {} ({})\n",
            part.param,
            spec.index,
            spec.count,
            part.indices,
            part.values.len(),
            part.scene_hash
        ))
    })
}

/// `mpirun -n K capstan sweep ...` (feature `mpi`): `None` when not under MPI with 2+ ranks.
#[cfg(feature = "mpi")]
fn sweep_mpi(args: &SweepArgs, values: &[f64]) -> Result<Option<String>, CliError> {
    use crate::scale::mpi::MpiSweep;
    let scene = &args.scene;
    match crate::scale::mpi::sweep(scene.scene.as_deref(), &scene.sets, &args.param, values)? {
        MpiSweep::Serial => Ok(None),
        // Other ranks print nothing (MPI is finalised when `sweep` returns).
        MpiSweep::Worker => std::process::exit(0),
        MpiSweep::Root(report) => sweep_output(args, &report).map(Some),
    }
}

fn export_system(args: &commands::export_system::ExportSystemArgs) -> Result<String, CliError> {
    let report = commands::export_system::run(args)?;
    render(args.scene.json, &report, || {
        Ok(commands::export_system::table(&report))
    })
}

fn figure(args: &crate::figures::command::FigureArgs, quiet: bool) -> Result<String, CliError> {
    let index = crate::figures::command::run(args, quiet)?;
    render(args.json, &index, || {
        Ok(crate::figures::command::table(&index))
    })
}

fn bench(args: &commands::bench::BenchArgs) -> Result<String, CliError> {
    match &args.what {
        commands::bench::BenchCommand::WorkPrecision(a) => {
            let report = commands::bench::report(a)?;
            render(a.json, &report, || Ok(commands::bench::table(&report)))
        }
    }
}

/// The main job on built-in defaults.
///
/// The paper's default scene (section 3): the membrane capstan profile on the obstacle
/// (section 2, Theorem 1) and the thick body under regularised Coulomb friction on the
/// default 250 x 41 grid, side by side.
fn default_job() -> Result<String, CliError> {
    let scene = Scene::default();
    let tension = commands::tension::report(&scene)?;
    let (contact, _) = commands::contact::solve(&scene)?;
    Ok(format!(
        "capstan: the paper's default scene (a = b = 2, mu = 1/2, tau0 = 1, tau_max = 2, h = 1, \
         E = 1e3, nu = 1/4, eps = 1e-5, grid 250 x 41)\n\n\
         Membrane (generalised capstan equation, section 2)\n{}\n\
         Thick body (Kikuchi-Oden regularised Coulomb, section 3)\n{}",
        commands::tension::table(&tension, &scene),
        commands::contact_output::table(&contact)
    ))
}
