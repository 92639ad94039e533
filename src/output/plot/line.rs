//! Line plots: several series with lines and/or markers, on linear or logarithmic axes.

use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::element::{Drawable, PointCollection};
use plotters::prelude::*;
use plotters_backend::{BackendCoord, DrawingErrorKind};

use super::style::{PALETTE, Plot, extent, font, label_axes};
use crate::output::error::{OutputError, check_all_finite, check_length, check_not_empty};

/// An axis scale.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum Scale {
    /// Linear.
    #[default]
    Linear,
    /// Base-10 logarithmic (all values must be positive).
    Log,
}

/// One curve: `(x[i], y[i])`, drawn as a line, markers or both.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// The legend entry (empty: not in the legend).
    pub label: String,
    /// Abscissae.
    pub x: Vec<f64>,
    /// Ordinates, as many as `x`.
    pub y: Vec<f64>,
    /// Join the points with a line.
    pub line: bool,
    /// Mark each point.
    pub markers: bool,
}

impl Series {
    /// A line through the points (a computed profile).
    pub fn line(label: impl Into<String>, x: impl Into<Vec<f64>>, y: impl Into<Vec<f64>>) -> Self {
        Self {
            label: label.into(),
            x: x.into(),
            y: y.into(),
            line: true,
            markers: false,
        }
    }

    /// Markers only (measurements, the paper's printed values).
    pub fn markers(
        label: impl Into<String>,
        x: impl Into<Vec<f64>>,
        y: impl Into<Vec<f64>>,
    ) -> Self {
        Self {
            line: false,
            markers: true,
            ..Self::line(label, x, y)
        }
    }

    /// Also marks the points of a line.
    pub fn with_markers(mut self) -> Self {
        self.markers = true;
        self
    }
}

/// Several series against a common pair of axes, with a legend.
///
/// Series take colours from a colour-blind-safe palette and, when marked, distinct marker
/// shapes (circle, triangle, square, cross), so they stay apart in greyscale.
///
/// # Example
/// ```
/// use capstan::output::{LinePlot, Series, render_svg};
/// let theta: Vec<f64> = (0..=20).map(|i| 0.1 * i as f64).collect();
/// let plot = LinePlot::new("Tension profile")
///     .x_label("theta (rad)")
///     .y_label("T / T0")
///     .series(Series::line("mu = 0.3", theta.clone(), theta.iter().map(|t| (0.3 * t).exp()).collect::<Vec<_>>()))
///     .series(Series::markers("paper", [0.0, 1.0, 2.0], [1.0, 1.35, 1.82]));
/// let svg = render_svg(&plot).unwrap();
/// assert!(svg.contains("Tension profile") && svg.contains("mu = 0.3"));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct LinePlot {
    title: String,
    x_label: String,
    y_label: String,
    series: Vec<Series>,
    x_scale: Scale,
    y_scale: Scale,
    legend: Legend,
    size: (u32, u32),
    y_min_span: f64,
}

/// Where the legend sits.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum Legend {
    /// The corner with the fewest data points nearby.
    #[default]
    Auto,
    /// Top right corner of the plotting area.
    UpperRight,
    /// Top left corner.
    UpperLeft,
    /// Bottom right corner.
    LowerRight,
    /// Bottom left corner.
    LowerLeft,
    /// No legend.
    Hidden,
}

impl LinePlot {
    /// An empty plot titled `title`, 900 x 600 pixels, linear axes, legend placed automatically.
    pub fn new(title: impl Into<String>) -> Self {
        Self {
            title: title.into(),
            x_label: String::new(),
            y_label: String::new(),
            series: Vec::new(),
            x_scale: Scale::Linear,
            y_scale: Scale::Linear,
            legend: Legend::Auto,
            size: (900, 600),
            y_min_span: 0.0,
        }
    }

    /// The same plot with `prefix` before its title (e.g. the tag `(a) ` of a panel).
    pub fn prefix_title(mut self, prefix: &str) -> Self {
        self.title = format!("{prefix}{}", self.title);
        self
    }

    /// Sets the x-axis description.
    pub fn x_label(mut self, label: impl Into<String>) -> Self {
        self.x_label = label.into();
        self
    }

    /// Sets the y-axis description.
    pub fn y_label(mut self, label: impl Into<String>) -> Self {
        self.y_label = label.into();
        self
    }

    /// Adds a series.
    pub fn series(mut self, series: Series) -> Self {
        self.series.push(series);
        self
    }

    /// Sets the x-axis scale.
    pub fn x_scale(mut self, scale: Scale) -> Self {
        self.x_scale = scale;
        self
    }

    /// Sets the y-axis scale.
    pub fn y_scale(mut self, scale: Scale) -> Self {
        self.y_scale = scale;
        self
    }

    /// Both axes logarithmic (work-precision: error against time).
    pub fn log_log(self) -> Self {
        self.x_scale(Scale::Log).y_scale(Scale::Log)
    }

    /// Moves (or hides) the legend.
    pub fn legend(mut self, legend: Legend) -> Self {
        self.legend = legend;
        self
    }

    /// A linear y-axis spans at least `span` (widened about the data's centre), so that a
    /// change by one quantum of the data (e.g. one contact node of a mean state) is not drawn
    /// across the whole height.
    pub fn y_min_span(mut self, span: f64) -> Self {
        self.y_min_span = span;
        self
    }

    /// Sets the size in pixels.
    pub fn size(mut self, width: u32, height: u32) -> Self {
        self.size = (width, height);
        self
    }

    /// Data range of one axis, padded: 4 % of the span (linear) or of the decades (log).
    fn range(&self, values: impl Iterator<Item = f64>, scale: Scale) -> (f64, f64) {
        match scale {
            Scale::Linear => {
                let (lo, hi) = extent(values);
                let pad = 0.04 * (hi - lo);
                (lo - pad, hi + pad)
            }
            Scale::Log => {
                let (lo, hi) = extent(values.map(f64::log10));
                let pad = 0.04 * (hi - lo).max(0.5);
                (10f64.powf(lo - pad), 10f64.powf(hi + pad))
            }
        }
    }

    /// The legend corner whose box (40 % of the width, 12 % of the height per entry) holds
    /// the fewest data points and line samples; ties go to upper right, upper left, lower right.
    fn emptiest_corner(&self, x: Range, y: Range) -> Legend {
        let entries = self.series.iter().filter(|s| !s.label.is_empty()).count();
        let height = (0.12 * entries as f64 + 0.04).min(0.9);
        let mut counts = [0usize; 4];
        for s in &self.series {
            let t: Vec<(f64, f64)> =
                s.x.iter()
                    .zip(&s.y)
                    .map(|(&a, &b)| (x.unit(a), y.unit(b)))
                    .collect();
            // lines: also sample between the points
            let mut samples = t.clone();
            if s.line {
                for w in t.windows(2) {
                    for k in 1..8 {
                        let f = k as f64 / 8.0;
                        samples.push((
                            w[0].0 + f * (w[1].0 - w[0].0),
                            w[0].1 + f * (w[1].1 - w[0].1),
                        ));
                    }
                }
            }
            for (u, v) in samples {
                let right = u > 0.6;
                let left = u < 0.4;
                let top = v > 1.0 - height;
                let bottom = v < height;
                counts[0] += usize::from(right && top);
                counts[1] += usize::from(left && top);
                counts[2] += usize::from(right && bottom);
                counts[3] += usize::from(left && bottom);
            }
        }
        let corners = [
            Legend::UpperRight,
            Legend::UpperLeft,
            Legend::LowerRight,
            Legend::LowerLeft,
        ];
        let best = (0..4).min_by_key(|&i| counts[i]).unwrap_or(0);
        corners[best]
    }

    fn draw_in<DB, X, Y>(
        &self,
        root: &DrawingArea<DB, Shift>,
        x: X,
        y: Y,
        (x_range, y_range): (Range, Range),
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>>
    where
        DB: DrawingBackend,
        X: AsRangedCoord<Value = f64>,
        Y: AsRangedCoord<Value = f64>,
        X::CoordDescType: ValueFormatter<f64>,
        Y::CoordDescType: ValueFormatter<f64>,
    {
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", font::TITLE))
            .margin(18)
            .x_label_area_size(56)
            .y_label_area_size(84)
            .build_cartesian_2d(x, y)?;
        let mut mesh = chart.configure_mesh();
        label_axes(&mut mesh, Some(&self.x_label), Some(&self.y_label));
        mesh.light_line_style(RGBColor(235, 235, 235))
            .bold_line_style(RGBColor(200, 200, 200))
            .draw()?;
        let mut marked = 0;
        for (i, s) in self.series.iter().enumerate() {
            let colour = PALETTE[i % PALETTE.len()];
            let shape = if s.markers {
                marked += 1;
                Some((marked - 1) % 4) // circle, triangle, square, cross
            } else {
                None
            };
            let points: Vec<(f64, f64)> = s.x.iter().copied().zip(s.y.iter().copied()).collect();
            let anno = if s.line {
                chart.draw_series(LineSeries::new(
                    points.iter().copied(),
                    colour.stroke_width(2),
                ))?
            } else {
                chart.draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())?
            };
            if !s.label.is_empty() {
                let line = s.line;
                anno.label(s.label.clone()).legend(move |at| Marker {
                    at,
                    shape,
                    colour,
                    legend_line: line,
                });
            }
            if shape.is_some() {
                chart.draw_series(points.iter().map(|&at| Marker {
                    at,
                    shape,
                    colour,
                    legend_line: false,
                }))?;
            }
        }
        let legend = match self.legend {
            Legend::Auto => self.emptiest_corner(x_range, y_range),
            other => other,
        };
        let position = match legend {
            Legend::Auto | Legend::UpperRight => SeriesLabelPosition::UpperRight,
            Legend::UpperLeft => SeriesLabelPosition::UpperLeft,
            Legend::LowerRight => SeriesLabelPosition::LowerRight,
            Legend::LowerLeft => SeriesLabelPosition::LowerLeft,
            Legend::Hidden => return Ok(()),
        };
        if self.series.iter().any(|s| !s.label.is_empty()) {
            chart
                .configure_series_labels()
                .position(position)
                .margin(12)
                .legend_area_size(34)
                .label_font(("sans-serif", font::TICK))
                .background_style(WHITE)
                .border_style(RGBColor(160, 160, 160))
                .draw()?;
        }
        Ok(())
    }
}

/// An axis range and scale, to place data in the unit square.
#[derive(Debug, Clone, Copy)]
struct Range {
    lo: f64,
    hi: f64,
    scale: Scale,
}

impl Range {
    /// Position of `v` along the axis, 0 at `lo`, 1 at `hi`.
    fn unit(&self, v: f64) -> f64 {
        match self.scale {
            Scale::Linear => (v - self.lo) / (self.hi - self.lo),
            Scale::Log => (v / self.lo).log10() / (self.hi / self.lo).log10(),
        }
    }
}

/// A marker (circle, triangle, square or cross for `shape` 0, 1, 2, 3) at one point; in the
/// legend optionally on a short line.
///
/// One concrete element type for every shape, so series and legend entries need no boxing.
struct Marker<C> {
    at: C,
    shape: Option<usize>,
    colour: RGBColor,
    legend_line: bool,
}

impl<'a, C: 'a> PointCollection<'a, C> for &'a Marker<C> {
    type Point = &'a C;
    type IntoIter = std::iter::Once<&'a C>;
    fn point_iter(self) -> Self::IntoIter {
        std::iter::once(&self.at)
    }
}

impl<C, DB: DrawingBackend> Drawable<DB> for Marker<C> {
    fn draw<I: Iterator<Item = BackendCoord>>(
        &self,
        mut points: I,
        backend: &mut DB,
        _: (u32, u32),
    ) -> Result<(), DrawingErrorKind<DB::ErrorType>> {
        let Some((x, y)) = points.next() else {
            return Ok(());
        };
        let fill = self.colour.filled();
        let stroke = self.colour.stroke_width(2);
        if self.legend_line {
            backend.draw_line((x - 14, y), (x + 14, y), &stroke)?;
        }
        match self.shape {
            None => {}
            Some(0) => backend.draw_circle((x, y), 5, &fill, true)?,
            Some(1) => backend.fill_polygon([(x, y - 7), (x - 6, y + 4), (x + 6, y + 4)], &fill)?,
            Some(2) => backend.draw_rect((x - 5, y - 5), (x + 5, y + 5), &fill, true)?,
            Some(_) => {
                backend.draw_line((x - 5, y - 5), (x + 5, y + 5), &stroke)?;
                backend.draw_line((x - 5, y + 5), (x + 5, y - 5), &stroke)?;
            }
        }
        Ok(())
    }
}

impl Plot for LinePlot {
    fn dimensions(&self) -> (u32, u32) {
        self.size
    }

    fn validate(&self) -> Result<(), OutputError> {
        check_not_empty("series", self.series.len(), "at least one series")?;
        for s in &self.series {
            check_length(&format!("{}.y", s.label), s.x.len(), s.y.len())?;
            for (axis, values, scale) in [("x", &s.x, self.x_scale), ("y", &s.y, self.y_scale)] {
                let column = format!("{}.{axis}", s.label);
                check_all_finite(&column, values)?;
                if scale == Scale::Log
                    && let Some(&v) = values.iter().find(|v| **v <= 0.0)
                {
                    return Err(OutputError::invalid(
                        if axis == "x" {
                            "x (log axis)"
                        } else {
                            "y (log axis)"
                        },
                        v,
                        "(0, inf)",
                    ));
                }
            }
        }
        Ok(())
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let (x0, x1) = self.range(
            self.series.iter().flat_map(|s| s.x.iter().copied()),
            self.x_scale,
        );
        let (mut y0, mut y1) = self.range(
            self.series.iter().flat_map(|s| s.y.iter().copied()),
            self.y_scale,
        );
        if self.y_scale == Scale::Linear && y1 - y0 < self.y_min_span {
            let centre = 0.5 * (y0 + y1);
            (y0, y1) = (
                centre - 0.5 * self.y_min_span,
                centre + 0.5 * self.y_min_span,
            );
        }
        let ranges = (
            Range {
                lo: x0,
                hi: x1,
                scale: self.x_scale,
            },
            Range {
                lo: y0,
                hi: y1,
                scale: self.y_scale,
            },
        );
        match (self.x_scale, self.y_scale) {
            (Scale::Linear, Scale::Linear) => self.draw_in(root, x0..x1, y0..y1, ranges),
            (Scale::Log, Scale::Linear) => self.draw_in(root, (x0..x1).log_scale(), y0..y1, ranges),
            (Scale::Linear, Scale::Log) => self.draw_in(root, x0..x1, (y0..y1).log_scale(), ranges),
            (Scale::Log, Scale::Log) => {
                self.draw_in(root, (x0..x1).log_scale(), (y0..y1).log_scale(), ranges)
            }
        }
    }
}
