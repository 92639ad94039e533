//! Plots as SVG and PNG, in pure Rust (plotters with an embedded font, no system libraries).
//!
//! Each plot kind implements [`Plot`]; [`write_plot`] renders it into memory as SVG and as
//! PNG and then writes `NAME.svg` and `NAME.png`, each atomically. Text is laid out with
//! DejaVu Sans (Bitstream Vera licence, embedded through the `dejavu` crate and registered
//! with plotters' `ab_glyph` font backend on first use), so no fontconfig or freetype is needed;
//! SVG files name the `sans-serif` family and leave the glyphs to the viewer.
//!
//! Plot kinds: [`LinePlot`] (several series, lines and/or markers, linear or log axes: tension
//! profiles, ratio against `b/a`, work-precision), [`StateStrip`] (stick/slip state along the
//! contact surface), [`ColourMap`] (a scalar field on the curved body, with a colour bar) and
//! [`Panel`] (line plots side by side as one figure).

mod colour_map;
mod line;
mod panel;
mod strip;

use std::path::{Path, PathBuf};
use std::sync::Once;

use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};

mod style;

pub use colour_map::ColourMap;
pub use line::{Legend, LinePlot, Scale, Series};
pub use panel::Panel;
pub use strip::StateStrip;

use super::atomic::write_atomic;
use super::error::OutputError;
pub use style::Plot;
#[cfg(test)]
use style::tick_label;

/// Registers the embedded DejaVu Sans as plotters' `sans-serif` family (once per process).
pub fn register_fonts() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let fonts = [
            (FontStyle::Normal, dejavu::sans::regular()),
            (FontStyle::Bold, dejavu::sans::bold()),
            (FontStyle::Oblique, dejavu::sans::oblique()),
            (FontStyle::Italic, dejavu::sans::oblique()),
        ];
        for (style, bytes) in fonts {
            if register_font("sans-serif", style, bytes).is_err() {
                unreachable!("the embedded DejaVu Sans is a valid TrueType font");
            }
        }
    });
}

fn plot_error(name: &str, e: impl std::fmt::Display) -> OutputError {
    OutputError::Plot {
        name: name.to_owned(),
        message: e.to_string(),
    }
}

/// Renders `plot` as an SVG document.
///
/// # Errors
/// As [`Plot::validate`]; [`OutputError::Plot`] if drawing fails.
pub fn render_svg<P: Plot + ?Sized>(plot: &P) -> Result<String, OutputError> {
    plot.validate()?;
    register_fonts();
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, plot.dimensions()).into_drawing_area();
        root.fill(&WHITE).map_err(|e| plot_error("svg", e))?;
        plot.draw(&root).map_err(|e| plot_error("svg", e))?;
        root.present().map_err(|e| plot_error("svg", e))?;
    }
    Ok(svg)
}

/// Renders `plot` as a PNG image (8-bit RGB).
///
/// # Errors
/// As [`Plot::validate`]; [`OutputError::Plot`] if drawing fails; [`OutputError::Png`].
pub fn render_png<P: Plot + ?Sized>(plot: &P) -> Result<Vec<u8>, OutputError> {
    plot.validate()?;
    register_fonts();
    let (w, h) = plot.dimensions();
    let mut rgb = vec![255u8; 3 * w as usize * h as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| plot_error("png", e))?;
        plot.draw(&root).map_err(|e| plot_error("png", e))?;
        root.present().map_err(|e| plot_error("png", e))?;
    }
    let mut bytes = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut bytes, w, h);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header()?;
        writer.write_image_data(&rgb)?;
        writer.finish()?;
    }
    Ok(bytes)
}

/// Writes `STEM.svg` and `STEM.png` (each atomically), rendering both before writing either;
/// returns their paths.
///
/// # Errors
/// As [`render_svg`] and [`render_png`] (nothing is written then); [`OutputError::Io`].
pub fn write_plot<P: Plot + ?Sized>(stem: &Path, plot: &P) -> Result<[PathBuf; 2], OutputError> {
    let name = stem
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    let named = |e: OutputError| match e {
        OutputError::Plot { message, .. } => OutputError::Plot {
            name: name.clone(),
            message,
        },
        other => other,
    };
    let svg = render_svg(plot).map_err(named)?;
    let png = render_png(plot).map_err(named)?;
    let svg_path = with_suffix(stem, "svg");
    let png_path = with_suffix(stem, "png");
    write_atomic(&svg_path, |w| {
        Ok(std::io::Write::write_all(w, svg.as_bytes())?)
    })?;
    write_atomic(&png_path, |w| Ok(std::io::Write::write_all(w, &png)?))?;
    Ok([svg_path, png_path])
}

/// `stem` with `.ext` appended (not replacing a dot already in the name, as in `ratio_b1.5`).
fn with_suffix(stem: &Path, ext: &str) -> PathBuf {
    let mut s = stem.as_os_str().to_owned();
    s.push(".");
    s.push(ext);
    PathBuf::from(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_labels_are_short() {
        assert_eq!(tick_label(&0.5), "0.5");
        assert_eq!(tick_label(&0.001), "1e-3");
        assert_eq!(tick_label(&2.0), "2");
        assert_eq!(tick_label(&1e-7), "1e-7");
        assert_eq!(tick_label(&2.5e6), "2.5e6");
        assert_eq!(tick_label(&0.30000000000000004), "0.3");
    }

    #[test]
    fn suffix_keeps_dots_in_the_stem() {
        assert_eq!(
            with_suffix(Path::new("d/ratio_b1.5"), "svg"),
            Path::new("d/ratio_b1.5.svg")
        );
    }
}
