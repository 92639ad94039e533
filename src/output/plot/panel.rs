//! Several line plots as one figure, on a grid of panels (the paper's Fig. fullset: four Slip
//! curves as one 2 x 2 figure).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::line::LinePlot;
use super::style::Plot;
use crate::output::error::OutputError;

/// Line plots drawn side by side, row by row, `columns` per row.
///
/// # Example
/// ```
/// use capstan::output::{LinePlot, Panel, Series, render_svg};
/// let plot = |t: &str| LinePlot::new(t).series(Series::line("s", [0.0, 1.0], [0.0, 1.0]));
/// let panel = Panel::new(vec![plot("a"), plot("b"), plot("c"), plot("d")], 2);
/// let svg = render_svg(&panel).unwrap();
/// assert!(svg.starts_with("<svg") && svg.matches("<text").count() >= 4); // four titles at least
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Panel {
    plots: Vec<LinePlot>,
    columns: usize,
    size: (u32, u32),
}

impl Panel {
    /// `plots` in rows of `columns` (at least 1), 1400 x 1000 pixels.
    pub fn new(plots: Vec<LinePlot>, columns: usize) -> Self {
        Self {
            plots,
            columns: columns.max(1),
            size: (1400, 1000),
        }
    }

    /// Sets the size in pixels.
    pub fn size(mut self, width: u32, height: u32) -> Self {
        self.size = (width, height);
        self
    }

    fn rows(&self) -> usize {
        self.plots.len().div_ceil(self.columns).max(1)
    }
}

impl Plot for Panel {
    fn dimensions(&self) -> (u32, u32) {
        self.size
    }

    fn validate(&self) -> Result<(), OutputError> {
        if self.plots.is_empty() {
            return Err(OutputError::invalid("plots", 0.0, "at least one plot"));
        }
        self.plots.iter().try_for_each(Plot::validate)
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        let areas = root.split_evenly((self.rows(), self.columns));
        for (plot, area) in self.plots.iter().zip(&areas) {
            plot.draw(area)?;
        }
        Ok(())
    }
}
