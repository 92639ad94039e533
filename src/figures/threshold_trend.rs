//! The threshold ratio against the swept key of a Slip figure at an accuracy target
//! (`figure slip-poisson` draws it beside the node-fraction Slip): each point's threshold
//! with its estimated error, so the trend is drawn at a stated accuracy.

use rayon::prelude::*;

use crate::commands::threshold;
use crate::error::CliError;
use crate::figures::settings::FigureSettings;
use crate::output::{LinePlot, OutputDir, Series, Table};

/// The accuracy target of the trend when the scene sets none: `1e-4` relative (`--quick`:
/// `1e-3`), an error bar ten times smaller than the threshold's change between the paper's
/// `nu` steps (docs/errata.md, finding (v)).
pub fn default_tolerance(quick: bool) -> f64 {
    if quick { 1e-3 } else { 1e-4 }
}

/// One point of the trend.
#[derive(Debug, Clone, PartialEq)]
pub struct TrendPoint {
    /// The swept key's value.
    pub value: f64,
    /// The threshold ratio.
    pub threshold: f64,
    /// Its estimated error (absolute).
    pub estimate: f64,
    /// The grid the accuracy target chose.
    pub grid: [usize; 2],
}

/// The threshold at an accuracy target over `values` of `key`, written as `<stem>.csv`
/// (`value, threshold_ratio, estimated_error, n2, n3`) and plotted as `<stem>` with the
/// `+- estimate` band; returns the points and the files written.
///
/// # Errors
/// The first point's error when every point fails (its scene, its threshold, the accuracy
/// target's budget); a failing point among others is left out of the curve.
pub fn threshold_trend(
    s: &FigureSettings,
    key: &str,
    values: &[f64],
    stem: &str,
    out: &OutputDir,
) -> Result<(Vec<TrendPoint>, Vec<String>), CliError> {
    let tolerance = default_tolerance(s.quick);
    let _sequential = capstan_elasticity::contact::sequential_linear_algebra_scope();
    let solved = values
        .par_iter()
        .map(|&v| -> Result<TrendPoint, CliError> {
            let mut scene = s.scene_with(&[format!("{key}={v}")])?;
            if scene.accuracy.tol.is_none() {
                scene.accuracy.tol = Some(tolerance);
            }
            let r = threshold::report(&scene)?;
            let estimate = r
                .estimated_error
                .as_ref()
                .and_then(|e| e.quantities.get("threshold_ratio").copied().flatten())
                .unwrap_or(f64::INFINITY);
            Ok(TrendPoint {
                value: v,
                threshold: r.threshold_ratio,
                estimate,
                grid: r.grid,
            })
        })
        .collect::<Vec<_>>();
    // a point whose threshold fails (a budget spent next to the rigid-sliding limit) is left
    // out of the curve and counted in the comparison, not the end of the figure
    let points: Vec<TrendPoint> = solved
        .iter()
        .filter_map(|r| r.as_ref().ok())
        .cloned()
        .collect();
    if points.is_empty()
        && let Some(Err(e)) = solved.into_iter().next()
    {
        return Err(e);
    }
    let column = |f: fn(&TrendPoint) -> f64| points.iter().map(f).collect::<Vec<_>>();
    let table = Table::new()
        .f64("value", column(|p| p.value))
        .f64("threshold_ratio", column(|p| p.threshold))
        .f64("estimated_error", column(|p| p.estimate))
        .f64("n2", column(|p| p.grid[0] as f64))
        .f64("n3", column(|p| p.grid[1] as f64));
    out.write_csv(&format!("{stem}.csv"), &table)?;
    let x = column(|p| p.value);
    let plot = LinePlot::new(format!(
        "threshold ratio against {key} (accuracy target {tolerance:e} unless the scene sets accuracy.tol)"
    ))
    .x_label(key)
    .y_label("threshold tension ratio")
    .series(Series::line("threshold", x.clone(), column(|p| p.threshold)).with_markers())
    .series(Series::line(
        "+ estimate",
        x.clone(),
        column(|p| p.threshold + p.estimate),
    ))
    .series(Series::line("- estimate", x, column(|p| p.threshold - p.estimate)));
    out.write_plot(stem, &plot)?;
    let files = vec![
        format!("{stem}.csv"),
        format!("{stem}.svg"),
        format!("{stem}.png"),
    ];
    Ok((points, files))
}

/// Whether consecutive thresholds change by more than the error bars of both points, and in
/// which direction: `Some(-1)` decreasing throughout, `Some(1)` increasing, `None` otherwise
/// (a step within the error bars, or a change of direction).
pub fn resolved_direction(points: &[TrendPoint]) -> Option<i8> {
    let mut direction = None;
    for w in points.windows(2) {
        let step = w[1].threshold - w[0].threshold;
        if step.abs() <= w[0].estimate + w[1].estimate {
            return None;
        }
        let d = if step > 0.0 { 1 } else { -1 };
        if direction.is_some_and(|x| x != d) {
            return None;
        }
        direction = Some(d);
    }
    direction
}

/// The trend beside the paper's finding (v) in `index.md`: quantity, ours, the paper's, note.
pub fn comparison(points: &[TrendPoint], key: &str) -> [String; 4] {
    let (first, last) = (points.first(), points.last());
    let ours = match (first, last) {
        (Some(a), Some(b)) => format!(
            "{:.5} +- {:.0e} at {key} = {} to {:.5} +- {:.0e} at {}",
            a.threshold, a.estimate, a.value, b.threshold, b.estimate, b.value
        ),
        _ => "-".into(),
    };
    let note = match resolved_direction(points) {
        Some(-1) => "threshold decreases monotonically, every step beyond both error bars",
        Some(_) => "threshold increases monotonically, every step beyond both error bars",
        None => "not resolved: a step within the error bars or a change of direction",
    };
    [
        format!("threshold ratio against {key} (accuracy target)"),
        ours,
        "Slip decreases slightly as nu increases".into(),
        note.into(),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(value: f64, threshold: f64, estimate: f64) -> TrendPoint {
        TrendPoint {
            value,
            threshold,
            estimate,
            grid: [0, 0],
        }
    }

    #[test]
    fn a_trend_is_resolved_only_with_steps_beyond_the_error_bars() {
        let down = [
            at(0.0, 3.35, 1e-4),
            at(0.1, 3.348, 1e-4),
            at(0.2, 3.345, 1e-4),
        ];
        assert_eq!(resolved_direction(&down), Some(-1));
        let blurred = [at(0.0, 3.35, 1e-3), at(0.1, 3.3495, 1e-3)];
        assert_eq!(resolved_direction(&blurred), None);
        let turning = [
            at(0.0, 3.35, 1e-5),
            at(0.1, 3.34, 1e-5),
            at(0.2, 3.345, 1e-5),
        ];
        assert_eq!(resolved_direction(&turning), None);
    }
}
