//! A categorical strip: the stick/slip state (-1, 0, +1, and 2 lifted off) along the
//! contact surface.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::style::{Plot, extent, font, label_axes};
use crate::output::error::{OutputError, check_all_finite, check_length, check_not_empty};

/// Band colours of the states -1, 0, +1, 2 (blue, grey, vermillion, bluish green).
const STATE_COLOURS: [RGBColor; 4] = [
    RGBColor(0, 114, 178),
    RGBColor(170, 170, 170),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
];

/// The row name of state 2 (a node lifted off the obstacle, unilateral contact); the row is
/// drawn only when some node has that state.
const SEPARATED_NAME: &str = "lifted off";

/// The state of each contact point (`-1`, `0`, `+1`, and `2` where it has lifted off under
/// unilateral contact) drawn as coloured bands on three rows (four with `2`), joined by a
/// step line.
///
/// Each sample `x[i]` owns the interval between the midpoints to its neighbours. The rows
/// are labelled by [`StateStrip::names`] (default `slip -`, `stick`, `slip +`).
///
/// # Example
/// ```
/// use capstan::output::{StateStrip, render_svg};
/// let x: Vec<f64> = (0..10).map(|i| 0.3 * i as f64).collect();
/// let strip = StateStrip::new("Contact state", x, vec![0, 0, 0, 1, 1, 1, 1, 0, -1, -1])
///     .x_label("x2 (rad)");
/// assert!(render_svg(&strip).unwrap().contains("stick"));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct StateStrip {
    title: String,
    x_label: String,
    x: Vec<f64>,
    states: Vec<i32>,
    names: [String; 3],
    size: (u32, u32),
}

impl StateStrip {
    /// A strip of `states[i]` at `x[i]` (increasing), 900 x 280 pixels.
    pub fn new(
        title: impl Into<String>,
        x: impl Into<Vec<f64>>,
        states: impl Into<Vec<i32>>,
    ) -> Self {
        Self {
            title: title.into(),
            x_label: String::new(),
            x: x.into(),
            states: states.into(),
            names: ["slip -".into(), "stick".into(), "slip +".into()],
            size: (900, 280),
        }
    }

    /// Sets the x-axis description.
    pub fn x_label(mut self, label: impl Into<String>) -> Self {
        self.x_label = label.into();
        self
    }

    /// Names of the rows for -1, 0, +1.
    pub fn names(mut self, names: [&str; 3]) -> Self {
        self.names = names.map(str::to_owned);
        self
    }

    /// Sets the size in pixels.
    pub fn size(mut self, width: u32, height: u32) -> Self {
        self.size = (width, height);
        self
    }

    /// The interval `[lo, hi]` owned by sample `i`.
    fn cell(&self, i: usize) -> (f64, f64) {
        let x = &self.x;
        let n = x.len();
        let half = |a: usize, b: usize| 0.5 * (x[a] + x[b]);
        let lo = if i > 0 {
            half(i - 1, i)
        } else if n > 1 {
            x[0] - 0.5 * (x[1] - x[0])
        } else {
            x[0] - 0.5
        };
        let hi = if i + 1 < n {
            half(i, i + 1)
        } else if n > 1 {
            x[n - 1] + 0.5 * (x[n - 1] - x[n - 2])
        } else {
            x[0] + 0.5
        };
        (lo, hi)
    }
}

impl Plot for StateStrip {
    fn dimensions(&self) -> (u32, u32) {
        self.size
    }

    fn validate(&self) -> Result<(), OutputError> {
        check_not_empty("x", self.x.len(), "at least one sample")?;
        check_length("states", self.x.len(), self.states.len())?;
        check_all_finite("x", &self.x)?;
        if let Some(w) = self.x.windows(2).find(|w| w[1] <= w[0]) {
            return Err(OutputError::invalid(
                "x (must increase)",
                w[1],
                "greater than the previous sample",
            ));
        }
        if let Some(&s) = self.states.iter().find(|s| !(-1..=2).contains(*s)) {
            return Err(OutputError::invalid(
                "states",
                f64::from(s),
                "{-1, 0, 1, 2}",
            ));
        }
        Ok(())
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let n = self.x.len();
        let lifted = self.states.contains(&2);
        let (x0, x1) = extent((0..n).flat_map(|i| {
            let (lo, hi) = self.cell(i);
            [lo, hi]
        }));
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", font::TITLE))
            .margin(18)
            .x_label_area_size(56)
            .y_label_area_size(84)
            .build_cartesian_2d(x0..x1, -1.6..if lifted { 2.6 } else { 1.6 })?;
        let mut mesh = chart.configure_mesh();
        label_axes(&mut mesh, Some(&self.x_label), None);
        mesh.disable_y_mesh()
            .y_labels(0) // rows are labelled below, exactly at -1, 0, +1
            .light_line_style(RGBColor(235, 235, 235))
            .bold_line_style(RGBColor(215, 215, 215))
            .draw()?;
        chart.draw_series((0..n).map(|i| {
            let (lo, hi) = self.cell(i);
            let s = self.states[i];
            let c = STATE_COLOURS[(s + 1) as usize];
            Rectangle::new(
                [(lo, f64::from(s) - 0.35), (hi, f64::from(s) + 0.35)],
                c.mix(0.85).filled(),
            )
        }))?;
        // step line through the band centres
        let mut path = Vec::with_capacity(2 * n);
        for i in 0..n {
            let (lo, hi) = self.cell(i);
            let s = f64::from(self.states[i]);
            path.push((lo, s));
            path.push((hi, s));
        }
        chart.draw_series(std::iter::once(PathElement::new(
            path,
            BLACK.stroke_width(1),
        )))?;
        let style = TextStyle::from(("sans-serif", font::TICK).into_font())
            .pos(Pos::new(HPos::Right, VPos::Center));
        let names = self.names.iter().map(String::as_str);
        let rows = if lifted { 4 } else { 3 };
        for (k, name) in names.chain([SEPARATED_NAME]).take(rows).enumerate() {
            let (px, py) = chart.backend_coord(&(x0, k as f64 - 1.0));
            root.draw(&Text::new(name, (px - 8, py), style.clone()))?;
        }
        Ok(())
    }
}
