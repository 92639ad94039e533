//! What every plot shares: the [`Plot`] trait, the palette, font sizes, tick labels and axis
//! extents.

use plotters::chart::MeshStyle;
use plotters::coord::Shift;
use plotters::prelude::*;

use crate::output::error::OutputError;

/// A figure that can be drawn on any plotters backend.
pub trait Plot {
    /// Width and height in pixels (the PNG's size; the SVG's view box).
    fn dimensions(&self) -> (u32, u32);

    /// Checks the data can be drawn (finite, consistent lengths, positive on log axes).
    ///
    /// # Errors
    /// [`OutputError::NonFinite`], [`OutputError::LengthMismatch`] or
    /// [`OutputError::InvalidParameter`] naming what is wrong.
    fn validate(&self) -> Result<(), OutputError>;

    /// Draws the figure on `root` (already sized to [`Plot::dimensions`]); called after
    /// [`Plot::validate`] succeeded and the font is registered.
    ///
    /// # Errors
    /// plotters' drawing errors.
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>>;
}

/// Colour-blind-safe series colours (Okabe–Ito), cycled.
pub(crate) const PALETTE: [RGBColor; 7] = [
    RGBColor(0, 114, 178),   // blue
    RGBColor(213, 94, 0),    // vermillion
    RGBColor(0, 158, 115),   // bluish green
    RGBColor(204, 121, 167), // reddish purple
    RGBColor(230, 159, 0),   // orange
    RGBColor(86, 180, 233),  // sky blue
    RGBColor(0, 0, 0),       // black
];

/// Font sizes in pixels, shared by all plot kinds.
pub(crate) mod font {
    /// Figure title.
    pub const TITLE: u32 = 26;
    /// Axis descriptions.
    pub const AXIS: u32 = 20;
    /// Tick labels and legend entries.
    pub const TICK: u32 = 16;
}

/// The axes of every plot: the descriptions given (`x_label`, `y_label`) in the axis font, tick
/// labels in the tick font written by [`tick_label`].
pub(crate) fn label_axes<X, Y, DB>(
    mesh: &mut MeshStyle<'_, '_, X, Y, DB>,
    x_label: Option<&str>,
    y_label: Option<&str>,
) where
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
    DB: DrawingBackend,
{
    if let Some(x) = x_label {
        mesh.x_desc(x);
    }
    if let Some(y) = y_label {
        mesh.y_desc(y);
    }
    mesh.axis_desc_style(("sans-serif", font::AXIS))
        .label_style(("sans-serif", font::TICK))
        .x_label_formatter(&tick_label)
        .y_label_formatter(&tick_label);
}

/// Tick label: plain for moderate magnitudes, otherwise `1.5e-7` (plotters' default prints
/// long decimals).
pub(crate) fn tick_label(v: &f64) -> String {
    let a = v.abs();
    if a == 0.0 {
        "0".to_owned()
    } else if (1e-2..1e5).contains(&a) {
        let s = format!("{v:.6}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_owned()
    } else {
        let s = format!("{v:.2e}");
        // 1.00e-7 -> 1e-7, 2.50e3 -> 2.5e3
        match s.split_once('e') {
            Some((m, e)) => {
                let m = m.trim_end_matches('0').trim_end_matches('.');
                format!("{m}e{e}")
            }
            None => s,
        }
    }
}

/// `[lo, hi]` of finite values, widened when empty or degenerate.
pub(crate) fn extent(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    if hi > lo {
        (lo, hi)
    } else {
        let pad = if lo == 0.0 { 1.0 } else { 0.05 * lo.abs() };
        (lo - pad, hi + pad)
    }
}
