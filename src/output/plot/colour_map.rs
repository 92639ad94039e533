//! A scalar field on the curved body: filled quads in Cartesian coordinates, with a colour bar.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::style::{Plot, extent, font, label_axes};
use crate::output::error::{OutputError, check_all_finite, check_length, check_not_empty};
use crate::output::vtu::QuadGrid;

/// Viridis at `t = 0, 1/8, ..., 1` (perceptually uniform, colour-blind safe, prints in grey).
const VIRIDIS: [(u8, u8, u8); 9] = [
    (68, 1, 84),
    (71, 44, 122),
    (59, 81, 139),
    (44, 113, 142),
    (33, 144, 141),
    (39, 173, 129),
    (92, 200, 99),
    (170, 220, 50),
    (253, 231, 37),
];

/// Viridis at `t` in `[0, 1]` (clamped), linearly interpolated between the anchors.
pub(crate) fn viridis(t: f64) -> RGBColor {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let s = t * 8.0;
    let i = (s.floor() as usize).min(7);
    let f = s - i as f64;
    let (a, b) = (VIRIDIS[i], VIRIDIS[i + 1]);
    let mix = |p: u8, q: u8| (f64::from(p) + f * (f64::from(q) - f64::from(p))).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// Width in pixels of the colour-bar panel on the right.
const BAR_PANEL: u32 = 150;

/// A scalar field on quads in the plane, coloured with viridis, drawn with equal axis scales
/// (the body keeps its shape) and a colour bar.
///
/// Usually built from a [`QuadGrid`] of the body with [`ColourMap::nodal`] or
/// [`ColourMap::cellwise`], projecting the points onto two Cartesian axes (for a prism
/// `sigma = (x1, u, v)`, axes `[1, 2]`: the cross-section).
///
/// # Example
/// ```
/// use capstan::geometry::{EllipticalPrism, ShellChart};
/// use capstan::output::{ColourMap, QuadGrid, render_svg};
/// let chart = ShellChart::new(EllipticalPrism::new(2.0, 1.0).unwrap());
/// let x2: Vec<f64> = (0..=20).map(|i| 0.15 * i as f64).collect();
/// let grid = QuadGrid::from_chart(&chart, 0.0, &x2, &[0.0, 0.1, 0.2], false).unwrap();
/// let pressure: Vec<f64> = grid.points().iter().map(|p| p[2]).collect();
/// let map = ColourMap::nodal("Pressure", &grid, [1, 2], &pressure).unwrap().label("p (Pa)");
/// assert!(render_svg(&map).unwrap().contains("p (Pa)"));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ColourMap {
    title: String,
    label: String,
    x_label: String,
    y_label: String,
    points: Vec<[f64; 2]>,
    cells: Vec<[usize; 4]>,
    values: Vec<f64>,
    outline: Vec<Vec<usize>>,
    range: Option<(f64, f64)>,
    size: (u32, u32),
}

impl ColourMap {
    /// Quads `cells` (node numbers into `points`) coloured by `cell_values`, one per cell;
    /// 900 x 640 pixels.
    pub fn new(
        title: impl Into<String>,
        points: Vec<[f64; 2]>,
        cells: Vec<[usize; 4]>,
        cell_values: Vec<f64>,
    ) -> Self {
        Self {
            title: title.into(),
            label: String::new(),
            x_label: String::new(),
            y_label: String::new(),
            points,
            cells,
            values: cell_values,
            outline: Vec::new(),
            range: None,
            size: (900, 640),
        }
    }

    /// A field given at the nodes of `grid` (each quad gets the mean of its four nodes),
    /// projected onto Cartesian axes `axes` (0 = x, 1 = y, 2 = z), with the body's outline.
    ///
    /// # Errors
    /// [`OutputError::LengthMismatch`] unless there is one value per node;
    /// [`OutputError::NonFinite`] naming the node; [`OutputError::InvalidParameter`] for an
    /// axis past 2.
    pub fn nodal(
        title: impl Into<String>,
        grid: &QuadGrid,
        axes: [usize; 2],
        node_values: &[f64],
    ) -> Result<Self, OutputError> {
        check_length("node values", grid.node_count(), node_values.len())?;
        check_all_finite("node values", node_values)?;
        let cells = grid.cells();
        let values = cells
            .iter()
            .map(|c| 0.25 * c.iter().map(|&k| node_values[k]).sum::<f64>())
            .collect();
        Self::from_grid(title, grid, axes, cells, values)
    }

    /// A field given per cell of `grid` (in [`QuadGrid::cells`] order); otherwise as
    /// [`ColourMap::nodal`].
    ///
    /// # Errors
    /// As [`ColourMap::nodal`], with one value per cell.
    pub fn cellwise(
        title: impl Into<String>,
        grid: &QuadGrid,
        axes: [usize; 2],
        cell_values: &[f64],
    ) -> Result<Self, OutputError> {
        check_length("cell values", grid.cell_count(), cell_values.len())?;
        Self::from_grid(title, grid, axes, grid.cells(), cell_values.to_vec())
    }

    fn from_grid(
        title: impl Into<String>,
        grid: &QuadGrid,
        axes: [usize; 2],
        cells: Vec<[usize; 4]>,
        values: Vec<f64>,
    ) -> Result<Self, OutputError> {
        if let Some(&a) = axes.iter().find(|&&a| a > 2) {
            return Err(OutputError::invalid("axes", a as f64, "{0, 1, 2}"));
        }
        let points = grid
            .points()
            .iter()
            .map(|p| [p[axes[0]], p[axes[1]]])
            .collect();
        let (n2, n3) = (grid.n2(), grid.n3());
        let node = |i2: usize, i3: usize| i2 * n3 + i3;
        let mut inner: Vec<usize> = (0..n2).map(|i2| node(i2, 0)).collect();
        let mut outer: Vec<usize> = (0..n2).map(|i2| node(i2, n3 - 1)).collect();
        let outline = if grid.is_periodic() {
            inner.push(node(0, 0));
            outer.push(node(0, n3 - 1));
            vec![inner, outer]
        } else {
            // one closed loop: inner face, far end, outer face backwards, near end
            let mut lp = inner;
            lp.extend((0..n3).map(|i3| node(n2 - 1, i3)));
            lp.extend(outer.iter().rev());
            lp.extend((0..n3).rev().map(|i3| node(0, i3)));
            vec![lp]
        };
        let mut map = Self::new(title, points, cells, values);
        map.outline = outline;
        let names = ["x", "y", "z"];
        map.x_label = names[axes[0]].to_owned();
        map.y_label = names[axes[1]].to_owned();
        Ok(map)
    }

    /// Sets the colour bar's description (the field and its unit).
    pub fn label(mut self, label: impl Into<String>) -> Self {
        self.label = label.into();
        self
    }

    /// Sets the axis descriptions (default: the Cartesian axis names).
    pub fn axis_labels(mut self, x: impl Into<String>, y: impl Into<String>) -> Self {
        self.x_label = x.into();
        self.y_label = y.into();
        self
    }

    /// Fixes the colour range (to compare frames of a sweep); values outside are clamped.
    pub fn range(mut self, lo: f64, hi: f64) -> Self {
        self.range = Some((lo, hi));
        self
    }

    /// Sets the size in pixels.
    pub fn size(mut self, width: u32, height: u32) -> Self {
        self.size = (width, height);
        self
    }

    fn colour_range(&self) -> (f64, f64) {
        self.range
            .unwrap_or_else(|| extent(self.values.iter().copied()))
    }
}

impl Plot for ColourMap {
    fn dimensions(&self) -> (u32, u32) {
        self.size
    }

    fn validate(&self) -> Result<(), OutputError> {
        check_not_empty("cells", self.cells.len(), "at least one cell")?;
        check_length("cell values", self.cells.len(), self.values.len())?;
        check_all_finite("points", self.points.as_flattened())?;
        check_all_finite("cell values", &self.values)?;
        let n = self.points.len();
        if let Some(&k) = self.cells.iter().flatten().find(|&&k| k >= n) {
            return Err(OutputError::invalid(
                "cells (node number)",
                k as f64,
                "below the number of points",
            ));
        }
        if let Some((lo, hi)) = self.range
            && !(lo.is_finite() && hi.is_finite() && hi > lo)
        {
            return Err(OutputError::invalid(
                "range",
                hi,
                "finite, above the lower end",
            ));
        }
        Ok(())
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let (w, h) = self.size;
        let (main, bar) = root.split_horizontally(w.saturating_sub(BAR_PANEL));
        let (lo, hi) = self.colour_range();

        // Equal scales: widen the narrower extent to the aspect of the plotting area.
        let (margin, x_area, y_area, caption) = (18u32, 56u32, 84u32, 44u32);
        let area_w = f64::from(w.saturating_sub(BAR_PANEL + 2 * margin + y_area).max(1));
        let area_h = f64::from(h.saturating_sub(2 * margin + x_area + caption).max(1));
        let (mut x0, mut x1) = extent(self.points.iter().map(|p| p[0]));
        let (mut y0, mut y1) = extent(self.points.iter().map(|p| p[1]));
        let pad = 0.04 * (x1 - x0).max(y1 - y0);
        (x0, x1, y0, y1) = (x0 - pad, x1 + pad, y0 - pad, y1 + pad);
        let scale = ((x1 - x0) / area_w).max((y1 - y0) / area_h);
        let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
        let (hx, hy) = (0.5 * scale * area_w, 0.5 * scale * area_h);

        let mut chart = ChartBuilder::on(&main)
            .caption(&self.title, ("sans-serif", font::TITLE))
            .margin(margin)
            .x_label_area_size(x_area)
            .y_label_area_size(y_area)
            .build_cartesian_2d(cx - hx..cx + hx, cy - hy..cy + hy)?;
        let mut mesh = chart.configure_mesh();
        label_axes(&mut mesh, Some(&self.x_label), Some(&self.y_label));
        mesh.light_line_style(RGBColor(240, 240, 240))
            .bold_line_style(RGBColor(215, 215, 215))
            .draw()?;
        let t = |v: f64| (v - lo) / (hi - lo);
        chart.draw_series(self.cells.iter().zip(&self.values).map(|(c, &v)| {
            let corners: Vec<(f64, f64)> = c
                .iter()
                .map(|&k| (self.points[k][0], self.points[k][1]))
                .collect();
            Polygon::new(corners, viridis(t(v)).filled())
        }))?;
        chart.draw_series(self.outline.iter().map(|lp| {
            PathElement::new(
                lp.iter()
                    .map(|&k| (self.points[k][0], self.points[k][1]))
                    .collect::<Vec<_>>(),
                BLACK.stroke_width(1),
            )
        }))?;

        // Colour bar: a column of thin bands with its own value axis on the right.
        let mut bar_chart = ChartBuilder::on(&bar)
            .margin_top(margin + caption)
            .margin_bottom(margin + x_area)
            .margin_left(8)
            .margin_right(8)
            .right_y_label_area_size(86)
            .build_cartesian_2d(0.0..1.0, lo..hi)?;
        let mut mesh = bar_chart.configure_mesh();
        label_axes(&mut mesh, None, Some(&self.label));
        mesh.disable_mesh().disable_x_axis().draw()?;
        let bands = 128;
        bar_chart.draw_series((0..bands).map(|i| {
            let a = lo + (hi - lo) * i as f64 / bands as f64;
            let b = lo + (hi - lo) * (i + 1) as f64 / bands as f64;
            Rectangle::new(
                [(0.0, a), (1.0, b)],
                viridis((i as f64 + 0.5) / bands as f64).filled(),
            )
        }))?;
        bar_chart.draw_series(std::iter::once(Rectangle::new(
            [(0.0, lo), (1.0, hi)],
            BLACK.stroke_width(1),
        )))?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn viridis_ends_and_clamps() {
        assert_eq!(viridis(0.0), RGBColor(68, 1, 84));
        assert_eq!(viridis(1.0), RGBColor(253, 231, 37));
        assert_eq!(viridis(2.0), viridis(1.0));
        assert_eq!(viridis(0.5), RGBColor(33, 144, 141));
    }
}
