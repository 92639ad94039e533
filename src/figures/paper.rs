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
pub use crate::figures::settings::{FigureRange, FigureSettings};
use crate::figures::threshold_trend;
use crate::output::{LinePlot, OutputDir, Panel, Series, Table};

/// The figures, in the order of the paper.
pub const FIGURES: [(&str, &str); 9] = [
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
    (
        "slip-panel",
        "Section 3, Fig. fullset: Slip against the ratio, b/a, h and nu as one 2 x 2 panel",
    ),
];

/// The four sweeps of the paper's Fig. fullset, in its panel order (a)-(d).
const PANEL: [&str; 4] = ["slip-ratio", "slip-ba", "slip-thickness", "slip-poisson"];

/// Slip plots drawn so far in a run: `slip-panel` reuses the four Slip plots when
/// `capstan figure all` has just drawn them (same settings), instead of solving again.
pub type PlotCache = Vec<SlipPlot>;

/// One drawn Slip figure: its name, plot and plotted points.
#[derive(Debug, Clone, PartialEq)]
pub struct SlipPlot {
    name: &'static str,
    plot: LinePlot,
    x: Vec<f64>,
    slip: Vec<f64>,
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
    /// `[n2, n3]` of the scene (the paper's 250 x 41 unless re-aimed).
    pub grid: [usize; 2],
    /// The scene file, if any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub scene: Option<String>,
    /// `--set` overrides.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub sets: Vec<String>,
    /// `--range KEY=A:B:N`, if given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub range: Option<String>,
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
pub fn run(
    name: &str,
    s: &FigureSettings,
    out: &OutputDir,
    cache: &mut PlotCache,
) -> Result<FigureReport, CliError> {
    let t = Instant::now();
    let title = FIGURES
        .iter()
        .find(|f| f.0 == name)
        .map(|f| f.1)
        .ok_or_else(|| names(name).unwrap_err())?;
    let (files, comparisons) = match name {
        "tension-ratio" => tension_ratio(s, out)?,
        "displacement" => single_solve(name, s).and_then(|_| displacement(s, out))?,
        "slip-stick" => single_solve(name, s).and_then(|_| slip_stick(s, out))?,
        "slip-panel" => slip_panel(s, out, cache)?,
        _ => slip_figure(name, s, out, cache)?,
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
    if index.scene.is_some() || !index.sets.is_empty() || index.range.is_some() {
        s += &format!(
            "Re-aimed: scene `{}`, --set `{}`, --range `{}`.\n\n",
            index.scene.as_deref().unwrap_or("(paper)"),
            index.sets.join(" "),
            index.range.as_deref().unwrap_or("-")
        );
    }
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
/// solver, beside the closed form `exp(2 mu atan(b/a))` (eq. PrismEqnPlot). Re-aimed by a scene
/// (any obstacle, loads, model) and by `--range` (any key: the ratio against that key).
fn tension_ratio(s: &FigureSettings, out: &OutputDir) -> Result<Output, CliError> {
    let defaults = [
        "friction.mu=0.5".to_owned(),
        format!("membrane.theta0={}", -FRAC_PI_4),
        format!("membrane.theta_max={FRAC_PI_4}"),
    ];
    let base = s.scene_with(&defaults)?;
    let a = base.obstacle.a;
    let steps = s.steps(41, 11);
    let (key, values) = s.sweep("obstacle.b", (0.5 * a, 1.5 * a), steps);
    // The paper's axis b/a and closed form hold on the ellipse over [-pi/4, pi/4] only.
    let paper_axis = key == "obstacle.b"
        && base.obstacle.shape == "ellipse"
        && base.membrane.theta0 == -FRAC_PI_4
        && base.membrane.theta_max == FRAC_PI_4
        && !tension::has_extra_loads(&base)
        && base.loads.membrane().weight_per_length() == 0.0
        && base.loads.membrane().speed_tension() == 0.0;
    let (x_label, x_scale) = if key == "obstacle.b" {
        ("b/a", 1.0 / a)
    } else {
        (key.as_str(), 1.0)
    };
    let (mut xs, mut ratio) = (vec![], vec![]);
    for &v in &values {
        let scene = base.with_raw(&key, &v.to_string(), "--range")?;
        xs.push(v * x_scale);
        ratio.push(tension::report(&scene)?.tension_ratio);
    }
    let mu = base.friction.mu;
    let closed: Vec<f64> = xs.iter().map(|r| (2.0 * mu * r.atan()).exp()).collect();
    let mut table = Table::new()
        .f64("value", values.clone())
        .f64(
            if key == "obstacle.b" { "b_over_a" } else { "x" },
            xs.clone(),
        )
        .f64("tension_ratio", ratio.clone());
    let mut plot = LinePlot::new(format!(
        "Membrane tension ratio on [{:.4}, {:.4}], mu = {mu}",
        base.membrane.theta0, base.membrane.theta_max
    ))
    .x_label(x_label)
    .y_label("T_max / T0")
    .series(Series::line(
        "capstan tension (solver)",
        xs.clone(),
        ratio.clone(),
    ));
    if paper_axis {
        table = table.f64("closed_form", closed.clone());
        plot = plot.series(Series::markers(
            "exp(2 mu atan(b/a))",
            xs.clone(),
            closed.clone(),
        ));
    }
    out.write_csv("tension-ratio.csv", &table)?;
    out.write_plot("tension-ratio", &plot)?;
    let files = written(&["tension-ratio.csv"], &["tension-ratio"]);
    let n = xs.len();
    let span = row(
        &format!(
            "tension ratio over {x_label} in [{:.4}, {:.4}]",
            xs[0],
            xs[n - 1]
        ),
        format!("{:.4} .. {:.4}", ratio[0], ratio[n - 1]),
        if paper_axis {
            "increasing (plot only)"
        } else {
            "-"
        },
        "membrane solver",
    );
    if !paper_axis {
        return Ok((files, vec![span]));
    }
    let err = ratio
        .iter()
        .zip(&closed)
        .map(|(x, y)| ((x - y) / y).abs())
        .fold(0.0f64, f64::max);
    let at_one = xs
        .iter()
        .position(|&x| (x - 1.0).abs() < 1e-12)
        .map_or("-".to_owned(), |i| format!("{:.6}", ratio[i]));
    Ok((
        files,
        vec![
            row(
                "tension ratio at b/a = 1",
                at_one,
                "exp(pi/4) = 2.193",
                "membrane solver",
            ),
            Comparison {
                note: format!("max relative difference to the closed form {err:.1e}"),
                ..span
            },
        ],
    ))
}

/// `--range` has no meaning for a figure of one solve.
fn single_solve(name: &str, s: &FigureSettings) -> Result<(), CliError> {
    match &s.range {
        Some(r) => Err(CliError::Scene {
            origin: "--range".into(),
            message: format!(
                "figure `{name}` draws one solve; `--range {}` applies to tension-ratio, slip-ratio, slip-ba, slip-thickness, slip-poisson, young and slip-panel (use --set {}=VALUE here)",
                r.key, r.key
            ),
        }),
        None => Ok(()),
    }
}

/// The scene's solve at `loads.tau_max = tau_max` (the paper's Figs. Oden1Eg1, Oden1Eg2;
/// a scene file keeps its own `loads.tau_max`).
fn solve_at(s: &FigureSettings, tau_max: f64) -> Result<contact::Solved, CliError> {
    let scene = s.scene_with(&[format!("loads.tau_max={tau_max}")])?;
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
    use crate::output::body;
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
        .i32("state", crate::output::body::contact_states(c));
    out.write_csv("slip-stick.csv", &table)?;
    out.write_plot(
        "slip-stick",
        &crate::output::body::state_strip(c, "Stick and slip, tau_max = 1"),
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

/// One Slip figure of the paper: its swept key, range, points (full, quick), plotted
/// abscissa per unit of the key, label, and the paper's statement.
struct SlipFigure {
    key: &'static str,
    range: (f64, f64),
    steps: (usize, usize),
    x_scale: f64,
    x_label: &'static str,
    paper: &'static str,
}

/// The paper's Slip figures by name.
fn slip_figure_of(name: &str) -> SlipFigure {
    let f = |key, range, steps, x_scale, x_label, paper| SlipFigure {
        key,
        range,
        steps,
        x_scale,
        x_label,
        paper,
    };
    match name {
        "slip-ratio" => f(
            "loads.tau_max",
            (1.0, 3.5),
            (51, 11),
            1.0,
            "tension ratio tau_max / tau0",
            "2.75",
        ),
        "slip-ba" => f(
            "obstacle.b",
            (1.0, 3.0),
            (11, 5),
            0.5,
            "b/a",
            "decreases as b/a increases",
        ),
        "slip-thickness" => f(
            "body.thickness",
            (0.5, 1.5),
            (11, 5),
            1.0,
            "h (m)",
            "decreases as h decreases",
        ),
        "slip-poisson" => f(
            "body.poisson",
            (0.0, 0.45),
            (11, 5),
            1.0,
            "nu",
            "decreases slightly as nu increases",
        ),
        _ => f(
            "body.young",
            (500.0, 1500.0),
            (5, 3),
            1.0,
            "E (Pa)",
            "71.2 % (constant)",
        ),
    }
}

/// Runs the Slip sweep of figure `name` (re-aimed by the scene and `--range`), writes
/// `<name>.csv`, `<name>.json` and the plot; returns the report, the plot and the files.
fn slip_sweep(
    name: &'static str,
    s: &FigureSettings,
    out: &OutputDir,
) -> Result<(sweep::SweepReport, SlipPlot, Vec<String>), CliError> {
    let f = slip_figure_of(name);
    let (key, values) = s.sweep(f.key, f.range, s.steps(f.steps.0, f.steps.1));
    let (x_label, x_scale) = if s.re_aimed(f.key) {
        (key.as_str(), 1.0)
    } else {
        (f.x_label, f.x_scale)
    };
    let sets = s.sets_with(&[]);
    let r = sweep::report(s.scene.as_deref(), &sets, &key, &values)?;
    let scene = s.scene_with(&[])?;
    let ok: Vec<&sweep::SweepPoint> = r.points.iter().filter(|p| p.converged).collect();
    let xs: Vec<f64> = ok.iter().map(|p| p.value * x_scale).collect();
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
    out.write_csv(&format!("{name}.csv"), &table)?;
    out.write_json(&format!("{name}.json"), &r)?;
    // Slip is a mean over the contact nodes: one node changing state moves it by 1/n2. The
    // y-axis spans at least 25 such steps, so a one-node change is not drawn as a jump.
    let quantum = 1.0 / scene.grid.n2 as f64;
    let plot = LinePlot::new(format!(
        "Slip against {x_label} (one contact node = {quantum:.4})"
    ))
    .x_label(x_label)
    .y_label("Slip (mean of -1/0/+1 states)")
    .y_min_span(25.0 * quantum)
    .series(Series::line("regularised Coulomb", xs.clone(), ys.clone()).with_markers());
    out.write_plot(name, &plot)?;
    let files = written(&[&format!("{name}.csv"), &format!("{name}.json")], &[name]);
    let drawn = SlipPlot {
        name,
        plot,
        x: xs,
        slip: ys,
    };
    Ok((r, drawn, files))
}

/// A Slip figure: the sweep, and our numbers beside the paper's.
fn slip_figure(
    name: &str,
    s: &FigureSettings,
    out: &OutputDir,
    cache: &mut PlotCache,
) -> Result<Output, CliError> {
    let name = FIGURES
        .iter()
        .map(|f| f.0)
        .find(|n| *n == name)
        .unwrap_or("young");
    let (r, plot, mut files) = slip_sweep(name, s, out)?;
    cache.retain(|p| p.name != name);
    cache.push(plot);
    let f = slip_figure_of(name);
    let mut rows = match name {
        "slip-ratio" => slip_ratio_rows(&r, s)?,
        "young" => young_rows(&r),
        _ => {
            let x_scale = if s.re_aimed(f.key) { 1.0 } else { f.x_scale };
            vec![trend_row(&r, x_scale, f.x_label, f.paper)]
        }
    };
    if name == "slip-poisson" && s.scene.is_none() && !s.re_aimed(f.key) {
        // the threshold at an accuracy target, the trend the node fraction cannot resolve, on
        // the paper's body (finding (v)); a scene file or another key re-aims the figure
        let (key, values) = s.sweep(f.key, f.range, s.steps(f.steps.0, f.steps.1));
        let stem = "slip-poisson-threshold";
        let (points, more) = threshold_trend::threshold_trend(s, &key, &values, stem, out)?;
        files.extend(more);
        let [quantity, ours, paper, note] = threshold_trend::comparison(&points, &key);
        rows.push(row(&quantity, ours, &paper, &note));
    }
    Ok((files, rows))
}

/// Fig. fullset: the four Slip plots (ratio, b/a, h, nu) as one 2 x 2 panel, from this run's
/// plots when `all` drew them, else by running the four sweeps.
fn slip_panel(
    s: &FigureSettings,
    out: &OutputDir,
    cache: &mut PlotCache,
) -> Result<Output, CliError> {
    let mut drawn = Vec::new();
    let mut files = Vec::new();
    for name in PANEL {
        match cache.iter().find(|p| p.name == name) {
            Some(p) => drawn.push(p.clone()),
            None => {
                let (_, p, f) = slip_sweep(name, s, out)?;
                files.extend(f);
                drawn.push(p);
            }
        }
    }
    let column =
        |f: fn(&SlipPlot) -> &Vec<f64>| drawn.iter().flat_map(f).copied().collect::<Vec<_>>();
    let table = Table::new()
        .text(
            "panel",
            drawn.iter().flat_map(|p| p.x.iter().map(|_| p.name)),
        )
        .f64("x", column(|p| &p.x))
        .f64("slip_fraction", column(|p| &p.slip));
    out.write_csv("slip-panel.csv", &table)?;
    let plots = drawn
        .iter()
        .zip(["(a) ", "(b) ", "(c) ", "(d) "])
        .map(|(p, tag)| p.plot.clone().prefix_title(tag).size(700, 500))
        .collect();
    out.write_plot("slip-panel", &Panel::new(plots, 2))?;
    files.extend(written(&["slip-panel.csv"], &["slip-panel"]));
    Ok((
        files,
        vec![row(
            "panels",
            "(a) ratio, (b) b/a, (c) h, (d) nu".into(),
            "Fig. fullset (a)-(d)",
            "one 2 x 2 figure; each panel as its own figure too",
        )],
    ))
}

/// The first ratio with Slip = 1 (or without a static solution) and the bisected threshold
/// with the capstan mu it implies.
fn slip_ratio_rows(
    r: &sweep::SweepReport,
    s: &FigureSettings,
) -> Result<Vec<Comparison>, CliError> {
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
        None => ("not reached in the sweep".into(), ""),
    };
    let mut rows = vec![row(
        "full slip above ratio (sweep)",
        sweep_ratio,
        "2.75",
        sweep_note,
    )];
    let threshold = "full-slip threshold ratio (bisection)";
    match crate::commands::threshold::report(&s.scene_with(&[])?) {
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
    Ok(rows)
}

/// Slip at the first and last converged point of a sweep.
fn trend_row(r: &sweep::SweepReport, x_scale: f64, x_label: &str, paper: &str) -> Comparison {
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
    let failed = r.points.iter().filter(|p| !p.converged).count();
    let note = format!("{} points, {failed} without a solution", r.points.len());
    row("Slip trend", trend, paper, &note)
}

/// Slip for E in [500, 1500]: the paper finds a constant 71.2 %.
fn young_rows(r: &sweep::SweepReport) -> Vec<Comparison> {
    let slips: Vec<f64> = r.points.iter().filter_map(|p| p.slip_fraction).collect();
    let (lo, hi) = slips
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    let ours = format!("{:.1} % .. {:.1} %", 100.0 * lo, 100.0 * hi);
    vec![row(
        "Slip for E in [500, 1500]",
        ours,
        "71.2 % (constant)",
        "Slip = mean of the -1/0/+1 node states",
    )]
}
