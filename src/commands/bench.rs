//! `capstan bench work-precision`: run time against error for the finite differences, the
//! Q1/Q2 finite elements and the Qp elements (`fem-qp2` ... `fem-qp8`, `bench/high_order.rs`) with each applicable linear backend, on three problems, beside a peer
//! FEM library (scikit-fem) on the Lamé cylinder.
//!
//! # Problems
//! - `lame`: the Lamé thick cylinder (exact), full wrap, `n2 = 4m`, `n3 = m + 1`;
//! - `mms`: the manufactured solution on the ellipse `b/a = 2` (traction-contact set),
//!   `n2 = 2m + 1`, `n3 = m + 1`;
//! - `paper`: the paper's default linear stand-in ([`PaperEllipse`]), `n2 = 4m + 1`,
//!   `n3 = m + 1`, against a Q2 reference on a grid twice as fine as the finest run.
//!
//! # Measures
//! - time: wall clock of building the discretisation (geometry, data, pattern), assembling,
//!   and analysing + factorising + solving, i.e. data to solution; every run is repeated by
//!   [`REPEAT_RULE`] (2 to 5 times, about 1 s), the peer's too, and the fastest kept;
//! - error: relative physical L2 norm of the displacement error, `||U_h - U|| / ||U||`
//!   (`dA = sqrt(g) dx2 dx3`): for the finite elements by Gauss quadrature of the
//!   interpolant, for the finite differences (nodal values only) by the nodal trapezoid rule;
//!   on `paper` the nodal trapezoid rule for every method, against the reference's nodes;
//! - memory: growth of the peak resident set (VmHWM) over the run, after resetting the peak
//!   through `/proc/self/clear_refs` (Linux); `estimate` (values + pattern + factor bound)
//!   where that is unavailable.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use capstan_elasticity::finite_element::{
    ElementOrder, ProblemParts, lame_parts, mms_parts, paper_parts,
};
use capstan_elasticity::samples::{
    LameCylinder, ManufacturedField, MmsBoundaries, PaperEllipse, PrismMms,
};
use capstan_elasticity::solvers::{
    ColumnOrdering, DirectParams, GridShape, IterativeParams, LinearBackend, LinearSolver,
    SparseCholesky,
};
use capstan_elasticity::verification::GridLevel;
use capstan_elasticity::{Discretisation, ElasticityError, ShellGeometry};
use clap::{Args, Subcommand};
use serde::Serialize;

use crate::error::CliError;
use crate::output::{LinePlot, OutputDir, Series, Table};

mod high_order;

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
    /// Run time against error: FD, FEM-Q1, FEM-Q2 with each linear backend, beside scikit-fem.
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
    /// Skip the scikit-fem peer even if `.venv/bin/python` has it.
    #[arg(long)]
    pub no_peer: bool,
}

/// One timed solve.
#[derive(Debug, Clone, Serialize)]
pub struct Run {
    /// `lame`, `mms`, `paper`.
    pub problem: &'static str,
    /// `fd`, `fem-q1`, `fem-q2`, `fem-qp2` ... `fem-qp8`, `skfem-q1`, `skfem-q2`.
    pub method: String,
    /// `lu`, `cholesky`, `gauss-seidel`, `scipy-superlu`.
    pub backend: String,
    /// Nodes in `x2` (the peer: vertices around).
    pub n2: usize,
    /// Nodes in `x3`.
    pub n3: usize,
    /// Unknowns.
    pub dofs: usize,
    /// Discretisation build (geometry, data, pattern), seconds.
    pub setup_seconds: f64,
    /// Assembly, seconds.
    pub assemble_seconds: f64,
    /// Analyse + factor + solve (or iterate), seconds.
    pub solve_seconds: f64,
    /// Data to solution, seconds.
    pub seconds: f64,
    /// Relative L2 displacement error.
    pub error: f64,
    /// Peak memory of the run, MiB.
    pub peak_mib: f64,
}

/// The time each series needs for one relative error, interpolated log-log between runs.
#[derive(Debug, Clone, Serialize)]
pub struct Headline {
    /// Problem.
    pub problem: &'static str,
    /// Target relative error.
    pub target_error: f64,
    /// Fastest capstan series at the target: `method/backend`.
    pub capstan: String,
    /// Its time, seconds.
    pub capstan_seconds: f64,
    /// Fastest peer series at the target.
    pub peer: Option<String>,
    /// Its time, seconds.
    pub peer_seconds: Option<f64>,
    /// `peer_seconds / capstan_seconds`.
    pub ratio: Option<f64>,
}

/// The whole benchmark.
#[derive(Debug, Clone, Serialize)]
pub struct WorkPrecisionReport {
    /// Whether only coarse grids were run.
    pub quick: bool,
    /// How memory was measured: `vmhwm-delta` or `estimate`.
    pub memory: &'static str,
    /// Threads of the rayon pool (element loops, faer).
    pub threads: usize,
    /// What happened to the peer (`ran`, or why it was skipped).
    pub peer: String,
    /// Every run.
    pub runs: Vec<Run>,
    /// Time to reach `1e-6` (and `1e-4`) relative error, per problem.
    pub headlines: Vec<Headline>,
    /// Files written.
    pub files: Vec<PathBuf>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Problem {
    Lame,
    Mms,
    Paper,
}

impl Problem {
    fn name(self) -> &'static str {
        match self {
            Self::Lame => "lame",
            Self::Mms => "mms",
            Self::Paper => "paper",
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
        }
    }

    fn parts(self, m: usize) -> Result<ProblemParts, ElasticityError> {
        let level = self.level(m);
        match self {
            Self::Lame => lame_parts(&LameCylinder::default(), level),
            Self::Mms => Ok(mms_parts(&mms(), level)?.0),
            Self::Paper => paper_parts(&PaperEllipse::default(), level),
        }
    }
}

fn mms() -> PrismMms {
    PrismMms::ellipse(2.0, MmsBoundaries::TractionContact)
}

/// Resets the peak resident set (Linux `clear_refs` 5); false if unavailable.
fn reset_peak() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

fn status_kib(field: &str) -> Option<f64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    s.lines()
        .find(|l| l.starts_with(field))
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|v| v.parse().ok())
}

/// What the error of a solution is measured against.
enum Reference<'a> {
    /// An exact field `x -> [v^2, v^3]`.
    Exact(&'a (dyn Fn([f64; 2]) -> [f64; 2] + Sync)),
    /// Nodal values of a finer nested grid `(n2, n3, v)`, every `stride`-th node.
    Nodal(&'a (usize, usize, Vec<f64>)),
}

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
        let u = match reference {
            Reference::Exact(f) => f([x2, x3]),
            Reference::Nodal((n2, n3, vr)) => {
                let s2 = (n2 - 1) / (g.n2() - 1);
                let s3 = (n3 - 1) / (g.n3() - 1);
                let kr = node[0] * s2 * n3 + node[1] * s3;
                [vr[2 * kr], vr[2 * kr + 1]]
            }
        };
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
        (Backend::Named(LinearBackend::Cholesky), Some(order)) => {
            cholesky(order.cholesky_ordering(&parts.grid))?
        }
        (Backend::CholeskyAmd, _) => cholesky(ColumnOrdering::Amd)?,
        (Backend::Named(b), _) => {
            let iterative = IterativeParams {
                tolerance: 1e-10,
                max_iterations: 20_000,
                ..Default::default()
            };
            b.build(&iterative).map_err(ElasticityError::from)?
        }
        (Backend::CholeskyNestedDissection, _) => {
            let grid = GridShape {
                n2: parts.grid.n2(),
                n3: parts.grid.n3(),
                dofs_per_node: 2,
                periodic: parts.grid.is_periodic(),
            };
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

/// How often each run of the benchmark (capstan's and the peer's alike) is repeated: at least
/// `min` times, then until `budget_seconds` of run time have been spent or `max` runs made; the
/// fastest run (total time) is kept, with its stage split. The minimum is the least perturbed
/// estimate of the work on a shared machine: noise only ever adds time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RepeatRule {
    /// Runs at least this many times.
    pub min: usize,
    /// Runs at most this many times.
    pub max: usize,
    /// Stops repeating (after `min` runs) once the runs have taken this long in total.
    pub budget_seconds: f64,
}

/// The rule of `capstan bench work-precision`: 2 to 5 runs, about 1 s per grid.
pub const REPEAT_RULE: RepeatRule = RepeatRule {
    min: 2,
    max: 5,
    budget_seconds: 1.0,
};

impl RepeatRule {
    /// Whether another run is due after `runs` runs that took `spent` seconds in total.
    pub fn again(&self, runs: usize, spent: f64) -> bool {
        runs < self.min || (runs < self.max && spent < self.budget_seconds)
    }

    /// The peer's command-line arguments for the same rule.
    fn peer_args(&self) -> [String; 6] {
        [
            "--repeat-min".to_owned(),
            self.min.to_string(),
            "--repeat-max".to_owned(),
            self.max.to_string(),
            "--repeat-budget".to_owned(),
            self.budget_seconds.to_string(),
        ]
    }
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
    let mut best: Option<Run> = None;
    let (mut runs, mut spent) = (0, 0.0);
    while REPEAT_RULE.again(runs, spent) {
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
                let error = match reference {
                    Reference::Exact(f) => {
                        let e = t.op.displacement_errors(&t.v, *f)?;
                        e.l2 / e.l2_exact
                    }
                    Reference::Nodal(_) => nodal_error(&t.op, &chart, &t.v, reference)?,
                };
                (*t.op.grid(), t.op.dof_count(), t.seconds, t.peak_mib, error)
            }
        };
        runs += 1;
        spent += seconds[3];
        let run = Run {
            problem: problem.name(),
            method: method.map_or("fd", ElementOrder::method_name).to_owned(),
            backend: backend.name().to_owned(),
            n2: grid.n2(),
            n3: grid.n3(),
            dofs,
            setup_seconds: seconds[0],
            assemble_seconds: seconds[1],
            solve_seconds: seconds[2],
            seconds: seconds[3],
            error,
            peak_mib,
        };
        if best.as_ref().is_none_or(|b| run.seconds < b.seconds) {
            best = Some(run);
        }
    }
    Ok(best.expect("at least one run"))
}

/// The peer script, if `.venv/bin/python` can import scikit-fem.
fn peer_python() -> Result<PathBuf, String> {
    let python = PathBuf::from(".venv/bin/python");
    let script = Path::new("bench/peers/skfem_lame.py");
    if !script.exists() {
        return Err(format!(
            "skipped: {} not found (run from the repository root)",
            script.display()
        ));
    }
    match Command::new(&python).args(["-c", "import skfem"]).output() {
        Ok(o) if o.status.success() => Ok(python),
        _ => Err("skipped: .venv/bin/python with scikit-fem not found (python3 -m venv .venv && .venv/bin/pip install scikit-fem)".to_owned()),
    }
}

fn run_peer(python: &Path, order: usize, levels: &str) -> Result<Vec<Run>, String> {
    let out = Command::new(python)
        .args([
            "bench/peers/skfem_lame.py",
            "--order",
            &order.to_string(),
            "--levels",
            levels,
        ])
        .args(REPEAT_RULE.peer_args())
        .output()
        .map_err(|e| format!("peer failed to start: {e}"))?;
    if !out.status.success() {
        return Err(format!(
            "peer failed: {}",
            String::from_utf8_lossy(&out.stderr)
                .lines()
                .last()
                .unwrap_or("")
        ));
    }
    let mut runs = vec![];
    for line in String::from_utf8_lossy(&out.stdout).lines() {
        let v: serde_json::Value =
            serde_json::from_str(line).map_err(|e| format!("peer output: {e}"))?;
        let num = |k: &str| v[k].as_f64().unwrap_or(f64::NAN);
        runs.push(Run {
            problem: "lame",
            method: format!("skfem-q{order}"),
            backend: "scipy-superlu".to_owned(),
            n2: num("n2") as usize,
            n3: num("n3") as usize,
            dofs: num("dofs") as usize,
            setup_seconds: num("setup_seconds"),
            assemble_seconds: num("assemble_seconds"),
            solve_seconds: num("solve_seconds"),
            seconds: num("seconds"),
            error: num("error"),
            peak_mib: num("peak_mib"),
        });
    }
    Ok(runs)
}

/// Time to reach `target` along one series (log-log interpolation between the bracketing
/// runs); `None` if the series never gets there.
fn time_to_error(runs: &[&Run], target: f64) -> Option<f64> {
    let mut pts: Vec<(f64, f64)> = runs.iter().map(|r| (r.error, r.seconds)).collect();
    pts.sort_by(|a, b| b.0.total_cmp(&a.0)); // decreasing error
    pts.windows(2).find_map(|w| {
        let ((e0, t0), (e1, t1)) = (w[0], w[1]);
        (e0 >= target && e1 <= target).then(|| {
            let s = (target.ln() - e0.ln()) / (e1.ln() - e0.ln());
            (t0.ln() + s * (t1.ln() - t0.ln())).exp()
        })
    })
}

fn series_names(runs: &[Run], problem: &str) -> Vec<(String, String)> {
    let mut names: Vec<(String, String)> = vec![];
    for r in runs.iter().filter(|r| r.problem == problem) {
        let key = (r.method.clone(), r.backend.clone());
        if !names.contains(&key) {
            names.push(key);
        }
    }
    names
}

fn headlines(runs: &[Run]) -> Vec<Headline> {
    let mut out = vec![];
    for problem in ["lame", "mms", "paper"] {
        for target in [1e-4, 1e-6, 1e-8, 1e-10] {
            let mut capstan: Option<(String, f64)> = None;
            let mut peer: Option<(String, f64)> = None;
            for (method, backend) in series_names(runs, problem) {
                let series: Vec<&Run> = runs
                    .iter()
                    .filter(|r| r.problem == problem && r.method == method && r.backend == backend)
                    .collect();
                if let Some(t) = time_to_error(&series, target) {
                    let slot = if method.starts_with("skfem") {
                        &mut peer
                    } else {
                        &mut capstan
                    };
                    if slot.as_ref().is_none_or(|s| t < s.1) {
                        *slot = Some((format!("{method}/{backend}"), t));
                    }
                }
            }
            if let Some((name, t)) = capstan {
                out.push(Headline {
                    problem,
                    target_error: target,
                    capstan: name,
                    capstan_seconds: t,
                    ratio: peer.as_ref().map(|p| p.1 / t),
                    peer_seconds: peer.as_ref().map(|p| p.1),
                    peer: peer.map(|p| p.0),
                });
            }
        }
    }
    out
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
    // the paper's reference: Q2 on a grid twice as fine as the finest run
    let m_ref = 2 * levels.last().copied().unwrap_or(16);
    let reference_values = {
        let level = Problem::Paper.level(m_ref);
        let op = Problem::Paper
            .parts(m_ref)?
            .finite_element(ElementOrder::Q2)?;
        let mut chol = LinearBackend::Cholesky
            .build(&IterativeParams::default())
            .map_err(ElasticityError::from)?;
        let v = op.solve(chol.as_mut())?;
        (level.n2, level.n3, v)
    };
    let mut runs = vec![];
    for problem in [Problem::Lame, Problem::Mms, Problem::Paper] {
        let reference = match problem {
            Problem::Lame => Reference::Exact(&lame_f),
            Problem::Mms => Reference::Exact(&mms_f),
            Problem::Paper => Reference::Nodal(&reference_values),
        };
        for method in [None, Some(ElementOrder::Q1), Some(ElementOrder::Q2)] {
            let mut backends = vec![Backend::Named(LinearBackend::Lu)];
            if method.is_some() {
                backends.push(Backend::Named(LinearBackend::Cholesky));
                backends.push(Backend::CholeskyAmd);
                backends.push(Backend::CholeskyNestedDissection);
            }
            for &backend in &backends {
                for &m in &levels {
                    runs.push(run_one(problem, m, method, backend, &reference, use_vmhwm)?);
                }
            }
            // the iterative baseline on the smallest grid only (20,000 sweeps at most)
            match run_one(
                problem,
                levels[0],
                method,
                Backend::Named(LinearBackend::GaussSeidel),
                &reference,
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
    // fem-qp, p = 2 ... 8 (static condensation, Cholesky of the skeleton): bench/high_order.rs
    for problem in [Problem::Lame, Problem::Mms, Problem::Paper] {
        let reference = match problem {
            Problem::Lame => Reference::Exact(&lame_f),
            Problem::Mms => Reference::Exact(&mms_f),
            Problem::Paper => Reference::Nodal(&reference_values),
        };
        for p in high_order::ORDERS {
            for k in high_order::element_levels(problem, p, args.quick) {
                runs.push(high_order::run_qp(problem, k, p, &reference, use_vmhwm)?);
            }
        }
    }
    let peer = if args.no_peer {
        "skipped: --no-peer".to_owned()
    } else {
        match peer_python() {
            Ok(python) => {
                let peer_levels = if args.quick { "4,8" } else { "4,8,16,32" };
                let mut status = "ran".to_owned();
                for order in [1, 2] {
                    match run_peer(&python, order, peer_levels) {
                        Ok(r) => runs.extend(r),
                        Err(e) => status = e,
                    }
                }
                status
            }
            Err(why) => why,
        }
    };
    if peer != "ran" {
        eprintln!("work-precision: peer {peer}");
    }
    let headlines = headlines(&runs);
    let out = OutputDir::create(
        args.out
            .clone()
            .unwrap_or_else(|| PathBuf::from("out/work-precision")),
    )?;
    let mut files = vec![];
    let col = |f: fn(&Run) -> f64| runs.iter().map(f).collect::<Vec<f64>>();
    let table = Table::new()
        .text("problem", runs.iter().map(|r| r.problem))
        .text("method", runs.iter().map(|r| r.method.clone()))
        .text("backend", runs.iter().map(|r| r.backend.clone()))
        .i32("n2", runs.iter().map(|r| r.n2 as i32).collect::<Vec<_>>())
        .i32("n3", runs.iter().map(|r| r.n3 as i32).collect::<Vec<_>>())
        .i32(
            "dofs",
            runs.iter().map(|r| r.dofs as i32).collect::<Vec<_>>(),
        )
        .f64("setup_s", col(|r| r.setup_seconds))
        .f64("assemble_s", col(|r| r.assemble_seconds))
        .f64("solve_s", col(|r| r.solve_seconds))
        .f64("seconds", col(|r| r.seconds))
        .f64("relative_l2_error", col(|r| r.error))
        .f64("peak_mib", col(|r| r.peak_mib));
    files.push(out.write_csv("work-precision.csv", &table)?);
    for problem in ["lame", "mms", "paper"] {
        let title = match problem {
            "lame" => "Lame cylinder (exact): relative L2 error vs time",
            "mms" => "Manufactured solution, ellipse b/a = 2: relative L2 error vs time",
            _ => "Paper's linear stand-in (Q2 reference): relative L2 error vs time",
        };
        let mut plot = LinePlot::new(title)
            .x_label("wall time (s)")
            .y_label("relative L2 error")
            .log_log();
        for (method, backend) in series_names(&runs, problem) {
            let mut pts: Vec<(f64, f64)> = runs
                .iter()
                .filter(|r| r.problem == problem && r.method == method && r.backend == backend)
                .map(|r| (r.seconds, r.error))
                .filter(|p| p.0 > 0.0 && p.1 > 0.0)
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            let label = format!("{method} {backend}");
            let (x, y): (Vec<f64>, Vec<f64>) = pts.into_iter().unzip();
            plot = plot.series(if x.len() > 1 {
                Series::line(label, x, y).with_markers()
            } else {
                Series::markers(label, x, y)
            });
        }
        files.extend(out.write_plot(&format!("work-precision-{problem}"), &plot)?);
    }
    let report = WorkPrecisionReport {
        quick: args.quick,
        memory: if use_vmhwm { "vmhwm-delta" } else { "estimate" },
        threads: rayon_threads(),
        peer,
        runs,
        headlines,
        files,
    };
    out.write_json("work-precision.json", &report)?;
    Ok(report)
}

fn rayon_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// A plain-text table of the runs and the headline ratios.
pub fn table(r: &WorkPrecisionReport) -> String {
    let mut s = format!(
        "capstan bench work-precision ({} grids, memory: {}, {} threads, peer: {})\n\n{:<6} {:<9} {:<14} {:>5} {:>5} {:>8} {:>9} {:>9} {:>9} {:>9} {:>10} {:>8}\n",
        if r.quick { "quick" } else { "all" },
        r.memory,
        r.threads,
        r.peer,
        "prob",
        "method",
        "backend",
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
            "{:<6} {:<9} {:<14} {:>5} {:>5} {:>8} {:>9.4} {:>9.4} {:>9.4} {:>9.4} {:>10.3e} {:>8.1}\n",
            x.problem,
            x.method,
            x.backend,
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
    s += "\ntime to reach a relative error (log-log interpolation):\n";
    for h in &r.headlines {
        s += &format!(
            "{:<6} {:>8.0e}: capstan {} {:.4} s",
            h.problem, h.target_error, h.capstan, h.capstan_seconds
        );
        if let (Some(p), Some(t), Some(ratio)) = (&h.peer, h.peer_seconds, h.ratio) {
            s += &format!(", peer {p} {t:.4} s, ratio {ratio:.1}x");
        }
        s.push('\n');
    }
    for f in &r.files {
        s += &format!("wrote {}\n", f.display());
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(error: f64, seconds: f64) -> Run {
        Run {
            problem: "lame",
            method: "fem-q2".into(),
            backend: "cholesky".into(),
            n2: 0,
            n3: 0,
            dofs: 0,
            setup_seconds: 0.0,
            assemble_seconds: 0.0,
            solve_seconds: 0.0,
            seconds,
            error,
            peak_mib: 0.0,
        }
    }

    #[test]
    fn repeat_rule_runs_twice_at_least_and_stops_at_the_budget_or_five() {
        let runs = |seconds: f64| {
            let mut n = 0;
            while REPEAT_RULE.again(n, n as f64 * seconds) {
                n += 1;
            }
            n
        };
        assert_eq!(runs(0.001), 5);
        assert_eq!(runs(0.3), 4); // 0.9 s after three runs: one more
        assert_eq!(runs(0.6), 2);
        assert_eq!(runs(3.0), 2);
    }

    #[test]
    fn time_to_error_interpolates_log_log_and_refuses_to_extrapolate() {
        let runs = [run(1e-3, 0.01), run(1e-5, 0.1), run(1e-7, 1.0)];
        let refs: Vec<&Run> = runs.iter().collect();
        // error ~ t^-2 here: 1e-6 lies half way (in logs) between 0.1 s and 1 s
        let t = time_to_error(&refs, 1e-6).unwrap();
        assert!((t - 10f64.powf(-0.5)).abs() < 1e-12);
        assert!(time_to_error(&refs, 1e-8).is_none());
    }
}
