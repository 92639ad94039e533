//! The `contact` problem of `capstan bench work-precision`: the default scene's frictional
//! contact problem (the paper's body on the circle, regularised Coulomb, `tau_max / tau0 = 2`),
//! time against the error of three converging quantities, each a series of its own:
//! `contact-slip` (the slipping measure of the contact face), `contact-threshold` (the tension
//! ratio at which the whole face slides) and `contact-v2` (max `|v2|`).
//!
//! # Series
//! - `fd`, `fem-q1`, `fem-q2` on the grids `(6m + 1) x (m + 1)` ([`grid_levels`]), each with
//!   the condensed `newton` and the `full-newton` (sparse LU, grid sequencing);
//! - `fem-qp-hp`: the steps of the accuracy ladder (`fem-qp`, `p = 2 ... 6` with `p` geometric
//!   layers of ratio `0.15`, then the `p = 6` mesh refined in `h`:
//!   [`crate::problem::Problem::accuracy_step`]), both solvers;
//! - `fem-qp-corner`: the corner-refined mesh of order `p = 2 ... 6` on `12 x 2` cells (five
//!   layers of `0.3`, the scheme's defaults), both solvers (a solver that does not converge on a
//!   mesh is reported in `contact.failures` and its point left out);
//! - `fem-qp-transition`: two passes a run ([`crate::problem::Problem::solve_graded_after`]):
//!   the accuracy ladder's first pass ([`crate::problem::Problem::transition_first_pass`],
//!   order 2 on `12 x 2` cells) locates the stick/slip transitions, the second,
//!   [`crate::problem::Problem::corner_mesh`] of order `p = 2 ... 6` on
//!   [`crate::problem::TRANSITION_LADDER_CELLS`] (`24 x 8`, the default five corner layers at
//!   every `p`), has its `x2` lines graded toward them
//!   ([`crate::problem::DEFAULT_TRANSITION_GRADING`]); the time is both passes', the values the
//!   second's. Every order is graded toward the same first-pass transitions: the ladder of
//!   `capstan contact --tol` ([`crate::problem::Problem::transition_step`]) relocates them on
//!   every step and has `p + 3` corner layers (the same mesh at `p = 2`; docs/work-precision.md
//!   compares the two). Its threshold (full slip: no transition) is the ungraded `24 x 8`
//!   corner mesh's.
//!
//! The threshold is the condensed solver's search bracketed from the rigid-sliding limit
//! (`ThresholdSettings::bracket_at_limit`, tolerance [`THRESHOLD_TOLERANCE`]), the same for
//! every series, so its rows are labelled `newton`.
//!
//! # Measures
//! - time: wall clock from the problem to the answer (model build, set-up, Newton, the
//!   quantities; for the threshold its three solves), the fastest of [`super::REPEAT_RULE`];
//!   `setup_s` is the solver's set-up (assembly, factorisation, condensation), `solve_s` the
//!   rest, `assemble_s` 0 (inside the set-up);
//! - error: relative to the reference ([`ContactReference`]):
//!   ```text
//!   slip:      |S_h - S_ref| / |Gamma|       (|Gamma| the x2-length of the face, pi)
//!   threshold: |R_h - R_ref| / R_ref
//!   v2:        |V_h - V_ref| / V_ref,        V = max |v2| on the contact face
//!   ```
//!   the same scales as `accuracy.tol` (`src/commands/accuracy.rs`);
//! - the time of every series to each of [`CONTACT_TARGETS`] (log-log interpolation between
//!   the bracketing runs, never extrapolated), and the fastest series per quantity and target.

use std::time::Instant;

use capstan_elasticity::contact::ThresholdSettings;
use capstan_elasticity::finite_element::{DiscretisationMethod, Grading};
use capstan_elasticity::solvers::LinearBackend;
use serde::{Deserialize, Serialize};

use super::run::Run;
use super::run::{REPEAT_RULE, reset_peak, seconds_cell, status_kib};
use super::targets::{SeriesTimes, series_times_at};
use crate::error::CliError;
use crate::output::OutputDir;
use crate::problem::{Problem, SolveMethod, Solved, TRANSITION_LADDER_CELLS};
use crate::scene::Scene;

/// The target relative errors of the contact quantities.
pub const CONTACT_TARGETS: [f64; 3] = [1e-3, 1e-4, 1e-5];

/// The series names (`problem` of the runs) of the three quantities.
pub const CONTACT_PROBLEMS: [&str; 3] = ["contact-slip", "contact-threshold", "contact-v2"];

/// The relative tolerance of the threshold search of every run and of the reference: far
/// below the smallest target.
pub const THRESHOLD_TOLERANCE: f64 = 1e-8;

/// Largest body of a grid run (unknowns).
const MAX_UNKNOWNS: usize = 200_000;

/// The reference mesh: `fem-qp` of order 6 with 6 geometric layers of ratio `0.15` at each end
/// (the ladder's hp corners) around a fine uniform interior, `e2 x e3` elements, and the
/// coarser check mesh (half the elements along `x2`). Quick: order 4, 4 layers.
fn reference_meshes(quick: bool) -> [ReferenceMesh; 2] {
    if quick {
        [
            ReferenceMesh::new(4, 4, [32, 8]),
            ReferenceMesh::new(4, 4, [16, 8]),
        ]
    } else {
        [
            ReferenceMesh::new(6, 6, [240, 14]),
            ReferenceMesh::new(6, 6, [120, 14]),
        ]
    }
}

/// A graded `fem-qp` mesh of the reference.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
struct ReferenceMesh {
    order: usize,
    layers: usize,
    elements: [usize; 2],
}

impl ReferenceMesh {
    const RATIO: f64 = 0.15;

    const fn new(order: usize, layers: usize, elements: [usize; 2]) -> Self {
        Self {
            order,
            layers,
            elements,
        }
    }

    fn grid(self) -> [usize; 2] {
        self.elements.map(|e| self.order * e + 1)
    }

    fn name(self) -> String {
        format!(
            "fem-qp p {}, {} layers of {} per end, {} x {} elements",
            self.order,
            self.layers,
            Self::RATIO,
            self.elements[0],
            self.elements[1]
        )
    }

    fn problem(self) -> Result<Problem, CliError> {
        let mut p = default_problem()?;
        let [n2, n3] = self.grid();
        p = p.with_grid(n2, n3);
        p.body.method = DiscretisationMethod::FemQp;
        p.body.settings.order = self.order;
        p.body.settings.grading = Grading::geometric(Self::RATIO, self.layers)?;
        p.solver.method = SolveMethod::Condensed;
        Ok(p)
    }
}

/// The three quantities of one solve.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ContactValues {
    /// Slipping measure of the face (`x2`-length).
    pub slip_measure: f64,
    /// The threshold ratio (`None` where it was not computed).
    pub threshold_ratio: Option<f64>,
    /// max `|v2|` on the contact face.
    pub max_abs_v2: f64,
}

/// The reference of the contact problem: a graded high-order solve much finer than any run,
/// its values, and its distance to the solve on half the elements along `x2` (its
/// self-convergence). Cached as `contact-reference.json` in the output directory and reused
/// while its mesh is the same.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ContactReference {
    /// The mesh, e.g. `fem-qp p 6, 6 layers of 0.15 per end, 240 x 14 elements`.
    pub method: String,
    /// `[n2, n3]`.
    pub grid: [usize; 2],
    /// Unknowns.
    pub dofs: usize,
    /// The `x2`-length of the contact face (the slip measure's scale).
    pub contact_measure: f64,
    /// The reference values (the threshold is the rigid-sliding limit `L` of the condensed
    /// solver, which the bracketed threshold search returns to [`THRESHOLD_TOLERANCE`] on the
    /// circle).
    pub values: ContactValues,
    /// The check mesh (half the elements along `x2`).
    pub check_method: String,
    /// The check's values.
    pub check_values: ContactValues,
    /// Relative distance of the check to the reference, `[slip, threshold, v2]`, in the scales
    /// of the errors.
    pub check_change: [f64; 3],
    /// Wall time of the two solves, seconds (when computed, not when read from the cache).
    pub seconds: f64,
    /// Whether it was read from the cache.
    #[serde(default)]
    pub cached: bool,
}

/// The contact part of the report.
#[derive(Debug, Clone, Serialize)]
pub struct ContactBench {
    /// The reference.
    pub reference: ContactReference,
    /// [`CONTACT_TARGETS`].
    pub targets: Vec<f64>,
    /// Time of every series to each of [`CONTACT_TARGETS`] (`problem`: the quantity).
    pub series: Vec<SeriesTimes>,
    /// The fastest series per quantity and target.
    pub fastest: Vec<ContactFastest>,
    /// Runs that failed (a solver that does not converge on a mesh), with the reason.
    pub failures: Vec<String>,
}

/// The fastest series of one quantity at one target.
#[derive(Debug, Clone, Serialize)]
pub struct ContactFastest {
    /// `contact-slip`, `contact-threshold`, `contact-v2`.
    pub quantity: &'static str,
    /// Target relative error.
    pub target_error: f64,
    /// `method/solver threads`, `None` if no series gets there.
    pub series: Option<String>,
    /// Its time, seconds.
    pub seconds: Option<f64>,
}

/// The default scene's problem.
fn default_problem() -> Result<Problem, CliError> {
    Scene::default().build()
}

/// The three quantities of a solved problem (`threshold` computed apart).
fn values_of(solved: &Solved) -> Result<(f64, f64, f64), CliError> {
    let probes = capstan_elasticity::contact::default_probes([
        -core::f64::consts::FRAC_PI_2,
        core::f64::consts::FRAC_PI_2,
    ]);
    let q = solved.quantities(&probes)?;
    Ok((
        q.slip_measure,
        solved.solution.max_azimuthal_displacement.value.abs(),
        q.contact_measure,
    ))
}

fn threshold_settings() -> ThresholdSettings {
    ThresholdSettings {
        tolerance: THRESHOLD_TOLERANCE,
        bracket_at_limit: true,
        ..Default::default()
    }
}

/// Solves one reference mesh: values and contact measure.
fn solve_reference(mesh: ReferenceMesh) -> Result<(ContactValues, f64), CliError> {
    let solved = mesh.problem()?.solve()?;
    let (slip, v2, measure) = values_of(&solved)?;
    Ok((
        ContactValues {
            slip_measure: slip,
            threshold_ratio: solved.limiting.map(|l| l[1]),
            max_abs_v2: v2,
        },
        measure,
    ))
}

/// Relative distance `[slip, threshold, v2]` of `a` to the reference `r`.
fn relative_errors(a: &ContactValues, r: &ContactValues, measure: f64) -> [f64; 3] {
    let threshold = match (a.threshold_ratio, r.threshold_ratio) {
        (Some(x), Some(y)) => (x - y).abs() / y.abs(),
        _ => f64::NAN,
    };
    [
        (a.slip_measure - r.slip_measure).abs() / measure,
        threshold,
        (a.max_abs_v2 - r.max_abs_v2).abs() / r.max_abs_v2.abs(),
    ]
}

/// The reference: read from `contact-reference.json` in `out` when its meshes are the same,
/// else solved (the check mesh too) and written there.
///
/// # Errors
/// The solves' errors; a reference without a threshold (no rigid-sliding limit); writing the
/// cache.
pub fn reference(quick: bool, out: &OutputDir) -> Result<ContactReference, CliError> {
    let [fine, check] = reference_meshes(quick);
    let cache = out.path().join("contact-reference.json");
    if let Ok(text) = std::fs::read_to_string(&cache)
        && let Ok(mut r) = serde_json::from_str::<ContactReference>(&text)
        && r.method == fine.name()
        && r.check_method == check.name()
    {
        r.cached = true;
        return Ok(r);
    }
    let t = Instant::now();
    let (values, contact_measure) = solve_reference(fine)?;
    if values.threshold_ratio.is_none() {
        return Err(CliError::Scene {
            origin: "bench contact reference".into(),
            message: "the reference body has no rigid-sliding limit (threshold)".into(),
        });
    }
    let (check_values, _) = solve_reference(check)?;
    let [n2, n3] = fine.grid();
    let r = ContactReference {
        method: fine.name(),
        grid: [n2, n3],
        dofs: 2 * n2 * n3,
        contact_measure,
        values,
        check_method: check.name(),
        check_values,
        check_change: relative_errors(&check_values, &values, contact_measure),
        seconds: t.elapsed().as_secs_f64(),
        cached: false,
    };
    out.write_json("contact-reference.json", &r)?;
    Ok(r)
}

/// The grid levels `m` of the `fd`, `fem-q1`, `fem-q2` series: `(6m + 1) x (m + 1)` nodes
/// (the default scene's 250 x 41 lies between `m = 32` and `64`), at most
/// [`MAX_UNKNOWNS`]; quick: `m = 4, 8`.
pub fn grid_levels(quick: bool) -> Vec<usize> {
    let ms: &[usize] = if quick {
        &[4, 8]
    } else {
        &[8, 16, 32, 64, 128]
    };
    ms.iter()
        .copied()
        .filter(|&m| 2 * (6 * m + 1) * (m + 1) <= MAX_UNKNOWNS)
        .collect()
}

/// One series of the contact bench: its name (`method` of the runs), its problems and, for a
/// two-pass series, the first pass that locates the stick/slip transitions the problems are
/// graded toward.
struct ContactSeries {
    method: &'static str,
    problems: Vec<Problem>,
    first_pass: Option<Problem>,
}

/// Solves `p`, graded toward the transitions of `first_pass` when given (both passes solved
/// here, by `p`'s solver: the caller's timing includes them).
fn solve_series_problem(p: &Problem, first_pass: Option<&Problem>) -> Result<Solved, CliError> {
    Ok(match first_pass {
        Some(first) => {
            let mut first = first.clone();
            first.solver.method = p.solver.method;
            let (layers, ratio) = crate::problem::DEFAULT_TRANSITION_GRADING;
            p.solve_graded_after(&first, layers, ratio)?.second
        }
        None => p.solve()?,
    })
}

/// Every series selected by `--methods` (`fd`, `fem-q1`, `fem-q2`, `fem-qp-hp`,
/// `fem-qp-corner`, `fem-qp-transition`).
fn contact_series(quick: bool, methods: &[String]) -> Result<Vec<ContactSeries>, CliError> {
    let base = default_problem()?;
    let mut out = vec![];
    for (name, method) in [
        ("fd", DiscretisationMethod::Fd),
        ("fem-q1", DiscretisationMethod::FemQ1),
        ("fem-q2", DiscretisationMethod::FemQ2),
    ] {
        let problems = grid_levels(quick)
            .into_iter()
            .map(|m| {
                let mut p = base.clone().with_grid(6 * m + 1, m + 1);
                p.body.method = method;
                p
            })
            .collect();
        out.push(ContactSeries {
            method: name,
            problems,
            first_pass: None,
        });
    }
    let steps = if quick { 0..=1 } else { 0..=5 };
    out.push(ContactSeries {
        method: "fem-qp-hp",
        problems: steps
            .map(|k| base.accuracy_step(k))
            .collect::<Result<_, _>>()?,
        first_pass: None,
    });
    let orders = if quick { 2..=3 } else { 2..=6 };
    out.push(ContactSeries {
        method: "fem-qp-corner",
        problems: orders
            .clone()
            .map(|p| base.corner_mesh(p, [12, 2]))
            .collect(),
        first_pass: None,
    });
    out.push(ContactSeries {
        method: "fem-qp-transition",
        problems: orders
            .map(|p| base.corner_mesh(p, TRANSITION_LADDER_CELLS))
            .collect(),
        first_pass: Some(base.transition_first_pass()),
    });
    out.retain(|s| methods.is_empty() || methods.iter().any(|m| m == s.method));
    Ok(out)
}

/// The solvers of every series: the condensed Newton and the full-system Newton (sparse LU).
const SOLVERS: [(&str, SolveMethod); 2] = [
    ("newton", SolveMethod::Condensed),
    ("full-newton", SolveMethod::FullNewton(LinearBackend::LU)),
];

/// The stage times `[set-up, rest, total]` of a run and its peak memory (MiB).
struct Timing {
    seconds: [f64; 3],
    peak_mib: f64,
}

/// Times `once` (returning the set-up part of its time) with the peak memory.
fn timed<T>(
    use_vmhwm: bool,
    once: impl FnOnce() -> Result<(T, f64), CliError>,
) -> Result<(T, Timing), CliError> {
    if use_vmhwm {
        reset_peak();
    }
    let base = status_kib("VmRSS:").unwrap_or(0.0);
    let t = Instant::now();
    let (value, setup) = once()?;
    let total = t.elapsed().as_secs_f64();
    let peak_mib = if use_vmhwm {
        (status_kib("VmHWM:").unwrap_or(0.0) - base).max(0.0) / 1024.0
    } else {
        0.0
    };
    Ok((
        value,
        Timing {
            seconds: [setup, (total - setup).max(0.0), total],
            peak_mib,
        },
    ))
}

fn run_of(
    problem: &'static str,
    method: &str,
    solver: &str,
    p: &Problem,
    timing: &Timing,
    error: f64,
) -> Run {
    Run {
        problem,
        method: method.to_owned(),
        backend: solver.to_owned(),
        threads: rayon::current_num_threads(),
        n2: p.body.n2,
        n3: p.body.n3,
        dofs: p.unknowns(),
        setup_seconds: timing.seconds[0],
        assemble_seconds: 0.0,
        solve_seconds: timing.seconds[1],
        seconds: timing.seconds[2],
        error,
        peak_mib: timing.peak_mib,
    }
}

/// Every contact run of the series selected by `quick` (the coarse levels only) and `methods`
/// (`--methods`; empty: all), in the current rayon pool; failures
/// (non-convergence on a mesh) are appended to `failures` and left out.
///
/// # Errors
/// Errors other than a solve's (the series' construction).
pub fn pass(
    quick: bool,
    methods: &[String],
    reference: &ContactReference,
    use_vmhwm: bool,
    failures: &mut Vec<String>,
) -> Result<Vec<Run>, CliError> {
    let r = &reference.values;
    let measure = reference.contact_measure;
    let r_threshold = r.threshold_ratio.unwrap_or(f64::NAN);
    let mut runs = vec![];
    let reported = failures.len();
    for series in contact_series(quick, methods)? {
        for (solver, method) in SOLVERS {
            for p in &series.problems {
                let mut p = p.clone();
                p.solver.method = method;
                let mut v2_error = f64::NAN;
                let slip = REPEAT_RULE.fastest(|| -> Result<Run, CliError> {
                    let ((slip, v2, dofs), timing) = timed(use_vmhwm, || {
                        let solved = solve_series_problem(&p, series.first_pass.as_ref())?;
                        let (slip, v2, _) = values_of(&solved)?;
                        let dofs = solved.model.operator().dof_count();
                        Ok(((slip, v2, dofs), solved.times[0]))
                    })?;
                    v2_error = (v2 - r.max_abs_v2).abs() / r.max_abs_v2.abs();
                    let e = (slip - r.slip_measure).abs() / measure;
                    // the solved body's unknowns (a graded second pass has more x2 lines)
                    let mut run = run_of("contact-slip", series.method, solver, &p, &timing, e);
                    run.dofs = dofs;
                    Ok(run)
                });
                match slip {
                    Ok(slip) => {
                        let mut v2 = slip.clone();
                        v2.problem = "contact-v2";
                        v2.error = v2_error;
                        runs.push(slip);
                        runs.push(v2);
                    }
                    Err(e) => failures.push(format!(
                        "{} {solver} {} x {}: {e}",
                        series.method, p.body.n2, p.body.n3
                    )),
                }
            }
        }
        // the threshold: the condensed search, one series per discretisation
        for p in &series.problems {
            let mut p = p.clone();
            p.solver.method = SolveMethod::Condensed;
            let threshold = REPEAT_RULE.fastest(|| -> Result<Run, CliError> {
                let (ratio, timing) = timed(use_vmhwm, || {
                    let t = p.threshold_with(threshold_settings())?;
                    Ok((t.ratio, 0.0))
                })?;
                let e = (ratio - r_threshold).abs() / r_threshold.abs();
                Ok(run_of(
                    "contact-threshold",
                    series.method,
                    "newton",
                    &p,
                    &timing,
                    e,
                ))
            });
            match threshold {
                Ok(run) => runs.push(run),
                Err(e) => failures.push(format!(
                    "{} threshold {} x {}: {e}",
                    series.method, p.body.n2, p.body.n3
                )),
            }
        }
    }
    for f in &failures[reported..] {
        eprintln!("work-precision: contact: {f}");
    }
    Ok(runs)
}

/// The contact part of the report from the runs.
pub fn summary(runs: &[Run], reference: ContactReference, failures: Vec<String>) -> ContactBench {
    let series = series_times_at(runs, &CONTACT_PROBLEMS, &CONTACT_TARGETS);
    let mut fastest = vec![];
    for quantity in CONTACT_PROBLEMS {
        for (k, &target) in CONTACT_TARGETS.iter().enumerate() {
            let best = series
                .iter()
                .filter(|s| s.problem == quantity)
                .filter_map(|s| {
                    s.seconds[k].map(|t| (format!("{}/{} {}t", s.method, s.backend, s.threads), t))
                })
                .min_by(|a, b| a.1.total_cmp(&b.1));
            fastest.push(ContactFastest {
                quantity,
                target_error: target,
                seconds: best.as_ref().map(|b| b.1),
                series: best.map(|b| b.0),
            });
        }
    }
    ContactBench {
        reference,
        targets: CONTACT_TARGETS.to_vec(),
        series,
        fastest,
        failures,
    }
}

/// The contact part of the plain-text table.
pub fn table(c: &ContactBench) -> String {
    let r = &c.reference;
    let mut s = format!(
        "\ncontact (default scene): reference {} ({} unknowns{}): slip measure {:.7}, threshold {:.8}, max |v2| {:.7e}; check {}: relative changes slip {:.1e}, threshold {:.1e}, v2 {:.1e}\n",
        r.method,
        r.dofs,
        if r.cached { ", cached" } else { "" },
        r.values.slip_measure,
        r.values.threshold_ratio.unwrap_or(f64::NAN),
        r.values.max_abs_v2,
        r.check_method,
        r.check_change[0],
        r.check_change[1],
        r.check_change[2],
    );
    s += "seconds to reach a relative error of the quantity (log-log interpolation; - never reached):\n";
    s += &format!(
        "{:<18} {:<14} {:<12} {:>3}",
        "quantity", "method", "solver", "thr"
    );
    for t in CONTACT_TARGETS {
        s += &format!(" {t:>9.0e}");
    }
    s.push('\n');
    for x in &c.series {
        s += &format!(
            "{:<18} {:<14} {:<12} {:>3}",
            x.problem, x.method, x.backend, x.threads
        );
        for &t in &x.seconds {
            s += &format!(" {:>9}", seconds_cell(t));
        }
        s.push('\n');
    }
    s += "fastest per quantity:\n";
    for f in &c.fastest {
        s += &format!("{:<18} {:>6.0e}: ", f.quantity, f.target_error);
        s += &match (&f.series, f.seconds) {
            (Some(n), Some(t)) => format!("{n} {t:.4} s\n"),
            _ => "not reached\n".to_owned(),
        };
    }
    for f in &c.failures {
        s += &format!("failed: {f}\n");
    }
    s
}
