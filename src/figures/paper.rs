//! The figures and tables of the paper's sections 2 and 3, regenerated from built-in scenes
//! (`capstan figure <name>|all --out DIR`).
//!
//! Each figure writes `NAME.csv` (the plotted data), `NAME.svg` and `NAME.png`; `index.md`
//! and `index.json` put our numbers beside the numbers printed in the paper. Nothing here is
//! tuned toward the paper: the scenes are the paper's stated parameters (section 3: `a = 2`,
//! `b = 2`, `h = 1`, `E = 1000`, `nu = 1/4`, `mu = 1/2`, `eps = 1e-5`, `tau0 = 1`,
//! `tau_max = 2`, grid 250 x 41) and every difference is reported as it comes out.
//!
//! Sweeps over the tension ratio reuse one bulk factorisation for every ratio
//! ([`crate::commands::sweep::report`] with `loads.tau_max`); sweeps over geometry or
//! material build one model per point, in parallel.

use std::f64::consts::FRAC_PI_4;
use std::time::Instant;

use serde::Serialize;

use crate::commands::{contact, sweep, tension};
use crate::error::CliError;
use crate::output::{LinePlot, OutputDir, Series, Table};
use crate::scene::Scene;

/// The figures, in the order of the paper.
pub const FIGURES: [(&str, &str); 8] = [
    (
        "tension-ratio",
        "Section 2, Fig. PrismEqnPlot2: membrane tension ratio against b/a on [-pi/4, pi/4]",
    ),
    (
        "displacement",
        "Section 3, Fig. Oden1Eg1: displacement field v^2, v^3 (tau_max = 1)",
    ),
    (
        "slip-stick",
        "Section 3, Fig. Oden1Eg2: slip and stick regions (tau_max = 1)",
    ),
    (
        "slip-ratio",
        "Section 3, Fig. Oden1T: Slip against the tension ratio; implied capstan mu",
    ),
    ("slip-ba", "Section 3, Fig. OdenCur: Slip against b/a"),
    (
        "slip-thickness",
        "Section 3, Fig. OdenH: Slip against the thickness h",
    ),
    (
        "slip-poisson",
        "Section 3, Fig. OdenPoi: Slip against Poisson's ratio",
    ),
    (
        "young",
        "Section 3, text: Slip for Young's modulus E in [500, 1500]",
    ),
];

/// How to run the figures.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FigureSettings {
    /// Grid points along `x2` (the paper: 250).
    pub n2: usize,
    /// Grid points along `x3` (the paper: 41).
    pub n3: usize,
    /// Fewer sweep points (for tests and a first look).
    pub quick: bool,
}

impl FigureSettings {
    /// The paper's grid, 250 x 41, full sweeps.
    pub fn paper() -> Self {
        Self {
            n2: 250,
            n3: 41,
            quick: false,
        }
    }

    /// A coarse grid (40 x 9) and short sweeps: seconds, for tests.
    pub fn quick() -> Self {
        Self {
            n2: 40,
            n3: 9,
            quick: true,
        }
    }

    fn steps(&self, full: usize, quick: usize) -> usize {
        if self.quick { quick } else { full }
    }

    fn sets(&self) -> Vec<String> {
        vec![
            format!("grid.n2={}", self.n2),
            format!("grid.n3={}", self.n3),
        ]
    }

    fn scene(&self) -> Scene {
        let mut s = Scene::default();
        s.grid.n2 = self.n2;
        s.grid.n3 = self.n3;
        s
    }
}

/// One number of a figure beside the paper's.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Comparison {
    /// What is compared.
    pub quantity: String,
    /// Our value (as printed).
    pub ours: String,
    /// The paper's value (as printed there), or `-`.
    pub paper: String,
    /// How ours was obtained, or why it differs.
    pub note: String,
}

fn row(quantity: &str, ours: String, paper: &str, note: &str) -> Comparison {
    Comparison {
        quantity: quantity.into(),
        ours,
        paper: paper.into(),
        note: note.into(),
    }
}

/// What one figure produced.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FigureReport {
    /// The figure's name (`capstan figure NAME`).
    pub name: String,
    /// What it shows.
    pub title: String,
    /// Files written, relative to the output directory.
    pub files: Vec<String>,
    /// Our numbers beside the paper's.
    pub comparisons: Vec<Comparison>,
    /// Wall time, seconds.
    pub seconds: f64,
}

/// `index.json`: every figure of a run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FigureIndex {
    /// `[n2, n3]`.
    pub grid: [usize; 2],
    /// Whether `--quick` sweeps were used.
    pub quick: bool,
    /// The figures in order.
    pub figures: Vec<FigureReport>,
}

/// Resolves `name` (`all` or one of [`FIGURES`]) to figure names.
///
/// # Errors
/// [`CliError::Scene`] naming the known figures.
pub fn names(name: &str) -> Result<Vec<&'static str>, CliError> {
    if name == "all" {
        return Ok(FIGURES.iter().map(|f| f.0).collect());
    }
    FIGURES
        .iter()
        .find(|f| f.0 == name)
        .map(|f| vec![f.0])
        .ok_or_else(|| CliError::Scene {
            origin: "figure".into(),
            message: format!(
                "unknown figure `{name}`; expected `all` or one of: {}",
                FIGURES.map(|f| f.0).join(", ")
            ),
        })
}

/// Runs figure `name` into `out`.
///
/// # Errors
/// Bad names, solver failures of the single solves, output errors. Failed sweep points are
/// left out of plots and listed in the CSV-less JSON of the sweep.
pub fn run(name: &str, s: &FigureSettings, out: &OutputDir) -> Result<FigureReport, CliError> {
    let t = Instant::now();
    let title = FIGURES
        .iter()
        .find(|f| f.0 == name)
        .map(|f| f.1)
        .ok_or_else(|| names(name).unwrap_err())?;
    let (files, comparisons) = match name {
        "tension-ratio" => tension_ratio(s, out)?,
        "displacement" => displacement(s, out)?,
        "slip-stick" => slip_stick(s, out)?,
        "slip-ratio" => slip_ratio(s, out)?,
        "slip-ba" => slip_param(s, out, name, "obstacle.b", (1.0, 3.0), "b/a", 0.5)?,
        "slip-thickness" => slip_param(s, out, name, "body.thickness", (0.5, 1.5), "h (m)", 1.0)?,
        "slip-poisson" => slip_param(s, out, name, "body.poisson", (0.0, 0.45), "nu", 1.0)?,
        _ => young(s, out)?,
    };
    Ok(FigureReport {
        name: name.into(),
        title: title.into(),
        files,
        comparisons,
        seconds: t.elapsed().as_secs_f64(),
    })
}

/// Writes `index.md` and `index.json` for `index`.
///
/// # Errors
/// Output errors.
pub fn write_index(out: &OutputDir, index: &FigureIndex) -> Result<(), CliError> {
    out.write_json("index.json", index)?;
    let md = index_markdown(index);
    out.write("index.md", |w| {
        use std::io::Write as _;
        w.write_all(md.as_bytes())
            .map_err(|e| crate::output::OutputError::io("index.md", e))
    })?;
    Ok(())
}

/// The Markdown index: one section per figure with its images and a table ours vs paper.
pub fn index_markdown(index: &FigureIndex) -> String {
    let mut s = format!(
        "# The paper's figures, regenerated\n\nGrid {} x {}{}. Generated by `capstan figure all`. \
         Nothing is tuned toward the paper; differences are reported as they come out.\n\n",
        index.grid[0],
        index.grid[1],
        if index.quick { " (quick sweeps)" } else { "" }
    );
    s += "| figure | quantity | ours | paper | note |\n|---|---|---|---|---|\n";
    for f in &index.figures {
        for c in &f.comparisons {
            let cell = |x: &str| x.replace('|', "\\|");
            s += &format!(
                "| {} | {} | {} | {} | {} |\n",
                f.name,
                cell(&c.quantity),
                cell(&c.ours),
                cell(&c.paper),
                cell(&c.note)
            );
        }
    }
    for f in &index.figures {
        s += &format!("\n## {}\n\n{} ({:.1} s)\n\n", f.name, f.title, f.seconds);
        for file in &f.files {
            if file.ends_with(".svg") {
                s += &format!("![{file}]({file})\n");
            }
        }
        s += "\nFiles: ";
        s += &f
            .files
            .iter()
            .map(|x| format!("`{x}`"))
            .collect::<Vec<_>>()
            .join(", ");
        s += "\n";
    }
    s
}

/// The names of the files a figure wrote: `files`, then each plot's `<stem>.svg` and
/// `<stem>.png`.
fn written(files: &[&str], plot_stems: &[&str]) -> Vec<String> {
    let plots = plot_stems
        .iter()
        .flat_map(|stem| [format!("{stem}.svg"), format!("{stem}.png")]);
    files.iter().map(|f| (*f).to_owned()).chain(plots).collect()
}

type Output = (Vec<String>, Vec<Comparison>);

/// Section 2: `T_max / T0` against `b/a` on `[-pi/4, pi/4]`, `mu = 1/2`, by the membrane
/// solver, beside the closed form `exp(2 mu atan(b/a))` (eq. PrismEqnPlot).
fn tension_ratio(s: &FigureSettings, out: &OutputDir) -> Result<Output, CliError> {
    let n = s.steps(41, 11);
    let mut scene = Scene::default();
    scene.friction.mu = 0.5;
    scene.membrane.theta0 = -FRAC_PI_4;
    scene.membrane.theta_max = FRAC_PI_4;
    let a = scene.obstacle.a;
    let (mut ba, mut ratio, mut closed) = (vec![], vec![], vec![]);
    for i in 0..n {
        let r = 0.5 + i as f64 / (n - 1) as f64;
        scene.obstacle.b = r * a;
        ba.push(r);
        ratio.push(tension::report(&scene)?.tension_ratio);
        closed.push((2.0 * 0.5 * r.atan()).exp());
    }
    let table = Table::new()
        .f64("b_over_a", ba.clone())
        .f64("tension_ratio", ratio.clone())
        .f64("closed_form", closed.clone());
    out.write_csv("tension-ratio.csv", &table)?;
    let plot = LinePlot::new("Membrane tension ratio on [-pi/4, pi/4], mu = 1/2")
        .x_label("b/a")
        .y_label("T_max / T0")
        .series(Series::line(
            "capstan tension (solver)",
            ba.clone(),
            ratio.clone(),
        ))
        .series(Series::markers(
            "exp(2 mu atan(b/a))",
            ba.clone(),
            closed.clone(),
        ));
    out.write_plot("tension-ratio", &plot)?;
    let mid = n / 2;
    let err = ratio
        .iter()
        .zip(&closed)
        .map(|(x, y)| ((x - y) / y).abs())
        .fold(0.0f64, f64::max);
    let files = written(&["tension-ratio.csv"], &["tension-ratio"]);
    Ok((
        files,
        vec![
            row(
                "tension ratio at b/a = 1",
                format!("{:.6}", ratio[mid]),
                "exp(pi/4) = 2.193",
                "membrane solver",
            ),
            row(
                "tension ratio over b/a in [0.5, 1.5]",
                format!("{:.4} .. {:.4}", ratio[0], ratio[n - 1]),
                "increasing (plot only)",
                &format!("max relative difference to the closed form {err:.1e}"),
            ),
        ],
    ))
}

fn solve_at(s: &FigureSettings, tau_max: f64) -> Result<contact::Solved, CliError> {
    let mut scene = s.scene();
    scene.loads.tau_max = tau_max;
    match contact::solve(&scene)?.1 {
        contact::ContactRun::Plane(solved) => Ok(solved),
        contact::ContactRun::Solid { .. } => Err(CliError::Scene {
            origin: "body.dimension".into(),
            message: "the paper's figures are of the plane-strain body (body.dimension = 2)".into(),
        }),
    }
}

/// Section 3, tau_max = 1: the displacement field on the body.
fn displacement(s: &FigureSettings, out: &OutputDir) -> Result<Output, CliError> {
    use crate::figures::body;
    let solved = solve_at(s, 1.0)?;
    let grid = body::body_grid(&solved.obstacle, &solved.fields)?;
    let [v2, v3] = body::displacement_maps(&grid, &solved.fields, "tau_max = 1")?;
    out.write_plot("displacement-v2", &v2)?;
    out.write_plot("displacement-v3", &v3)?;
    out.write_vtu(
        "displacement.vtu",
        &body::body_vtu(&grid, &solved.fields, &solved.solution.contact),
    )?;
    let n = &solved.nodes;
    let table = Table::new()
        .f64("x2", n.x2.clone())
        .f64("x3", n.x3.clone())
        .f64("v2", n.v2.clone())
        .f64("v3", n.v3.clone());
    out.write_csv("displacement.csv", &table)?;
    let sol = &solved.solution;
    let (e2, e3) = (sol.max_azimuthal_displacement, sol.max_radial_displacement);
    // The extreme of opposite sign of v^2 (the paper quotes +-).
    let v2min = n.v2.iter().copied().fold(f64::INFINITY, f64::min);
    let v2max = n.v2.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let files = written(
        &["displacement.csv", "displacement.vtu"],
        &["displacement-v2", "displacement-v3"],
    );
    Ok((
        files,
        vec![
            row(
                "max v^2 (rad)",
                format!("{v2max:+.3e} / {v2min:+.3e}"),
                "+-1.72e-3",
                &format!("largest |v^2| at (x2, x3) = ({:.3}, {:.3})", e2.x2, e2.x3),
            ),
            row(
                "max |v^3| (m)",
                format!("{:+.3e}", e3.value),
                "-8.24e-4",
                &format!("at (x2, x3) = ({:.3}, {:.3})", e3.x2, e3.x3),
            ),
        ],
    ))
}

/// Section 3, tau_max = 1: stick and slip along the contact surface.
fn slip_stick(s: &FigureSettings, out: &OutputDir) -> Result<Output, CliError> {
    let solved = solve_at(s, 1.0)?;
    let sol = &solved.solution;
    let c = &sol.contact;
    let table = Table::new()
        .f64("x2", c.x2.clone())
        .f64("slip", c.slip.clone())
        .i32("state", crate::figures::body::contact_states(c));
    out.write_csv("slip-stick.csv", &table)?;
    out.write_plot(
        "slip-stick",
        &crate::figures::body::state_strip(c, "Stick and slip, tau_max = 1"),
    )?;
    let stick = sol
        .stick_interval
        .map_or("none".into(), |i| format!("({:.4}, {:.4})", i.from, i.to));
    let inner: Vec<String> = sol
        .slip_intervals()
        .map(|i| {
            let edge = if i.state > 0 { i.from } else { i.to };
            format!("{edge:+.4}")
        })
        .collect();
    let files = written(&["slip-stick.csv"], &["slip-stick"]);
    Ok((
        files,
        vec![
            row(
                "stick interval (rad)",
                stick,
                "(-0.0201, 0.0201)",
                "interpolated where |u| = eps",
            ),
            row(
                "slip beyond (rad)",
                inner.join(" / "),
                "+-0.0694",
                "inner ends of the slip runs; we find no gap between stick and slip",
            ),
            row(
                "Slip (mean state)",
                format!("{:.4}", sol.slip_fraction),
                "0 (symmetric)",
                "",
            ),
        ],
    ))
}

/// A figure of Slip against one scene key: the sweep, its table (`<stem>.csv`, `<stem>.json`)
/// and its plot.
struct SlipSweep<'a> {
    /// File stem.
    stem: &'a str,
    /// The swept scene key.
    key: &'a str,
    /// First and last value.
    range: (f64, f64),
    /// Points of the full and of the quick figure.
    steps: (usize, usize),
    /// Plotted abscissa per unit of the swept value.
    x_scale: f64,
    /// Abscissa label (its first word names the CSV column).
    x_label: &'a str,
    /// Plot title.
    title: &'a str,
}

impl<'a> SlipSweep<'a> {
    /// `steps.0` (quick: `steps.1`) values of `key` from `range.0` to `range.1`, plotted
    /// against the value itself with the key as label until [`SlipSweep::axis`] says otherwise.
    fn new(stem: &'a str, key: &'a str, range: (f64, f64), steps: (usize, usize)) -> Self {
        Self {
            stem,
            key,
            range,
            steps,
            x_scale: 1.0,
            x_label: key,
            title: key,
        }
    }

    /// The plotted abscissa `x_scale * value` with its label, and the plot's title.
    fn axis(self, x_label: &'a str, x_scale: f64, title: &'a str) -> Self {
        Self {
            x_label,
            x_scale,
            title,
            ..self
        }
    }

    /// Runs the sweep and writes its files: the report and the files' names.
    fn run(
        &self,
        s: &FigureSettings,
        out: &OutputDir,
    ) -> Result<(sweep::SweepReport, Vec<String>), CliError> {
        let values = sweep::values(
            self.range.0,
            self.range.1,
            s.steps(self.steps.0, self.steps.1),
        )?;
        let r = sweep::report(None, &s.sets(), self.key, &values)?;
        let files = self.write(out, &r)?;
        Ok((r, files))
    }

    fn write(&self, out: &OutputDir, r: &sweep::SweepReport) -> Result<Vec<String>, CliError> {
        let (stem, x_label) = (self.stem, self.x_label);
        let ok: Vec<&sweep::SweepPoint> = r.points.iter().filter(|p| p.converged).collect();
        let xs: Vec<f64> = ok.iter().map(|p| p.value * self.x_scale).collect();
        let ys: Vec<f64> = ok.iter().map(|p| p.slip_fraction.unwrap_or(0.0)).collect();
        let table = Table::new()
            .f64("value", ok.iter().map(|p| p.value).collect::<Vec<_>>())
            .f64(x_label.split(' ').next().unwrap_or("x"), xs.clone())
            .f64("slip_fraction", ys.clone())
            .f64(
                "max_v2",
                ok.iter()
                    .map(|p| p.max_azimuthal_displacement.map_or(0.0, |e| e.value))
                    .collect::<Vec<_>>(),
            )
            .text("status", ok.iter().map(|p| p.status.name()));
        out.write_csv(&format!("{stem}.csv"), &table)?;
        out.write_json(&format!("{stem}.json"), r)?;
        let plot = LinePlot::new(self.title)
            .x_label(x_label)
            .y_label("Slip (mean of -1/0/+1 states)")
            .series(Series::line("regularised Coulomb", xs, ys).with_markers());
        out.write_plot(stem, &plot)?;
        Ok(written(
            &[&format!("{stem}.csv"), &format!("{stem}.json")],
            &[stem],
        ))
    }
}

/// Slip against the tension ratio (one factorisation for every ratio), the first ratio with
/// Slip = 1 and the capstan mu it implies on `[-pi/2, pi/2]`.
fn slip_ratio(s: &FigureSettings, out: &OutputDir) -> Result<Output, CliError> {
    let (r, files) = SlipSweep::new("slip-ratio", "loads.tau_max", (1.0, 3.5), (51, 11))
        .axis(
            "tension ratio tau_max / tau0",
            1.0,
            "Slip against the tension ratio",
        )
        .run(s, out)?;
    let full = r
        .points
        .iter()
        .find(|p| !p.converged || p.slip_fraction.is_some_and(|x| x >= 1.0));
    let last_ok = r
        .points
        .iter()
        .filter(|p| p.converged)
        .map(|p| p.value)
        .fold(f64::NAN, f64::max);
    let (sweep_ratio, sweep_note) = match full {
        Some(p) => (
            format!("{:.3} (last converged {last_ok:.3})", p.value),
            if p.converged {
                "first sweep point with Slip = 1"
            } else {
                "first sweep point without a static solution"
            },
        ),
        None => ("not reached in [1, 3.5]".into(), ""),
    };
    let mut rows = vec![row(
        "full slip above ratio (sweep)",
        sweep_ratio,
        "2.75",
        sweep_note,
    )];
    // The bisected threshold and the capstan mu it implies.
    let threshold = "full-slip threshold ratio (bisection)";
    match crate::commands::threshold::report(&s.scene()) {
        Ok(t) => {
            let note = if t.no_equilibrium_beyond {
                "no static equilibrium beyond"
            } else {
                "Slip reaches 1"
            };
            rows.push(row(
                threshold,
                format!("{:.4}", t.threshold_ratio),
                "2.75",
                note,
            ));
            rows.push(row(
                "implied capstan mu",
                format!("{:.4}", t.implied_mu),
                "0.322",
                "Corollary 1 on [-pi/2, pi/2] at the threshold ratio; thick-body mu = 0.5",
            ));
        }
        Err(e) => {
            let note = format!("capstan threshold: {e}");
            rows.push(row(threshold, "failed".into(), "2.75", &note));
        }
    }
    Ok((files, rows))
}

/// Slip against one scene key (geometry or material: one model per point).
fn slip_param(
    s: &FigureSettings,
    out: &OutputDir,
    stem: &str,
    key: &str,
    range: (f64, f64),
    x_label: &str,
    x_scale: f64,
) -> Result<Output, CliError> {
    let title = format!("Slip against {x_label}, tau_max = 2");
    let (r, files) = SlipSweep::new(stem, key, range, (11, 5))
        .axis(x_label, x_scale, &title)
        .run(s, out)?;
    let ok: Vec<(f64, f64)> = r
        .points
        .iter()
        .filter_map(|p| p.slip_fraction.map(|y| (p.value * x_scale, y)))
        .collect();
    let trend = match (ok.first(), ok.last()) {
        (Some(a), Some(b)) if ok.len() > 1 => format!(
            "{:.4} at {} = {:.3} .. {:.4} at {:.3}",
            a.1,
            x_label.split(' ').next().unwrap_or("x"),
            a.0,
            b.1,
            b.0
        ),
        _ => "no converged points".into(),
    };
    let paper = match stem {
        "slip-ba" => "decreases as b/a increases",
        "slip-thickness" => "decreases as h decreases",
        _ => "decreases slightly as nu increases",
    };
    let failed = r.points.iter().filter(|p| !p.converged).count();
    let note = format!("{} points, {failed} without a solution", r.points.len());
    Ok((files, vec![row("Slip trend", trend, paper, &note)]))
}

/// Slip for E in [500, 1500]: the paper finds a constant 71.2 %.
fn young(s: &FigureSettings, out: &OutputDir) -> Result<Output, CliError> {
    let (r, files) = SlipSweep::new("young", "body.young", (500.0, 1500.0), (5, 3))
        .axis("E (Pa)", 1.0, "Slip against Young's modulus, tau_max = 2")
        .run(s, out)?;
    let slips: Vec<f64> = r.points.iter().filter_map(|p| p.slip_fraction).collect();
    let (lo, hi) = slips
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    let ours = format!("{:.1} % .. {:.1} %", 100.0 * lo, 100.0 * hi);
    let note = "Slip = mean of the -1/0/+1 node states";
    Ok((
        files,
        vec![row(
            "Slip for E in [500, 1500]",
            ours,
            "71.2 % (constant)",
            note,
        )],
    ))
}
