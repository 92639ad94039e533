//! The error of a peer's run measured by capstan against its own reference (`paper`): the peer
//! writes the quadrature points of its own elements, their weights and its solution there
//! (`--error-points`, [`super::peers`]); capstan maps every point back to the chart's
//! coordinates, evaluates the reference there and forms the relative L2 error with the peer's
//! weights. This is the measure of capstan's own rows (quadrature over the run's elements,
//! the reference evaluated at the quadrature points), with the peer's elements.
//!
//! # Math
//! For rows `(x, y, w, u_x, u_y)`: find `(x2, x3)` with `Theta(0, x2, x3) = (0, x, y)` (the
//! chart's plane is its components 2 and 3) by Newton's method,
//! `d = -[g_2 g_3]^-1 (Theta - P)` (components 2, 3 of the covariant basis), started from the
//! previous point's solution (a peer writes the points element by element, so neighbours
//! are close) or, if that does not converge to a point of the rectangle (widened by 5%), from
//! the nearest of `SEARCH x SEARCH` samples of
//! the coordinate rectangle; then `U = v^2 g_2 + v^3 g_3` from the reference's `[v^2, v^3]`
//! and
//! ```text
//! e = sqrt( sum w |u - U|^2 / sum w |U|^2 ).
//! ```
//! Points a little outside the rectangle (a curved mesh's geometry error) keep their `x3`
//! slightly outside `[0, h]`; the reference clamps to its rectangle.

use std::path::Path;

use capstan_elasticity::ShellGeometry;

/// What the error of a solution is measured against: a field `x -> [v^2, v^3]`
/// (contravariant components at `(x2, x3)`; exact, or the paper's graded reference).
pub type Reference<'a> = &'a (dyn Fn([f64; 2]) -> [f64; 2] + Sync);

/// Newton steps per point.
const NEWTON_STEPS: usize = 40;

/// Samples per direction of the start search.
const SEARCH: usize = 48;

/// Relative tolerance of the position, times the rectangle's size.
const TOLERANCE: f64 = 1e-13;

/// How far outside the rectangle (a fraction of its size) a point may map.
const MARGIN: f64 = 0.05;

/// The coordinate rectangle the points lie in (up to a curved mesh's geometry error).
#[derive(Debug, Clone, Copy)]
pub struct Rectangle {
    /// `[x2_min, x2_max]`.
    pub theta: [f64; 2],
    /// `h`: `x3` in `[0, h]`.
    pub thickness: f64,
}

/// The plane position `(Theta^2, Theta^3)` and the columns `g_2`, `g_3` (components 2, 3).
fn frame(chart: &dyn ShellGeometry, x: [f64; 2]) -> Result<([f64; 2], [[f64; 2]; 2]), String> {
    let p = chart
        .shell_point([0.0, x[0], x[1]])
        .map_err(|e| format!("peer points: chart at {x:?}: {e}"))?;
    let g = &p.covariant_basis;
    Ok((
        [p.position[1], p.position[2]],
        [[g[1][1], g[1][2]], [g[2][1], g[2][2]]],
    ))
}

/// Newton's method for `Theta(x) = target` from `start`; `None` if it does not converge to a
/// point of the rectangle widened by [`MARGIN`] of its size on every side (the chart is not
/// one-to-one far from it: on a circle `x3 -> -2R - x3` with `x2 -> x2 + pi` is the same point).
fn newton(
    chart: &dyn ShellGeometry,
    target: [f64; 2],
    start: [f64; 2],
    rect: Rectangle,
) -> Option<[f64; 2]> {
    let width = (rect.theta[1] - rect.theta[0]).abs();
    let scale = width + rect.thickness;
    let inside = |x: [f64; 2]| {
        x[0] >= rect.theta[0] - MARGIN * width
            && x[0] <= rect.theta[1] + MARGIN * width
            && x[1] >= -MARGIN * rect.thickness
            && x[1] <= (1.0 + MARGIN) * rect.thickness
    };
    let mut x = start;
    for _ in 0..NEWTON_STEPS {
        let (pos, [g2, g3]) = frame(chart, x).ok()?;
        let r = [pos[0] - target[0], pos[1] - target[1]];
        if r[0].hypot(r[1]) <= TOLERANCE * scale {
            return inside(x).then_some(x);
        }
        // [g2 g3] d = -r
        let det = g2[0] * g3[1] - g3[0] * g2[1];
        if !det.is_finite() || det == 0.0 {
            return None;
        }
        let d = [
            -(g3[1] * r[0] - g3[0] * r[1]) / det,
            -(-g2[1] * r[0] + g2[0] * r[1]) / det,
        ];
        x = [x[0] + d[0], x[1] + d[1]];
        if !(x[0].is_finite() && x[1].is_finite()) {
            return None;
        }
    }
    None
}

/// The sample of the rectangle nearest to `target`.
fn nearest_sample(
    chart: &dyn ShellGeometry,
    target: [f64; 2],
    rect: Rectangle,
) -> Result<[f64; 2], String> {
    let mut best = ([0.0; 2], f64::INFINITY);
    for i in 0..=SEARCH {
        for j in 0..=SEARCH {
            let x = [
                rect.theta[0] + (rect.theta[1] - rect.theta[0]) * i as f64 / SEARCH as f64,
                rect.thickness * j as f64 / SEARCH as f64,
            ];
            let (pos, _) = frame(chart, x)?;
            let d = (pos[0] - target[0]).hypot(pos[1] - target[1]);
            if d < best.1 {
                best = (x, d);
            }
        }
    }
    Ok(best.0)
}

/// The relative L2 error of the rows `(x, y, w, u_x, u_y)` (little-endian f64) in `bytes`
/// against `reference` (`[v^2, v^3]` at `(x2, x3)`) on `chart`.
///
/// # Errors
/// A length that is not a whole number of rows, no rows, a non-finite value or weight, a
/// point Newton's method cannot map back (after the sampled start), or a zero reference norm.
pub fn points_error_of(
    bytes: &[u8],
    chart: &dyn ShellGeometry,
    rect: Rectangle,
    reference: Reference<'_>,
) -> Result<f64, String> {
    const ROW: usize = 5 * 8;
    if bytes.is_empty() || !bytes.len().is_multiple_of(ROW) {
        return Err(format!(
            "peer points: {} bytes is not a positive number of rows (x, y, w, u_x, u_y)",
            bytes.len()
        ));
    }
    let mut last: Option<[f64; 2]> = None;
    let (mut num, mut den) = (0.0, 0.0);
    for row in bytes.chunks_exact(ROW) {
        let f: Vec<f64> = row
            .chunks_exact(8)
            .map(|b| f64::from_le_bytes(b.try_into().expect("8 bytes")))
            .collect();
        if f.iter().any(|v| !v.is_finite()) || f[2] < 0.0 {
            return Err(format!("peer points: invalid row {f:?}"));
        }
        let target = [f[0], f[1]];
        let x = match last.and_then(|s| newton(chart, target, s, rect)) {
            Some(x) => x,
            None => {
                let start = nearest_sample(chart, target, rect)?;
                newton(chart, target, start, rect).ok_or_else(|| {
                    format!("peer points: ({}, {}) not found on the chart", f[0], f[1])
                })?
            }
        };
        last = Some(x);
        let (_, [g2, g3]) = frame(chart, x)?;
        let [v2, v3] = reference(x);
        let u = [v2 * g2[0] + v3 * g3[0], v2 * g2[1] + v3 * g3[1]];
        let e = [f[3] - u[0], f[4] - u[1]];
        num += f[2] * (e[0] * e[0] + e[1] * e[1]);
        den += f[2] * (u[0] * u[0] + u[1] * u[1]);
    }
    if den <= 0.0 {
        return Err("peer points: the reference vanishes at every point".to_owned());
    }
    Ok((num / den).sqrt())
}

/// [`points_error_of`] of the file `path`.
///
/// # Errors
/// The file cannot be read, or any error of [`points_error_of`].
pub fn points_error(
    path: &Path,
    chart: &dyn ShellGeometry,
    rect: Rectangle,
    reference: Reference<'_>,
) -> Result<f64, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("peer points {}: {e}", path.display()))?;
    points_error_of(&bytes, chart, rect, reference)
}

#[cfg(test)]
mod tests {
    use capstan_elasticity::samples::{
        ManufacturedField, MmsBoundaries, PaperEllipse, PrismMms, TrigonometricField,
    };
    use capstan_elasticity::studies::paper_parts;
    use capstan_elasticity::verification::GridLevel;

    use super::*;

    const LEVEL: GridLevel = GridLevel { n2: 5, n3: 3 };

    /// Rows at `n x n` points of the rectangle (a scrambled order, so that warm starts are
    /// sometimes far off), `u = scale U` of the trigonometric field, unit weights times
    /// `1 + x2^2`.
    fn rows(chart: &dyn ShellGeometry, rect: Rectangle, n: usize, scale: f64) -> Vec<u8> {
        let mut bytes = vec![];
        for k in 0..n * n {
            let (i, j) = ((k * 7) % n, (k * 3 + k / n) % n);
            let x = [
                rect.theta[0] + (rect.theta[1] - rect.theta[0]) * (i as f64 + 0.3) / n as f64,
                rect.thickness * (j as f64 + 0.6) / n as f64,
            ];
            let (pos, [g2, g3]) = frame(chart, x).unwrap();
            let [v2, v3] = TrigonometricField.displacement(x).value;
            let u = [v2 * g2[0] + v3 * g3[0], v2 * g2[1] + v3 * g3[1]];
            for v in [
                pos[0],
                pos[1],
                1.0 + x[0] * x[0],
                scale * u[0],
                scale * u[1],
            ] {
                bytes.extend_from_slice(&v.to_le_bytes());
            }
        }
        bytes
    }

    fn field(x: [f64; 2]) -> [f64; 2] {
        TrigonometricField.displacement(x).value
    }

    #[test]
    fn maps_points_back_on_the_circle_and_the_ellipse_and_measures_a_known_error() {
        let paper = paper_parts(&PaperEllipse::default(), LEVEL).unwrap();
        let mms = PrismMms::ellipse(2.0, MmsBoundaries::TractionContact)
            .parts(LEVEL)
            .unwrap()
            .0;
        for parts in [paper, mms] {
            let rect = Rectangle {
                theta: parts.grid.theta(),
                thickness: parts.grid.thickness(),
            };
            // the same field at the points: zero (Newton maps every point back to 1e-13)
            let exact = points_error_of(
                &rows(&parts.chart, rect, 12, 1.0),
                &parts.chart,
                rect,
                &field,
            )
            .unwrap();
            assert!(exact < 1e-12, "{exact}");
            // 1.01 U: 1e-2 relative, whatever the weights
            let off = points_error_of(
                &rows(&parts.chart, rect, 12, 1.01),
                &parts.chart,
                rect,
                &field,
            )
            .unwrap();
            assert!((off / 1e-2 - 1.0).abs() < 1e-10, "{off}");
        }
    }

    #[test]
    fn rejects_bad_rows_and_points_off_the_chart() {
        let parts = paper_parts(&PaperEllipse::default(), LEVEL).unwrap();
        let rect = Rectangle {
            theta: parts.grid.theta(),
            thickness: parts.grid.thickness(),
        };
        let good = rows(&parts.chart, rect, 2, 1.0);
        let chart = &parts.chart;
        assert!(points_error_of(&[], chart, rect, &field).is_err());
        assert!(points_error_of(&good[..good.len() - 8], chart, rect, &field).is_err());
        let mut nan = good.clone();
        nan[16..24].copy_from_slice(&f64::NAN.to_le_bytes());
        assert!(points_error_of(&nan, chart, rect, &field).is_err());
        // the centre of the circle: the chart is singular there (r = 0 is x3 = -2)
        let mut centre = good.clone();
        centre[..16].copy_from_slice(&[0.0f64.to_le_bytes(), 0.0f64.to_le_bytes()].concat());
        assert!(points_error_of(&centre, chart, rect, &field).is_err());
        assert!(points_error(Path::new("/nonexistent/points.f64"), chart, rect, &field).is_err());
    }
}
