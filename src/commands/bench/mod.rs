//! `capstan bench work-precision`: run time against error for the finite differences, the
//! Q1/Q2 finite elements and the Qp elements (`fem-qp2` ... `fem-qp10`, `bench/high_order.rs`)
//! with each applicable linear backend, on three problems, beside peer FEM libraries (scikit-fem
//! on the Lamé cylinder, NGSolve on all three: [`PEERS`]; on `paper` the peer's error is
//! measured by capstan against its reference at the peer's quadrature points, `peer_error`).
//!
//! # Problems
//! - `lame`: the Lamé thick cylinder (exact), full wrap, `n2 = 4m`, `n3 = m + 1`;
//! - `mms`: the manufactured solution on the ellipse `b/a = 2` (traction-contact set),
//!   `n2 = 2m + 1`, `n3 = m + 1`, plus the `fem-qpP-x2` series (`e2 x 1` elements);
//! - `paper`: the paper's default linear stand-in ([`PaperEllipse`]), `n2 = 4m + 1`,
//!   `n3 = m + 1`, against the graded `fem-qp` reference of `bench/high_order.rs`
//!   (`high_order::paper_reference`: `p = 10`, 12 geometric layers per end, its change from
//!   `p = 9`, 11 layers in the report), plus the graded `fem-qpP-graded` series;
//! - `contact`: the default scene's frictional contact problem, time against the error of the
//!   slip measure, the threshold and max `|v2|` (series `contact-slip`, `contact-threshold`,
//!   `contact-v2`) for FD, Q1, Q2, the `fem-qp` hp ladder and `fem-qp-corner` with both
//!   nonlinear solvers, against a graded `fem-qp` reference (`contact.rs`), with its own
//!   targets [`CONTACT_TARGETS`].
//!
//! # Measures
//! - time: wall clock of building the discretisation (geometry, data, pattern), assembling,
//!   and analysing + factorising + solving, i.e. data to solution; every run is repeated by
//!   [`REPEAT_RULE`] (2 to 5 times, about 1 s), the peers' too, and the fastest kept; capstan
//!   with each `--threads` count (a rayon pool of that size: the element loops, and faer,
//!   whose default parallelism is the current pool's), the peers with one thread;
//! - error: relative physical L2 norm of the displacement error, `||U_h - U|| / ||U||`
//!   (`dA = sqrt(g) dx2 dx3`): for the finite elements by Gauss quadrature of the
//!   interpolant over the run's elements, for the finite differences (nodal values only) by
//!   the nodal trapezoid rule; on `paper` the same, against the reference's element
//!   polynomial evaluated at the quadrature points (or the FD nodes);
//! - memory: growth of the peak resident set (VmHWM) over the run, after resetting the peak
//!   through `/proc/self/clear_refs` (Linux); `estimate` (values + pattern + factor bound)
//!   where that is unavailable.
//!
//! # Output
//! Every run, the time of every series to each of [`TARGETS`] (log-log interpolation), and
//! the fastest capstan series per thread count against the fastest peer at each target.

mod contact;
mod corner;
mod high_order;
mod outputs;
mod peer_error;
mod peers;
mod run;
mod targets;

pub use contact::{
    CONTACT_PROBLEMS, CONTACT_TARGETS, ContactBench, ContactFastest, ContactReference,
    ContactValues, THRESHOLD_TOLERANCE,
};
use outputs::write_outputs;
pub use peer_error::{Rectangle, points_error, points_error_of};
pub use peers::{PEERS, Peer, PeerOrder, PeerProblem, PeerSelection, PeerStatus};
pub use run::{REPEAT_RULE, RepeatRule, Run, SeriesKey};
use run::{reset_peak, seconds_cell, status_kib};
pub use targets::{Headline, SeriesTimes, TARGETS, time_to_error};

use std::path::PathBuf;
use std::time::Instant;

use capstan_elasticity::finite_element::ElementOrder;
use capstan_elasticity::samples::{
    LameCylinder, ManufacturedField, MmsBoundaries, PaperEllipse, PrismMms,
};
use capstan_elasticity::solvers::{
    ColumnOrdering, DirectParams, IterativeParams, LinearBackend, LinearSettings, LinearSolver,
    SparseCholesky,
};
use capstan_elasticity::studies::{ProblemParts, lame_parts, mms_parts, paper_parts};
use capstan_elasticity::verification::GridLevel;
use capstan_elasticity::{Discretisation, ElasticityError, ShellGeometry};
use clap::{Args, Subcommand};
use serde::Serialize;

use crate::error::CliError;
use crate::output::OutputDir;

/// Arguments of `capstan bench`.
#[derive(Debug, Args, Clone)]
pub struct BenchArgs {
    /// Which benchmark.
    #[command(subcommand)]
    pub what: BenchCommand,
}

/// The benchmarks.
#[derive(Debug, Subcommand, Clone)]
pub enum BenchCommand {
    /// Run time against error: FD, FEM-Q1, FEM-Q2 with each linear backend, beside scikit-fem
    /// and NGSolve.
    #[command(
        after_help = "Examples:\n  capstan bench work-precision --quick\n  cargo run --release -- bench work-precision --out out/work-precision"
    )]
    WorkPrecision(WorkPrecisionArgs),
}

/// Arguments of `capstan bench work-precision`.
#[derive(Debug, Args, Clone, Default)]
pub struct WorkPrecisionArgs {
    /// Print one JSON object instead of tables.
    #[arg(long)]
    pub json: bool,
    /// Output directory for `work-precision.csv` and the plots (default `out/work-precision`).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Three coarse grids per series only (seconds, not minutes).
    #[arg(long)]
    pub quick: bool,
    /// Skip the peers (scikit-fem, NGSolve) even if `.venv/bin/python` has them.
    #[arg(long)]
    pub no_peer: bool,
    /// Thread counts of capstan's runs, each a pass over every series (e.g. `1,2`); default:
    /// all available cores (as does 0). The peers always run with one thread.
    #[arg(long, value_delimiter = ',')]
    pub threads: Vec<usize>,
    /// Problems to run (e.g. `paper`); default: all four.
    #[arg(long, value_delimiter = ',', value_enum)]
    pub problems: Vec<Problem>,
    /// capstan methods to run (e.g. `fem-qp6,fem-qp7`; `fem-qpP` also selects the graded
    /// `fem-qpP-graded` and the corner-refined `fem-qpP-corner` series of `paper` and the
    /// `fem-qpP-x2` series of `mms` (one element through the thickness);
    /// `fem-qp-hp`, `fem-qp-corner` and `fem-qp-transition` are the `contact` problem's
    /// ladder, corner-mesh and two-pass transition-graded series, the last graded toward one
    /// first pass's transitions, not relocated as by `--tol`); default: all.
    #[arg(long, value_delimiter = ',', value_parser = [
        "fd", "fem-q1", "fem-q2", "fem-qp2", "fem-qp3", "fem-qp4", "fem-qp5", "fem-qp6",
        "fem-qp7", "fem-qp8", "fem-qp9", "fem-qp10", "fem-qp-hp", "fem-qp-corner",
        "fem-qp-transition",
    ])]
    pub methods: Vec<String>,
    /// Peers to run (e.g. `ngsolve`); default: all (`--no-peer` skips them all).
    #[arg(long, value_delimiter = ',', value_parser = ["scikit-fem", "ngsolve"])]
    pub peers: Vec<String>,
    /// Peer orders to run (e.g. `6,8`), 1 to 8; default: all.
    #[arg(long, value_delimiter = ',', value_parser = clap::value_parser!(u64).range(1..=8))]
    pub peer_orders: Vec<u64>,
}

impl WorkPrecisionArgs {
    /// Whether `name` is in `list` or `list` is empty (no restriction).
    fn selects(list: &[String], name: &str) -> bool {
        list.is_empty() || list.iter().any(|x| x == name)
    }

    /// Whether `problem` is run (`--problems`; empty: every problem).
    fn selects_problem(&self, problem: Problem) -> bool {
        self.problems.is_empty() || self.problems.contains(&problem)
    }
}

/// The `paper` problem's reference: a graded `fem-qp` solve and its distance to the two graded
/// solves before it (`p - 1`, `p - 2`, one and two layers fewer per end).
#[derive(Debug, Clone, Serialize)]
pub struct PaperReferenceReport {
    /// `fem-qp10-graded, 12 layers, sigma 0.4`.
    pub method: String,
    /// Unknowns.
    pub dofs: usize,
    /// Relative L2 distance to the solve with `p - 1`, one layer fewer.
    pub change: f64,
    /// Relative L2 distance of that solve to the one with `p - 2`, two layers fewer.
    pub previous_change: f64,
}

/// The whole benchmark.
#[derive(Debug, Clone, Serialize)]
pub struct WorkPrecisionReport {
    /// Whether only coarse grids were run.
    pub quick: bool,
    /// How memory was measured: `vmhwm-delta` or `estimate`.
    pub memory: &'static str,
    /// Threads of capstan's largest pass (rayon pool: element loops, faer); kept from the first
    /// report version, see `thread_counts`.
    pub threads: usize,
    /// Thread counts of capstan's passes, one pass each.
    pub thread_counts: Vec<usize>,
    /// The `paper` problem's reference and its self-convergence (`None` unless `paper` ran).
    pub paper_reference: Option<PaperReferenceReport>,
    /// What happened to the scikit-fem peer (`ran`, or why it was skipped); kept from the first
    /// report version, see `peers`.
    pub peer: String,
    /// What happened to each peer.
    pub peers: Vec<PeerStatus>,
    /// Every run.
    pub runs: Vec<Run>,
    /// Time of every series to each of [`TARGETS`].
    pub series: Vec<SeriesTimes>,
    /// Fastest capstan series (per thread count) against the fastest peer at each target.
    pub headlines: Vec<Headline>,
    /// The `contact` problem: its reference, the time of every series to each of
    /// [`CONTACT_TARGETS`] and the fastest per quantity (`None` unless `contact` ran).
    pub contact: Option<ContactBench>,
    /// Files written.
    pub files: Vec<PathBuf>,
}

/// The problems of the benchmark (`--problems`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Problem {
    /// The Lamé thick cylinder (exact).
    Lame,
    /// The manufactured solution on the ellipse `b/a = 2`.
    Mms,
    /// The paper's default linear stand-in (graded `fem-qp` reference).
    Paper,
    /// The default scene's frictional contact problem (slip measure, threshold, max `|v2|`).
    Contact,
}

impl Problem {
    fn name(self) -> &'static str {
        match self {
            Self::Lame => "lame",
            Self::Mms => "mms",
            Self::Paper => "paper",
            Self::Contact => "contact",
        }
    }

    fn level(self, m: usize) -> GridLevel {
        match self {
            Self::Lame => GridLevel {
                n2: 4 * m,
                n3: m + 1,
            },
            Self::Mms => GridLevel {
                n2: 2 * m + 1,
                n3: m + 1,
            },
            Self::Paper => GridLevel {
                n2: 4 * m + 1,
                n3: m + 1,
            },
            Self::Contact => GridLevel {
                n2: 6 * m + 1,
                n3: m + 1,
            },
        }
    }

    fn parts(self, m: usize) -> Result<ProblemParts, ElasticityError> {
        let level = self.level(m);
        match self {
            Self::Lame => lame_parts(&LameCylinder::default(), level),
            Self::Mms => Ok(mms_parts(&mms(), level)?.0),
            Self::Paper => paper_parts(&PaperEllipse::default(), level),
            // not a linear problem: contact.rs solves it (never in `PROBLEMS`)
            Self::Contact => Err(ElasticityError::InvalidParameter {
                field: "--problems",
                value: m as f64,
                allowed: "lame, mms, paper have linear parts; contact is solved by contact.rs",
            }),
        }
    }
}

fn mms() -> PrismMms {
    PrismMms::ellipse(2.0, MmsBoundaries::TractionContact)
}

// What the error of a solution is measured against: a field `x -> [v^2, v^3]` (exact, or
// the paper's graded reference), `peer_error::Reference`.
use peer_error::Reference;

/// Relative nodal L2 error (trapezoid, `sqrt(g)` weights) of `v` on `op`'s grid.
fn nodal_error(
    op: &dyn Discretisation,
    chart: &capstan_elasticity::samples::SampleChart,
    v: &[f64],
    reference: &Reference<'_>,
) -> Result<f64, CliError> {
    let g = *op.grid();
    let (mut num, mut den) = (0.0, 0.0);
    for k in 0..g.node_count() {
        let node = g.node(k);
        let [x2, x3] = g.coordinates(node);
        let u = reference([x2, x3]);
        let p = chart.shell_point([0.0, x2, x3])?;
        let m = &p.metric;
        let e = [v[2 * k] - u[0], v[2 * k + 1] - u[1]];
        let n2 = |a: [f64; 2]| {
            m[1][1] * a[0] * a[0] + 2.0 * m[1][2] * a[0] * a[1] + m[2][2] * a[1] * a[1]
        };
        let w = g.quadrature_weight(node) * p.sqrt_g;
        num += w * n2(e);
        den += w * n2(u);
    }
    Ok((num / den).sqrt())
}

/// Timings `[setup, assemble, solve, total]`, nonzeros and the solution of one build + solve.
struct Timed<D> {
    op: D,
    v: Vec<f64>,
    seconds: [f64; 4],
    peak_mib: f64,
}

fn solve_timed<D: Discretisation>(
    build: impl FnOnce() -> Result<D, ElasticityError>,
    mut solver: Box<dyn LinearSolver<f64> + Send>,
    use_vmhwm: bool,
) -> Result<Timed<D>, CliError> {
    if use_vmhwm {
        reset_peak();
    }
    let base = status_kib("VmRSS:").unwrap_or(0.0);
    let start = Instant::now();
    let op = build()?;
    let t_setup = start.elapsed().as_secs_f64();
    let t = Instant::now();
    let system = op.system()?;
    let t_assemble = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let v = system.solve(solver.as_mut())?;
    let t_solve = t.elapsed().as_secs_f64();
    let total = start.elapsed().as_secs_f64();
    let peak_mib = if use_vmhwm {
        (status_kib("VmHWM:").unwrap_or(0.0) - base).max(0.0) / 1024.0
    } else {
        // values + pattern (12 B per nonzero) and a few vectors; the factor is not counted
        (12.0 * system.pattern.nnz() as f64 + 40.0 * op.dof_count() as f64) / 1_048_576.0
    };
    Ok(Timed {
        op,
        v,
        seconds: [t_setup, t_assemble, t_solve, total],
        peak_mib,
    })
}

/// A linear backend of the benchmark: one of [`LinearBackend`] (`cholesky`: for the finite
/// elements with the grid's ordering, [`ElementOrder::cholesky_ordering`]), Cholesky with AMD
/// on the node quotient graph (`cholesky-amd`, the solver's default when it knows no grid), or
/// Cholesky with the nested dissection of the grid by separators as wide as the element's
/// reach (`cholesky-nd`, `k` lines, cut anywhere).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Backend {
    Named(LinearBackend),
    CholeskyAmd,
    CholeskyNestedDissection,
}

impl Backend {
    fn name(self) -> &'static str {
        match self {
            Self::Named(b) => b.name(),
            Self::CholeskyAmd => "cholesky-amd",
            Self::CholeskyNestedDissection => "cholesky-nd",
        }
    }
}

fn build_solver(
    backend: Backend,
    parts: &ProblemParts,
    method: Option<ElementOrder>,
) -> Result<Box<dyn LinearSolver<f64> + Send>, CliError> {
    let cholesky = |ordering| -> Result<Box<dyn LinearSolver<f64> + Send>, CliError> {
        let params = DirectParams {
            ordering,
            ..Default::default()
        };
        Ok(Box::new(
            SparseCholesky::new(params).map_err(ElasticityError::from)?,
        ))
    };
    Ok(match (backend, method) {
        (Backend::Named(b), Some(order)) if b == LinearBackend::CHOLESKY => {
            cholesky(order.cholesky_ordering(&parts.grid))?
        }
        (Backend::CholeskyAmd, _) => cholesky(ColumnOrdering::Amd)?,
        (Backend::Named(b), _) => {
            let iterative = IterativeParams {
                tolerance: 1e-10,
                max_iterations: 20_000,
                ..Default::default()
            };
            let settings = LinearSettings {
                iterative,
                ..Default::default()
            };
            b.build(&settings, &()).map_err(ElasticityError::from)?
        }
        (Backend::CholeskyNestedDissection, _) => {
            let grid = parts.grid.shape();
            let separator_width = method.map_or(1, ElementOrder::degree);
            let params = DirectParams {
                ordering: ColumnOrdering::NestedDissection {
                    grid,
                    separator_width,
                },
                ..Default::default()
            };
            Box::new(SparseCholesky::new(params).map_err(ElasticityError::from)?)
        }
    })
}

/// One method/backend on one grid: time, error, memory; the fastest of the runs of
/// [`REPEAT_RULE`].
fn run_one(
    problem: Problem,
    m: usize,
    method: Option<ElementOrder>,
    backend: Backend,
    reference: &Reference<'_>,
    use_vmhwm: bool,
) -> Result<Run, CliError> {
    REPEAT_RULE.fastest(|| {
        let parts = problem.parts(m)?;
        let chart = parts.chart.clone();
        let solver = build_solver(backend, &parts, method)?;
        let (grid, dofs, seconds, peak_mib, error) = match method {
            None => {
                let t = solve_timed(|| parts.finite_difference(), solver, use_vmhwm)?;
                let error = nodal_error(&t.op, &chart, &t.v, reference)?;
                (*t.op.grid(), t.op.dof_count(), t.seconds, t.peak_mib, error)
            }
            Some(order) => {
                let t = solve_timed(|| parts.finite_element(order), solver, use_vmhwm)?;
                let e = t.op.displacement_errors(&t.v, *reference)?;
                let error = e.l2 / e.l2_exact;
                (*t.op.grid(), t.op.dof_count(), t.seconds, t.peak_mib, error)
            }
        };
        Ok(Run {
            problem: problem.name(),
            method: method.map_or("fd", ElementOrder::method_name).to_owned(),
            backend: backend.name().to_owned(),
            threads: rayon::current_num_threads(),
            n2: grid.n2(),
            n3: grid.n3(),
            dofs,
            setup_seconds: seconds[0],
            assemble_seconds: seconds[1],
            solve_seconds: seconds[2],
            seconds: seconds[3],
            error,
            peak_mib,
        })
    })
}

/// Runs the benchmark and writes the CSV and plots.
///
/// # Errors
/// Any elasticity, solver or output error.
pub fn report(args: &WorkPrecisionArgs) -> Result<WorkPrecisionReport, CliError> {
    let use_vmhwm = reset_peak() && status_kib("VmHWM:").is_some();
    let levels: Vec<usize> = if args.quick {
        vec![4, 8, 16]
    } else {
        vec![4, 8, 16, 32, 64, 128]
    };
    let lame = LameCylinder::default().field();
    let lame_f = move |x: [f64; 2]| lame.displacement(x).value;
    let mms_f = |x: [f64; 2]| {
        capstan_elasticity::samples::TrigonometricField
            .displacement(x)
            .value
    };
    // the paper's reference: graded fem-qp, p = 10, 12 layers (quick: 8, 8)
    let paper = if args.selects_problem(Problem::Paper) {
        let r = high_order::paper_reference(args.quick)?;
        let PaperReferenceReport {
            method,
            dofs,
            change,
            previous_change,
        } = &r.summary;
        eprintln!(
            "work-precision: paper reference {method} ({dofs} unknowns): change from the previous graded solve {change:.2e} (before: {previous_change:.2e})"
        );
        Some(r)
    } else {
        None
    };
    let paper_f = |x: [f64; 2]| {
        paper
            .as_ref()
            .map_or([f64::NAN; 2], |r| r.op.displacement_at(&r.v, x)) // never read unselected
    };
    let references: [Reference<'_>; 3] = [&lame_f, &mms_f, &paper_f];
    let out = OutputDir::create(
        args.out
            .clone()
            .unwrap_or_else(|| PathBuf::from("out/work-precision")),
    )?;
    // the contact problem's reference (cached in the output directory)
    let contact_reference = if args.selects_problem(Problem::Contact) {
        let r = contact::reference(args.quick, &out)?;
        eprintln!(
            "work-precision: contact reference {} ({} unknowns{}): check {} changes slip {:.1e}, threshold {:.1e}, v2 {:.1e}",
            r.method,
            r.dofs,
            if r.cached { ", cached" } else { "" },
            r.check_method,
            r.check_change[0],
            r.check_change[1],
            r.check_change[2]
        );
        Some(r)
    } else {
        None
    };
    let mut contact_failures = vec![];
    let threads = if args.threads.is_empty() {
        vec![rayon_threads()]
    } else {
        let all = rayon_threads();
        args.threads
            .iter()
            .map(|&n| if n == 0 { all } else { n })
            .collect()
    };
    let mut runs = vec![];
    for &n in &threads {
        // the element loops run in this pool; faer's default parallelism, `Par::rayon(0)`,
        // is the current pool's size
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map_err(|e| CliError::Io {
                path: format!("rayon pool of --threads {n}"),
                source: std::io::Error::other(e),
            })?;
        runs.extend(pool.install(|| capstan_pass(&levels, &references, use_vmhwm, args))?);
        if let Some(reference) = &contact_reference {
            runs.extend(pool.install(|| {
                contact::pass(
                    args.quick,
                    &args.methods,
                    reference,
                    use_vmhwm,
                    &mut contact_failures,
                )
            })?);
        }
    }
    let mut statuses = vec![];
    if args.no_peer {
        eprintln!("work-precision: peers skipped (--no-peer)");
    } else {
        let keep_order =
            |o: usize| args.peer_orders.is_empty() || args.peer_orders.contains(&(o as u64));
        let keep_problem = |name: &str| {
            PROBLEMS
                .iter()
                .any(|p| p.name() == name && args.selects_problem(*p))
        };
        let points_error = |name: &str, file: &std::path::Path| -> Result<f64, String> {
            let (problem, reference) = PROBLEMS
                .into_iter()
                .zip(&references)
                .find(|(p, _)| p.name() == name)
                .ok_or_else(|| format!("peer points: no problem `{name}`"))?;
            let parts = problem.parts(4).map_err(|e| e.to_string())?;
            let rect = Rectangle {
                theta: parts.grid.theta(),
                thickness: parts.grid.thickness(),
            };
            points_error(file, &parts.chart, rect, *reference)
        };
        let selection = PeerSelection {
            quick: args.quick,
            keep_order: &keep_order,
            keep_problem: &keep_problem,
            points_error: &points_error,
        };
        for peer in PEERS
            .iter()
            .filter(|p| WorkPrecisionArgs::selects(&args.peers, p.name))
        {
            let (r, status) = peers::run_peer(peer, &selection);
            if status.status != "ran" {
                eprintln!("work-precision: peer {}: {}", peer.name, status.status);
            }
            runs.extend(r);
            statuses.push(status);
        }
    }
    let series = targets::series_times(&runs, &PROBLEMS.map(Problem::name));
    let headlines = targets::headlines(&series);
    let contact = contact_reference.map(|r| contact::summary(&runs, r, contact_failures));
    let files = write_outputs(&out, &runs)?;
    let report = WorkPrecisionReport {
        quick: args.quick,
        memory: if use_vmhwm { "vmhwm-delta" } else { "estimate" },
        threads: threads.iter().copied().max().unwrap_or(1),
        peer: statuses
            .iter()
            .find(|p| p.name == "scikit-fem")
            .map_or_else(|| "skipped (--no-peer)".to_owned(), |p| p.status.clone()),
        thread_counts: threads,
        paper_reference: paper.as_ref().map(|r| r.summary.clone()),
        peers: statuses,
        runs,
        series,
        headlines,
        contact,
        files,
    };
    out.write_json("work-precision.json", &report)?;
    Ok(report)
}

/// The problems, in the order they run.
const PROBLEMS: [Problem; 3] = [Problem::Lame, Problem::Mms, Problem::Paper];

/// capstan's methods: `None` the finite differences, else the finite elements of that order.
/// A new method is one more entry here.
const METHODS: [Option<ElementOrder>; 3] = [None, Some(ElementOrder::Q1), Some(ElementOrder::Q2)];

/// The linear backends of one method: LU for all; the Cholesky variants for the (symmetric)
/// finite elements.
fn backends(method: Option<ElementOrder>) -> Vec<Backend> {
    let mut backends = vec![Backend::Named(LinearBackend::LU)];
    if method.is_some() {
        backends.push(Backend::Named(LinearBackend::CHOLESKY));
        backends.push(Backend::CholeskyAmd);
        backends.push(Backend::CholeskyNestedDissection);
    }
    backends
}

/// Every capstan series of every problem selected by `args` (`--problems`, `--methods`), in
/// the current rayon pool; `references` in the order of [`PROBLEMS`].
fn capstan_pass(
    levels: &[usize],
    references: &[Reference<'_>; 3],
    use_vmhwm: bool,
    args: &WorkPrecisionArgs,
) -> Result<Vec<Run>, CliError> {
    let quick = args.quick;
    let selected = || {
        PROBLEMS
            .into_iter()
            .zip(references)
            .filter(|(p, _)| args.selects_problem(*p))
    };
    let mut runs = vec![];
    for (problem, reference) in selected() {
        for method in METHODS.into_iter().filter(|m| {
            WorkPrecisionArgs::selects(&args.methods, m.map_or("fd", ElementOrder::method_name))
        }) {
            for backend in backends(method) {
                for &m in levels {
                    runs.push(run_one(problem, m, method, backend, reference, use_vmhwm)?);
                }
            }
            // the iterative baseline on the smallest grid only (20,000 sweeps at most)
            match run_one(
                problem,
                levels[0],
                method,
                Backend::Named(LinearBackend::GAUSS_SEIDEL),
                reference,
                use_vmhwm,
            ) {
                Ok(r) => runs.push(r),
                Err(CliError::Elasticity(e)) => eprintln!(
                    "work-precision: gauss-seidel on {} {}: {e}",
                    problem.name(),
                    method.map_or("fd", ElementOrder::method_name)
                ),
                Err(e) => return Err(e),
            }
        }
    }
    // fem-qp, p = 2 ... 10 (static condensation, Cholesky of the skeleton): high_order.rs;
    // on `paper` also graded meshes, and corner-refined ones (corner.rs), p <= 8
    for (problem, reference) in selected() {
        for p in high_order::ORDERS.filter(|&p| {
            WorkPrecisionArgs::selects(
                &args.methods,
                capstan_elasticity::finite_element::high_order::order_name(p),
            )
        }) {
            let mut meshes: Vec<high_order::QpMesh> = high_order::element_levels(problem, p, quick)
                .into_iter()
                .map(high_order::QpMesh::Uniform)
                .collect();
            if problem == Problem::Mms {
                meshes.extend(
                    high_order::x2_levels(p, quick)
                        .into_iter()
                        .map(high_order::QpMesh::AlongX2),
                );
            }
            let refined = problem == Problem::Paper && p <= high_order::PAPER_REFINED_MAX_ORDER;
            if refined {
                meshes.extend(
                    high_order::graded_layers(p, quick)
                        .into_iter()
                        .map(high_order::QpMesh::Graded),
                );
            }
            for mesh in meshes {
                runs.push(high_order::run_qp(problem, mesh, p, *reference, use_vmhwm)?);
            }
            if refined {
                for &n in corner::corner_layers(quick) {
                    runs.push(corner::run_corner(p, n, *reference, use_vmhwm)?);
                }
            }
        }
    }
    Ok(runs)
}

fn rayon_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// A plain-text table of the runs, the times to the targets and the headline ratios.
pub fn table(r: &WorkPrecisionReport) -> String {
    let peers: Vec<String> = r
        .peers
        .iter()
        .map(|p| match &p.version {
            Some(v) => format!("{} {v}: {}", p.name, p.status),
            None => format!("{}: {}", p.name, p.status),
        })
        .collect();
    let mut s = format!(
        "capstan bench work-precision ({} grids, memory: {}, threads {:?}, peers: {})\n\n{:<6} {:<10} {:<14} {:>3} {:>5} {:>5} {:>8} {:>9} {:>9} {:>9} {:>9} {:>10} {:>8}\n",
        if r.quick { "quick" } else { "all" },
        r.memory,
        r.thread_counts,
        if peers.is_empty() {
            "skipped".to_owned()
        } else {
            peers.join("; ")
        },
        "prob",
        "method",
        "backend",
        "thr",
        "n2",
        "n3",
        "dofs",
        "setup s",
        "asm s",
        "solve s",
        "total s",
        "rel error",
        "MiB"
    );
    for x in &r.runs {
        s += &format!(
            "{:<6} {:<10} {:<14} {:>3} {:>5} {:>5} {:>8} {:>9.4} {:>9.4} {:>9.4} {:>9.4} {:>10.3e} {:>8.1}\n",
            x.problem,
            x.method,
            x.backend,
            x.threads,
            x.n2,
            x.n3,
            x.dofs,
            x.setup_seconds,
            x.assemble_seconds,
            x.solve_seconds,
            x.seconds,
            x.error,
            x.peak_mib
        );
    }
    s += "\nseconds to reach a relative error (log-log interpolation; - never reached):\n";
    s += &format!(
        "{:<6} {:<10} {:<14} {:>3}",
        "prob", "method", "backend", "thr"
    );
    for t in TARGETS {
        s += &format!(" {:>9.0e}", t);
    }
    s.push('\n');
    for x in &r.series {
        s += &format!(
            "{:<6} {:<10} {:<14} {:>3}",
            x.problem, x.method, x.backend, x.threads
        );
        for &t in &x.seconds {
            s += &format!(" {:>9}", seconds_cell(t));
        }
        s.push('\n');
    }
    s += "\nfastest capstan (per thread count) against the fastest peer (ratio: peer / capstan):\n";
    for h in &r.headlines {
        s += &format!("{:<6} {:>6.0e} {}t: ", h.problem, h.target_error, h.threads);
        s += &match (&h.capstan, h.capstan_seconds) {
            (Some(c), Some(t)) => format!("capstan {c} {t:.4} s"),
            _ => "capstan does not reach it".to_owned(),
        };
        if let (Some(p), Some(t)) = (&h.peer, h.peer_seconds) {
            s += &format!(", peer {p} {t:.4} s");
        }
        if let Some(ratio) = h.ratio {
            s += &format!(", ratio {ratio:.2}x");
        }
        s.push('\n');
    }
    if let Some(c) = &r.contact {
        s += &contact::table(c);
    }
    for f in &r.files {
        s += &format!("wrote {}\n", f.display());
    }
    s
}
