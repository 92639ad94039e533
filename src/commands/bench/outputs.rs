//! The outputs of `capstan bench work-precision`: the CSV, the log-log plots (every series,
//! and the best backend of each method beside the peers) and the plain-text table.

use std::path::PathBuf;

use super::peers;
use super::run::{Run, SeriesKey};
use super::targets::{self, TARGETS, time_to_error};
use crate::error::CliError;
use crate::output::{LinePlot, OutputDir, Series, Table};

/// A series' label in the plots: `method backend`, with the threads of capstan's series.
fn label(key: &SeriesKey) -> String {
    if peers::is_peer_method(&key.0) {
        format!("{} {}", key.0, key.1)
    } else {
        format!("{} {} {}t", key.0, key.1, key.2)
    }
}

/// For the peer plot: per (method, threads), the backend that reaches the smallest error
/// target the fastest (the other backends of the method are in the CSV and the main plot).
fn best_backends(runs: &[Run], problem: &str) -> Vec<SeriesKey> {
    // (targets reached, -time to the last one reached): larger is better
    let score = |key: &SeriesKey| {
        let series = targets::series_runs(runs, problem, key);
        TARGETS
            .iter()
            .filter_map(|&t| time_to_error(&series, t))
            .enumerate()
            .last()
            .map_or((0, f64::NEG_INFINITY), |(k, t)| (k + 1, -t))
    };
    let names = targets::series_names(runs, problem);
    let mut best: Vec<SeriesKey> = vec![];
    for key in &names {
        if best.iter().any(|b| b.0 == key.0 && b.2 == key.2) {
            continue; // this method and thread count has been chosen
        }
        let winner = names
            .iter()
            .filter(|k| k.0 == key.0 && k.2 == key.2)
            .max_by(|a, b| {
                let (sa, sb) = (score(a), score(b));
                sa.0.cmp(&sb.0).then(sa.1.total_cmp(&sb.1))
            })
            .unwrap_or(key);
        best.push(winner.clone());
    }
    best
}

/// The CSV and the log-log plots: one per problem with every series, and one per problem with
/// the best backend of each method, capstan's and the peers'.
pub(super) fn write_outputs(out: &OutputDir, runs: &[Run]) -> Result<Vec<PathBuf>, CliError> {
    let mut files = vec![];
    let col = |f: fn(&Run) -> f64| runs.iter().map(f).collect::<Vec<f64>>();
    let int = |f: fn(&Run) -> usize| runs.iter().map(|r| f(r) as i32).collect::<Vec<i32>>();
    let table = Table::new()
        .text("problem", runs.iter().map(|r| r.problem))
        .text("method", runs.iter().map(|r| r.method.clone()))
        .text("backend", runs.iter().map(|r| r.backend.clone()))
        .i32("threads", int(|r| r.threads))
        .i32("n2", int(|r| r.n2))
        .i32("n3", int(|r| r.n3))
        .i32("dofs", int(|r| r.dofs))
        .f64("setup_s", col(|r| r.setup_seconds))
        .f64("assemble_s", col(|r| r.assemble_seconds))
        .f64("solve_s", col(|r| r.solve_seconds))
        .f64("seconds", col(|r| r.seconds))
        .f64("relative_l2_error", col(|r| r.error))
        .f64("peak_mib", col(|r| r.peak_mib));
    files.push(out.write_csv("work-precision.csv", &table)?);
    let plots = [
        (
            "lame",
            "Lame cylinder (exact): relative L2 error vs time",
            false,
        ),
        (
            "lame",
            "Lame cylinder: capstan and the peers, best backend per method",
            true,
        ),
        (
            "mms",
            "Manufactured solution, ellipse b/a = 2: relative L2 error vs time",
            false,
        ),
        (
            "mms",
            "Manufactured solution, ellipse b/a = 2: capstan and NGSolve, best backend per method",
            true,
        ),
        (
            "paper",
            "Paper's linear stand-in (graded fem-qp10 reference): relative L2 error vs time",
            false,
        ),
        (
            "paper",
            "Paper's linear stand-in: capstan and NGSolve (RefineHP at the corners), best backend per method",
            true,
        ),
    ];
    // the contact problem's quantities (contact.rs): every series, no peers
    let contact = [
        (
            "contact-slip",
            "Default contact scene: slip measure, relative error (of the face length) vs time",
        ),
        (
            "contact-threshold",
            "Default contact scene: threshold ratio, relative error vs time",
        ),
        (
            "contact-v2",
            "Default contact scene: max |v2|, relative error vs time",
        ),
    ];
    let plots = plots
        .into_iter()
        .map(|(p, t, b)| (p, t, b, "relative L2 error"))
        .chain(
            contact
                .into_iter()
                .map(|(p, t)| (p, t, false, "relative error of the quantity")),
        );
    for (problem, title, best, y_label) in plots {
        let mut plot = LinePlot::new(title)
            .size(1200, 800)
            .x_label("wall time (s)")
            .y_label(y_label)
            .log_log();
        let keys = if best {
            best_backends(runs, problem)
        } else {
            targets::series_names(runs, problem)
        };
        if keys.is_empty() {
            continue; // a problem left out by `--problems`
        }
        for key in keys {
            let mut pts: Vec<(f64, f64)> = targets::series_runs(runs, problem, &key)
                .into_iter()
                .map(|r| (r.seconds, r.error))
                .filter(|p| p.0 > 0.0 && p.1 > 0.0)
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            let (x, y): (Vec<f64>, Vec<f64>) = pts.into_iter().unzip();
            plot = plot.series(if x.len() > 1 {
                Series::line(label(&key), x, y).with_markers()
            } else {
                Series::markers(label(&key), x, y)
            });
        }
        let name = if best {
            format!("work-precision-{problem}-peers")
        } else {
            format!("work-precision-{problem}")
        };
        files.extend(out.write_plot(&name, &plot)?);
    }
    Ok(files)
}
